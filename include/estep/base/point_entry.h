#ifndef estep_base_point_entry_h
#define estep_base_point_entry_h

#include <array>
#include <string>

namespace estep
{
  /**
   * The point "x, y, z" of an input entry. Throws std::runtime_error naming
   * @p entry (its path in the input) unless @p text is three finite
   * comma-separated numbers.
   */
  std::array<double, 3>
  parse_point(const std::string &text, const std::string &entry);
} // namespace estep

#endif
