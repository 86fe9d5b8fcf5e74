#ifndef estep_io_progress_log_h
#define estep_io_progress_log_h

#include <estep/io/postprocessor.h>
#include <estep/io/progress_line.h>

#include <chrono>
#include <fstream>
#include <memory>
#include <string>

namespace estep
{
  /**
   * The progress of a run: every @p interval seconds of wall time a line
   * with the simulated time, the percentage, the steps, steps per second and
   * the estimated time left, appended to a log file, and a last line when the
   * run ends. On a terminal a ProgressLine shows the same, rewritten in place;
   * without one (a batch job) the log's lines also go to standard output. A
   * line that cannot be written to the log throws OutputFailed.
   */
  class ProgressLog : public Postprocessor
  {
  public:
    /** The log of @p integrator's run from @p start_time to @p end_time in
     * @p filename; @p terminal: show a ProgressLine instead of printing the
     * log's lines. */
    ProgressLog(const std::string    &filename,
                const TimeIntegrator &integrator,
                const double          start_time,
                const double          end_time,
                const double          interval,
                const bool            terminal);

    /** Opens the log file. */
    void
    start() override;

    /** Appends to the log file, with a line saying where the run resumed. */
    void
    resume(StateReader &in) override;

    void
    after_step(const TimeIntegrator &integrator) override;

    /** Clears the terminal line; the last line of the log, with how the run
     * ended (unless it failed: the disk may be full). */
    void
    finish(const TimeLoopResult &result) override;

  private:
    void
    write(const TimeIntegrator &integrator, const std::string &suffix);

    const std::string                     filename;
    const TimeIntegrator                 &integrator;
    const double                          start_time, end_time;
    const std::chrono::duration<double>   interval;
    const bool                            to_standard_output;
    std::unique_ptr<ProgressLine>         line;
    std::ofstream                         out;
    std::chrono::steady_clock::time_point wall_start, last_line;
    /** Where this process took the run over (the start, or a checkpoint). */
    double        first_time;
    std::uint64_t first_step = 0;
  };
} // namespace estep

#endif
