#ifndef estep_app_renamed_entries_h
#define estep_app_renamed_entries_h

#include <string>

namespace estep
{
  /**
   * Where an entry of an earlier version of estep's input went: for @p path
   * ("Section/Subsection/Entry") of an entry that was renamed or moved, the
   * sentence "<path> is now <new path>." (with what else to change, if
   * anything); "" for any other path.
   */
  std::string
  renamed_entry_message(const std::string &path);
} // namespace estep

#endif
