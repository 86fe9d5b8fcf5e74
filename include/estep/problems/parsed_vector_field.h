#ifndef estep_problems_parsed_vector_field_h
#define estep_problems_parsed_vector_field_h

#include <estep/systems/mechanical_system.h>

#include <string>

namespace estep
{
  /**
   * A vector field given in an input file in deal.II's FunctionParser
   * conventions, evaluated at every point of @p points (point-major, three
   * coordinates per point): @p expression holds the @p n_components
   * components separated by ';', @p variables names the coordinates
   * ("x,y,z"), and @p constants is a list "name=value, ...". Returns the
   * values point-major, @p n_components per point.
   * Throws std::runtime_error naming @p entry (the input's entry) when the
   * constants or the expression cannot be read, or when a value is not
   * finite (naming the point and the component), in one line.
   */
  Vector
  evaluate_vector_field(const std::string &entry,
                        const std::string &expression,
                        const std::string &variables,
                        const std::string &constants,
                        const Vector      &points,
                        const unsigned int n_components = 3);
} // namespace estep

#endif
