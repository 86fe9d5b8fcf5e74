#ifndef estep_io_progress_log_h
#define estep_io_progress_log_h

#include <estep/time_integration/time_loop.h>

#include <chrono>
#include <fstream>
#include <string>

namespace estep
{
  /**
   * Progress for runs without a terminal (batch jobs): every @p interval
   * seconds of wall time a line with the simulated time, the percentage, the
   * steps, steps per second and the estimated time left, on standard output
   * (if asked) and appended to a log file; a last line when the run ends.
   * A line that cannot be written to the log throws OutputFailed.
   */
  class ProgressLog : public RunObserver
  {
  public:
    ProgressLog(const std::string &filename,
                const double       start_time,
                const double       end_time,
                const double       interval,
                const bool         to_standard_output);

    void
    after_step(const TimeIntegrator &integrator) override;

    /** The last line, with how the run ended. */
    void
    finish(const TimeIntegrator &integrator, const std::string &status);

  private:
    void
    write(const TimeIntegrator &integrator, const std::string &suffix);

    const std::string                     filename;
    const double                          start_time, end_time;
    const std::chrono::duration<double>   interval;
    const bool                            to_standard_output;
    std::ofstream                         out;
    std::chrono::steady_clock::time_point wall_start, last_line;
  };
} // namespace estep

#endif
