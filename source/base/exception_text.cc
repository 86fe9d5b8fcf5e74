#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <estep/base/exception_text.h>

#include <new>
#include <sstream>

namespace estep
{
  std::string
  one_line_message(const std::exception &exception)
  {
    std::string text = exception.what();
    if (dynamic_cast<const std::bad_alloc *>(&exception) != nullptr)
      text = "out of memory (" + text +
             "): the problem is too large for this machine";
    else if (const auto *deal_ii =
               dynamic_cast<const dealii::ExceptionBase *>(&exception))
      {
        std::ostringstream info;
        deal_ii->print_info(info);
        text = info.str();
        if (dealii::Utilities::trim(text).empty())
          text = deal_ii->get_exc_name();
      }
    // Collapse hard line breaks and indentation into single spaces.
    std::string collapsed;
    bool        space = false;
    for (const char c : text)
      if (c == '\n' || c == ' ' || c == '\t')
        space = true;
      else
        {
          if (space && !collapsed.empty())
            collapsed += ' ';
          collapsed += c;
          space = false;
        }
    return collapsed;
  }



  std::string
  message_number(const double x, const int digits)
  {
    std::ostringstream text;
    text.precision(digits);
    text << x;
    return text.str();
  }
} // namespace estep
