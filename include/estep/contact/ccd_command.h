#ifndef estep_contact_ccd_command_h
#define estep_contact_ccd_command_h

#include <ostream>
#include <string>
#include <vector>

namespace estep
{
  namespace contact
  {
    /**
     * The command `estep ccd FILE_OR_DIR...`: run the conservative continuous
     * collision detection (default CcdSettings) on every query of the given CSV
     * files (directories are searched recursively for *.csv files, in sorted
     * order) and print to @p out the number of files and queries, the positives
     * of the ground truth, false negatives, false positives, how many queries
     * reached the iteration cap and the mean time per query (microseconds, CCD
     * calls only), each for all queries and for the non-degenerate ones
     * (ccd_query_is_non_degenerate(); each class is timed as one batch per
     * file).
     *
     * Returns 0 if there was no false negative, 1 otherwise. Throws
     * std::runtime_error with the file (and line) for a missing path, an empty
     * list or a malformed file.
     */
    int
    run_ccd_command(const std::vector<std::string> &csv_files,
                    std::ostream                   &out);
  } // namespace contact
} // namespace estep

#endif
