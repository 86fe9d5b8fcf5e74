#ifndef estep_app_ccd_command_h
#define estep_app_ccd_command_h

#include <ostream>
#include <string>
#include <vector>

namespace estep
{
  /**
   * The command `estep ccd FILE_OR_DIR...`: run the conservative continuous
   * collision detection (contact::vertex_face_ccd(), contact::edge_edge_ccd()
   * with default contact::CcdSettings) on every query of the given CSV files
   * (contact::read_ccd_query_file(); directories are searched recursively for
   * *.csv files, in sorted order) and print to @p out the number of files and
   * queries, the positives of the ground truth, false negatives, false
   * positives, how many queries reached the iteration cap and the mean time per
   * query (microseconds, CCD calls only), each for all queries and for the
   * non-degenerate ones (contact::ccd_query_is_non_degenerate(); each class is
   * timed as one batch per file).
   *
   * Returns 0 if there was no false negative, 1 otherwise. Throws
   * std::runtime_error with the file (and line) for a missing path, an empty
   * list or a malformed file.
   */
  int
  run_ccd_command(const std::vector<std::string> &csv_files, std::ostream &out);
} // namespace estep

#endif
