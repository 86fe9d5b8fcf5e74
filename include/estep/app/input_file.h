#ifndef estep_app_input_file_h
#define estep_app_input_file_h

#include <string>

namespace dealii
{
  class ParameterHandler;
}

namespace estep
{
  /**
   * Read the input file @p filename (.prm, .json or .xml) into @p prm, after
   * the checks that deal.II's readers cannot survive or report clearly: a
   * .prm or .json file may begin with a UTF-8 byte-order mark (it is
   * dropped); the `include` lines of a .prm file (resolved as deal.II
   * resolves them, from the working directory) may neither form a cycle nor
   * nest deeper than 32 files; a JSON file may not nest deeper than 64
   * levels; the text of a .prm file (outside comments) and of a .xml file
   * must be UTF-8, as the parameters.json it leads to must be; an entry of an
   * earlier version of the input that has moved is named with its new place;
   * an entry may be set only once in a file (a file may set again what the
   * files it includes set), and a .prm or .json file must set at least one
   * entry.
   * A JSON file is read here rather than by deal.II, so that an undeclared
   * entry or subsection, or a value that does not match its pattern, is named
   * by its full path. Each violation is a std::runtime_error naming the file,
   * and the line or the entry. @p skip_undeclared: ignore entries and
   * subsections @p prm does not declare (a first reading for a few entries).
   */
  void
  read_input_file(dealii::ParameterHandler &prm,
                  const std::string        &filename,
                  const bool                skip_undeclared = false);
} // namespace estep

#endif
