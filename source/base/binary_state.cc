#include <estep/base/binary_state.h>

namespace estep
{
  void
  StateWriter::put(const std::string &text)
  {
    put(static_cast<std::uint64_t>(text.size()));
    bytes += text;
  }



  StateReader::StateReader(const std::string &bytes)
    : bytes(bytes)
  {}



  std::string
  StateReader::get_string()
  {
    const auto n = get<std::uint64_t>();
    return std::string(take(n), n);
  }



  const char *
  StateReader::take(const std::size_t n)
  {
    if (n > bytes.size() - position)
      throw std::runtime_error("the checkpoint ends early: it is damaged or "
                               "was written by another build of estep.");
    const char *start = bytes.data() + position;
    position += n;
    return start;
  }
} // namespace estep
