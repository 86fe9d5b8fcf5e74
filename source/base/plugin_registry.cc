#include <estep/base/plugin_registry.h>

namespace estep
{
  std::vector<std::string> &
  plugin_registration_errors()
  {
    static std::vector<std::string> errors;
    return errors;
  }

  std::size_t &
  plugin_registration_count()
  {
    static std::size_t count = 0;
    return count;
  }
} // namespace estep
