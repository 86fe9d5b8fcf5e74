#include <estep/base/plugin_registry.h>

namespace estep
{
  std::vector<std::string> &
  plugin_registration_errors()
  {
    static std::vector<std::string> errors;
    return errors;
  }
} // namespace estep
