#ifndef estep_base_exception_text_h
#define estep_base_exception_text_h

#include <exception>
#include <string>

namespace estep
{
  /**
   * What an exception says, in one line: for a deal.II exception its
   * additional information without the source location and the violated
   * condition (the part written for its user, not its developer), for
   * std::bad_alloc that memory ran out, for any other its what().
   */
  std::string
  one_line_message(const std::exception &exception);

  /** @p x as an error message gives a number: @p digits significant
   * digits. */
  std::string
  message_number(const double x, const int digits = 6);
} // namespace estep

#endif
