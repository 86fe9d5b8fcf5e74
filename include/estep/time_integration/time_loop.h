#ifndef estep_time_integration_time_loop_h
#define estep_time_integration_time_loop_h

#include <estep/time_integration/time_integrator.h>

#include <functional>
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
    interrupted,
    /** Bodies passed into each other (MechanicalSystem::penetration()). */
    penetrated
  };

  /** The shortest span of time a run from @p start_time to @p end_time can
   * be stepped through in floating point: about a million units of
   * round-off of the run's largest time. */
  double
  time_resolution(const double start_time, const double end_time);

  /** Text of a status for output ("completed", "unstable", "stalled",
   * "failed", "interrupted", "penetrated"). */
  std::string
  to_string(const RunStatus status);

  /** Thrown by an observer whose output cannot be written; the run ends with
   * status failed. */
  class OutputFailed : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /** What the time loop itself carries from step to step (the rest of a
   * run's state is the integrator's and the observers'). */
  struct TimeLoopState
  {
    /** The kinetic energy above which the run is unstable (from the initial
     * state). */
    double blowup_bound = 0.;
    /** Steps in a row that left the time where it was. */
    std::uint64_t steps_in_place = 0;
    /** The initial |T0| + |V0| and conserved energy (TimeIntegrator::
     * conserved_energy()), and the largest drift of that energy over the
     * output times so far, relative to |T0| + |V0|, with its time. */
    double energy_scale              = 0.;
    double initial_energy            = 0.;
    double largest_energy_drift      = 0.;
    double largest_energy_drift_time = 0.;
    /** How many output times have been passed (the next one's index): a
     * resumed run takes over there (when it continues a completed run to a
     * later end time, see TimeGrid::resume_after() in time_loop.cc). */
    std::uint64_t outputs_passed = 0;

    void
    save(StateWriter &out) const;
    void
    load(StateReader &in);
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
    /**
     * The run ends with a warning (TimeLoopResult::warnings) when the energy
     * its integrator conserves (TimeIntegrator::conserved_energy()) differs
     * at an output time from its initial value by more than this fraction of
     * the initial energy scale |T0| + |V0|.
     */
    double energy_drift_warning = 0.1;

    /**
     * Checkpoints: write_checkpoint is called (if set) after the first step
     * that reaches each multiple of checkpoint_interval of simulated time
     * past start_time (0: none), after every checkpoint_wall_seconds of wall
     * time (0: none), and when the run completes or is interrupted. It
     * receives the loop's own state; the integrator and the observers are in
     * their post-step states. It may throw OutputFailed.
     */
    std::function<void(const TimeLoopState &)> write_checkpoint;
    double                                     checkpoint_interval     = 0.;
    double                                     checkpoint_wall_seconds = 0.;
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
    /** The largest |E(t) - E(t0)| over the output times, E the conserved
     * energy, relative to the initial |T0| + |V0| (0 if that is 0), and the
     * output time where it was reached. */
    double largest_energy_drift      = 0.;
    double largest_energy_drift_time = 0.;
    /** Warnings about the run as it went, one sentence each. */
    std::vector<std::string> warnings;
  };

  /**
   * The one time loop of estep: step the initialised @p integrator to the end
   * time, hand the exact state at each output time to the observers, and stop
   * with status "unstable" (and a message) if the state becomes non-finite or
   * explodes, with status "penetrated" if the system reports bodies passed
   * into each other (MechanicalSystem::penetration(), after every step). A run
   * that does not end unstable but whose conserved energy drifted at an output
   * time by more than TimeLoopSettings:: energy_drift_warning times the initial
   * |T0| + |V0| ends with a warning.
   */
  TimeLoopResult
  run_time_loop(TimeIntegrator                   &integrator,
                const TimeLoopSettings           &settings,
                const std::vector<RunObserver *> &observers);

  /**
   * Continue a run from a checkpoint: @p integrator and the observers have
   * loaded their states, @p state is the loop's. Output times and
   * checkpoints continue on the grid of the run from settings.start_time, the
   * start not being observed again; the result is that of the uninterrupted
   * run, bit for bit, when the integrator restores its state exactly.
   */
  TimeLoopResult
  resume_time_loop(TimeIntegrator                   &integrator,
                   const TimeLoopSettings           &settings,
                   const std::vector<RunObserver *> &observers,
                   const TimeLoopState              &state);
} // namespace estep

#endif
