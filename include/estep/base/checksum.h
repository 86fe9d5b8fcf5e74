#ifndef estep_base_checksum_h
#define estep_base_checksum_h

#include <cstddef>
#include <cstdint>

namespace estep
{
  /** The checksum of no bytes (FNV-1a's offset basis). */
  constexpr std::uint64_t empty_checksum = 14695981039346656037ull;

  /**
   * The 64-bit FNV-1a checksum of the @p n bytes at @p bytes, continuing
   * from @p checksum, the checksum of the bytes before them: enough to notice
   * a damaged file or a changed input, not a cryptographic hash.
   */
  std::uint64_t
  checksum(const void         *bytes,
           const std::size_t   n,
           const std::uint64_t checksum = empty_checksum);
} // namespace estep

#endif
