// Fuzz driver of the input-file reader with estep's own declarations: an input
// is read as `estep INPUT` reads its input file before it builds the problem
// (every parameter of the registered plugins declared, the file read leniently,
// declared again, read strictly; the run's own entries checked), then printed
// as a run prints parameters.prm and parameters.json, and both must read back
// to the same parameters. The file is a .json file when the input starts with
// '{', a .xml file when it starts with '<', a .prm file otherwise (the estep
// command goes by the extension). The plugin libraries of `Additional shared
// libraries` are not loaded.
#include <deal.II/base/parameter_handler.h>

#include <estep/app/application.h>
#include <estep/app/run_parameters.h>

#include "fuzz_support.h"

#include <cstdlib>
#include <iostream>
#include <sstream>

namespace
{
  std::string
  input_file(const std::uint8_t *data, const std::size_t size)
  {
    std::size_t first = 0;
    while (first < size && (data[first] == ' ' || data[first] == '\t' ||
                            data[first] == '\r' || data[first] == '\n'))
      ++first;
    static const std::string prm  = estep_fuzz::scratch_file("input.prm"),
                             json = estep_fuzz::scratch_file("input.json"),
                             xml  = estep_fuzz::scratch_file("input.xml");
    if (first < size && data[first] == '{')
      return json;
    if (first < size && data[first] == '<')
      return xml;
    return prm;
  }

  /** The parameters read from @p file, printed as parameters.prm. */
  std::string
  read_and_print(const std::string &file, std::string *json = nullptr)
  {
    dealii::ParameterHandler prm;
    estep::declare_and_read_parameters(prm, file);
    estep::RunParameters run;
    run.parse_parameters(prm);
    std::ostringstream text;
    prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
    if (json != nullptr)
      {
        std::ostringstream json_text;
        prm.print_parameters(json_text, dealii::ParameterHandler::ShortJSON);
        *json = json_text.str();
      }
    return text.str();
  }
} // namespace



extern "C" int
LLVMFuzzerInitialize(int *, char ***)
{
  estep_fuzz::initialize();
  return 0;
}



extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, const std::size_t size)
{
  const std::string file = input_file(data, size);
  estep_fuzz::write_file(file, data, size);
  std::string printed, json;
  try
    {
      printed = read_and_print(file, &json);
    }
  catch (const std::exception &error)
    {
      estep_fuzz::check_rejection(error);
      return 0;
    }

  // parameters.prm and parameters.json of a run are valid input files with
  // the same parameters.
  static const std::string prm_again  = estep_fuzz::scratch_file("again.prm"),
                           json_again = estep_fuzz::scratch_file("again.json");
  for (const auto &[again, text] :
       {std::pair{&prm_again, &printed}, std::pair{&json_again, &json}})
    {
      estep_fuzz::write_file(*again,
                             reinterpret_cast<const std::uint8_t *>(
                               text->data()),
                             text->size());
      std::string reprinted;
      try
        {
          reprinted = read_and_print(*again);
        }
      catch (const std::exception &error)
        {
          std::cerr << "fuzz driver: the printed parameters (" << *again
                    << ") cannot be read back: " << error.what()
                    << "\n--- printed:\n"
                    << *text;
          std::abort();
        }
      if (reprinted != printed)
        {
          std::cerr << "fuzz driver: the printed parameters (" << *again
                    << ") read back to other values\n--- printed:\n"
                    << printed << "--- read back and printed:\n"
                    << reprinted;
          std::abort();
        }
    }
  return 0;
}
