#ifndef estep_io_progress_line_h
#define estep_io_progress_line_h

#include <estep/time_integration/time_loop.h>

#include <chrono>

namespace estep
{
  /**
   * A progress line on the terminal for long runs: simulated time, percentage,
   * steps per second and estimated time left, rewritten in place at most four
   * times a second on standard error.
   */
  class ProgressLine : public RunObserver
  {
  public:
    ProgressLine(const double start_time, const double end_time);

    /** Clears the line. */
    ~ProgressLine() override;

    void
    after_step(const TimeIntegrator &integrator) override;

    /** Rates and the time left from now on, the run being at time @p t after
     * @p steps steps (a resumed run). */
    void
    watch_from(const double t, const std::uint64_t steps);

    /** Whether standard error is a terminal (the default for showing the line).
     */
    static bool
    stderr_is_terminal();

  private:
    const double                          start_time, end_time;
    double                                first_time;
    std::uint64_t                         first_step = 0;
    std::chrono::steady_clock::time_point wall_start, last_print;
    bool                                  printed = false;
  };
} // namespace estep

#endif
