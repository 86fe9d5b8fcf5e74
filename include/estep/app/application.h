#ifndef estep_app_application_h
#define estep_app_application_h

#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace estep
{
  /** Exit codes of the estep command. */
  enum ExitCode
  {
    /** The run completed. */
    exit_success = 0,
    /** Bad input: command line, parameter file, mesh, ... A message says what.
     */
    exit_input_error = 1,
    /** The run ended unstable (blow-up); summary.json says so. */
    exit_unstable = 2,
    /** The run stalled (could not advance in time); summary.json says so. */
    exit_stalled = 3,
    /** An output could not be written (e.g. a full disk), or the run failed
     * otherwise once started (e.g. a plugin threw); summary.json says so
     * where it still can be written. */
    exit_failed = 4,
    /** Bodies passed into each other (e.g. through a penalty too soft to
     * keep them apart); summary.json says so. */
    exit_penetrated = 5
    // A run ended by SIGINT or SIGTERM exits with 128 + the signal's number.
  };

  /**
   * The estep command: parses the command line, reads and checks the
   * parameters, builds the problem and the integrator, runs the time loop with
   * its observers and writes the summary. Every error reaches the user as one
   * message on standard error and an exit code (see ExitCode), never as an
   * abort.
   */
  int
  run_application(int argc, char **argv);

  /**
   * Declare every parameter of the registered plugins in @p prm, then read
   * the input file @p input_file (.prm, .json or .xml, see read_input_file();
   * none if empty) and the overrides @p overrides ("Section/Entry=value"), as
   * the estep command does once it has loaded the libraries of `Additional
   * shared libraries` (this function loads none). Declarations may depend on
   * values (e.g. `Number of bodies` sizes a scene's body subsections): the
   * parameters are declared once with their defaults, the input is read
   * leniently, they are declared again with what it set, and the input is
   * read again, strictly. Then every value is checked against its pattern
   * once more (deal.II's readers do not check a value that holds a '{'), and
   * a value that a .prm file cannot hold (with '#', a line break or a control
   * character, white space at its ends, a final backslash: possible from a
   * .json or .xml file or an override) is rejected, since parameters.prm of a
   * run must read back to the same parameters. Bad input throws
   * (std::runtime_error or a deal.II exception) with one message.
   */
  void
  declare_and_read_parameters(dealii::ParameterHandler       &prm,
                              const std::string              &input_file,
                              const std::vector<std::string> &overrides = {});
} // namespace estep

#endif
