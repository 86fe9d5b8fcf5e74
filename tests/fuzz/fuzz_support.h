// What the fuzz drivers of tests/fuzz/ share. estep's readers take file names:
// each input is written to a file of a scratch directory of the process, then
// read as estep reads its input. A reader may reject an input with an exception
// carrying a message (check_rejection()); a crash, an abort, a hang, an
// uncaught exception, an exception without a message or a sanitizer report is a
// failure, which libFuzzer reports with the input that caused it.
#ifndef estep_tests_fuzz_fuzz_support_h
#define estep_tests_fuzz_fuzz_support_h

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

namespace estep_fuzz
{
  /**
   * The path of @p name (which may contain directories, e.g.
   * "vertex-face/query.csv") in this process's scratch directory; the
   * directories are created. The scratch directory is removed at exit.
   */
  std::string
  scratch_file(const std::string &name);

  /** Write the bytes [data, data + size) to the file @p name. */
  void
  write_file(const std::string  &name,
             const std::uint8_t *data,
             const std::size_t   size);

  /**
   * Settings every driver needs once: deal.II's exceptions are thrown (as in
   * the estep command), without stack traces.
   */
  void
  initialize();

  /**
   * An input was rejected with @p error: acceptable when it says why. An
   * exception without a message aborts (a failure).
   */
  void
  check_rejection(const std::exception &error);
} // namespace estep_fuzz

#endif
