#include <deal.II/base/utilities.h>

#include <estep/base/point_entry.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace estep
{
  std::array<double, 3>
  parse_point(const std::string &text, const std::string &entry)
  {
    const std::vector<std::string> parts =
      dealii::Utilities::split_string_list(text, ',');
    std::array<double, 3> point;
    try
      {
        if (parts.size() != 3)
          throw std::invalid_argument("");
        for (unsigned int d = 0; d < 3; ++d)
          {
            point[d] = dealii::Utilities::string_to_double(parts[d]);
            if (!std::isfinite(point[d]))
              throw std::invalid_argument("");
          }
      }
    catch (...)
      {
        throw std::runtime_error(
          entry + ": <" + text +
          "> is not three finite comma-separated numbers.");
      }
    return point;
  }
} // namespace estep
