#include <estep/base/checksum.h>

namespace estep
{
  std::uint64_t
  checksum(const void *bytes, const std::size_t n, const std::uint64_t checksum)
  {
    std::uint64_t hash = checksum;
    for (std::size_t i = 0; i < n; ++i)
      {
        hash ^= static_cast<const unsigned char *>(bytes)[i];
        hash *= 1099511628211ull;
      }
    return hash;
  }
} // namespace estep
