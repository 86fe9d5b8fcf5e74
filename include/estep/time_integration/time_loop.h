#ifndef estep_time_integration_time_loop_h
#define estep_time_integration_time_loop_h

#include <estep/time_integration/time_integrator.h>

#include <string>
#include <vector>

namespace estep
{
  /**
   * Something that watches a run: it sees the state at the requested output
   * times and is told after every step.
   */
  class RunObserver
  {
  public:
    virtual ~RunObserver() = default;

    /** The state at a requested output time (exact dense output of the
     * integrator). */
    virtual void
    observe(const Snapshot &snapshot);

    /** Called after every step, with the integrator in its post-step state. */
    virtual void
    after_step(const TimeIntegrator &integrator);
  };

  /** How a run ended. */
  enum class RunStatus
  {
    completed,
    unstable,
    /** The integrator could not advance (e.g. a search crawling at round-off).
     */
    stalled,
    /** An output could not be written (e.g. a full disk). */
    failed,
    /** Stopped on request (a signal such as SIGINT or SIGTERM). */
    interrupted
  };

  /** Text of a status for output ("completed", "unstable", "stalled",
   * "failed", "interrupted"). */
  std::string
  to_string(const RunStatus status);

  /** Thrown by an observer whose output cannot be written; the run ends with
   * status failed. */
  class OutputFailed : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /** Settings of the time loop. */
  struct TimeLoopSettings
  {
    double start_time = 0.;
    double end_time   = 1.;
    /** Output every this much simulated time, from start_time on, plus the end
     * time. */
    double output_interval = 0.1;
    /**
     * The run is declared unstable when the kinetic energy exceeds this factor
     * times the initial energy scale |T0| + |V0| (checked after every step).
     */
    double blowup_factor = 1e3;
  };

  /** What the time loop reports at its end. */
  struct TimeLoopResult
  {
    RunStatus   status = RunStatus::completed;
    std::string message;
    /** The signal that interrupted the run, if one did. */
    int    signal       = 0;
    double final_time   = 0.;
    double wall_seconds = 0.;
  };

  /**
   * Ask a running time loop to stop after its current step, reporting @p
   * signal. Async-signal-safe: meant for a signal handler.
   */
  void
  request_interruption(const int signal) noexcept;

  /**
   * The one time loop of estep: step the initialised @p integrator to the end
   * time, hand the exact state at each output time to the observers, and stop
   * with status "unstable" (and a message) if the state becomes non-finite or
   * explodes.
   */
  TimeLoopResult
  run_time_loop(TimeIntegrator                   &integrator,
                const TimeLoopSettings           &settings,
                const std::vector<RunObserver *> &observers);
} // namespace estep

#endif
