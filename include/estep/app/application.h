#ifndef estep_app_application_h
#define estep_app_application_h

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
    /** An output could not be written (e.g. a full disk); summary.json says
     * so where it still can be written. */
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
} // namespace estep

#endif
