#include <deal.II/base/function_parser.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>

#include <estep/base/exception_text.h>
#include <estep/problems/parsed_vector_field.h>

#include <cmath>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace estep
{
  Vector
  evaluate_vector_field(const std::string &entry,
                        const std::string &expression,
                        const std::string &variables,
                        const std::string &constants,
                        const Vector      &points,
                        const unsigned int n_components)
  {
    std::map<std::string, double> values;
    for (const std::string &item :
         dealii::Utilities::split_string_list(constants, ','))
      {
        const auto parts = dealii::Utilities::split_string_list(item, '=');
        if (parts.size() != 2)
          throw std::runtime_error(entry + ": the constant <" + item +
                                   "> is not of the form name=value.");
        try
          {
            values[parts[0]] = dealii::Utilities::string_to_double(parts[1]);
          }
        catch (...)
          {
            throw std::runtime_error(entry + ": the constant <" + item +
                                     "> has no numeric value.");
          }
      }
    // deal.II parses on the first evaluation and prints its diagnosis of a
    // bad expression (several lines) before it throws: keep the diagnosis
    // and say it in one line naming the entry.
    std::ostringstream    diagnosis;
    std::streambuf *const cerr_buffer = std::cerr.rdbuf(diagnosis.rdbuf());
    const unsigned int    n           = n_components;
    Vector                field(points.size() / 3 * n);
    try
      {
        dealii::FunctionParser<3> function(n);
        function.initialize(variables,
                            dealii::Utilities::split_string_list(expression,
                                                                 ';'),
                            values);
        for (unsigned int i = 0; 3 * i < points.size(); ++i)
          {
            const dealii::Point<3> X(points[3 * i],
                                     points[3 * i + 1],
                                     points[3 * i + 2]);
            for (unsigned int c = 0; c < n; ++c)
              field[n * i + c] = function.value(X, c);
          }
        std::cerr.rdbuf(cerr_buffer);
      }
    catch (const dealii::ExceptionBase &exception)
      {
        std::cerr.rdbuf(cerr_buffer);
        std::string        message;
        std::istringstream lines(diagnosis.str());
        for (std::string line; std::getline(lines, line);)
          if (line.rfind("Message:", 0) == 0)
            message = dealii::Utilities::trim(line.substr(8));
        // Without a diagnosis (e.g. a wrong number of components), the
        // exception's own text.
        if (message.empty())
          message = one_line_message(exception);
        while (!message.empty() && message.back() == '.')
          message.pop_back();
        throw std::runtime_error(
          entry + ": <" + expression + "> cannot be evaluated" +
          (message.empty() ? std::string(".") : ": " + message + "."));
      }
    for (unsigned int i = 0; i < field.size(); ++i)
      if (!std::isfinite(field[i]))
        {
          std::ostringstream point;
          point << points[3 * (i / n)] << ", " << points[3 * (i / n) + 1]
                << ", " << points[3 * (i / n) + 2];
          throw std::runtime_error(
            entry + ": <" + expression + "> is " + std::to_string(field[i]) +
            " at the point (" + point.str() + ") (component " +
            std::to_string(i % n) + ").");
        }
    return field;
  }
} // namespace estep
