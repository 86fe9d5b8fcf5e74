#ifndef estep_time_integration_time_integrator_h
#define estep_time_integration_time_integrator_h

#include <estep/base/binary_state.h>
#include <estep/base/json_writer.h>
#include <estep/systems/mechanical_system.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace estep
{
  /**
   * The state of a run at one instant, as observers see it.
   */
  struct Snapshot
  {
    double t;
    Vector q;
    Vector v;
    double kinetic_energy;
    double potential_energy;
    /** The potential the integrator conserves energy with: L h for
     * energy-stepping, V for the others (see
     * TimeIntegrator::conserved_energy()). */
    double terraced_potential_energy;
  };

  /** A named work counter of an integrator (steps, reflections, evaluations,
   * ...). */
  using Counter = std::pair<std::string, std::uint64_t>;

  /**
   * A time integrator of a MechanicalSystem. The driver (run_time_loop()) calls
   * step() until the end time and asks for dense output at the requested output
   * times in between.
   */
  class TimeIntegrator
  {
  public:
    explicit TimeIntegrator(const MechanicalSystem &system);
    virtual ~TimeIntegrator() = default;

    /** A short name for output ("energy stepping", ...). */
    virtual std::string
    name() const = 0;

    /** Set the initial state. */
    virtual void
    initialize(const double t0, const Vector &q0, const Vector &v0) = 0;

    /**
     * Advance by one step, never past @p t_limit. Throws UnstableRun when the
     * state becomes non-finite.
     */
    virtual void
    step(const double t_limit) = 0;

    /** The state at time t in [previous_time(), time()], exactly as the scheme
     * defines it between its steps. */
    virtual Snapshot
    dense_output(const double t) const = 0;

    /**
     * The positions and velocities of dense_output() at time t, without the
     * energies (NaN): what an observer that needs only the state asks for.
     * The default calls dense_output(), which evaluates V (on several MPI
     * ranks a sum they compute together, so the postprocessors that call
     * dense_state() run on every rank); an override that skips V is
     * cheaper.
     */
    virtual Snapshot
    dense_state(const double t) const;

    /**
     * Make position() and velocity() hold every coordinate: an integrator
     * that keeps only some current between its steps on several MPI ranks
     * (MechanicalSystem::kept_coordinates()) fills in the others from the
     * ranks that keep them. Collective; the time loop calls it before a
     * checkpoint and at the end of the run. The default: nothing.
     */
    virtual void
    complete_state();

    /** The kinetic energy at time(), the same on every MPI rank: summed
     * over the fixed blocks of coordinates, each rank its own where the
     * system shares its state (sum_over_coordinate_blocks()), so from the
     * kept coordinates alone where the integrator keeps only some. */
    virtual double
    current_kinetic_energy() const;

    /** Work counters, in a fixed order. */
    virtual std::vector<Counter>
    counters() const = 0;

    /**
     * Add the integrator's own figures to the summary's `energies` object
     * (energy-stepping: its energy step and terraced energies). The default
     * adds nothing.
     */
    virtual void
    add_energies_to_summary(JsonObject &energies) const;

    /**
     * Warnings about the run as initialised (e.g. an energy step coarser than
     * the system's energy scale), one sentence each, for the application to
     * print. The default: the unread settings, as recorded.
     */
    virtual std::vector<std::string>
    warnings() const;

    /** Record the settings of the input that this integrator does not read
     * (entries_unread_by_type()), one sentence each, for warnings(). */
    void
    record_unread_settings(std::vector<std::string> sentences);

    /**
     * @name Checkpoints
     * @{
     */
    /**
     * Store everything the next steps depend on, so that load_state() on an
     * integrator built from the same parameters continues the run exactly.
     * The default stores the time, the previous time, q, v and the step
     * statistics; an integrator with more state (a terrace index, a last
     * flight, work counters) extends it, calling this first.
     */
    virtual void
    save_state(StateWriter &out) const;

    /** Restore what save_state() stored (the counterpart of initialize() for
     * a resumed run). */
    virtual void
    load_state(StateReader &in);
    /** @} */

    /**
     * Whether step() stops at the system's constraint events
     * (MechanicalSystem::first_constraint_event(), impenetrable contact) and
     * reflects there. An integrator that does not (the default) is refused
     * for a system with constraints by create_integrator(), since it would
     * step through them.
     */
    virtual bool
    follows_constraint_events() const;

    /** The energy the integrator conserves, as a formula for messages: "T +
     * V" by default, the time loop checks its drift. */
    virtual std::string
    conserved_energy() const;

    double
    time() const
    {
      return t;
    }

    double
    previous_time() const
    {
      return t_previous;
    }

    /** The positions at time(); on several MPI ranks whose system shares
     * its state, whole only after complete_state(). */
    const Vector &
    position() const
    {
      return q;
    }

    /** The velocities at time(), as position(). */
    const Vector &
    velocity() const
    {
      return v;
    }

    /** Number of steps taken. */
    std::uint64_t
    n_steps() const
    {
      return steps;
    }

    /** Smallest step taken so far (0 before the first step). */
    double
    min_step() const
    {
      return smallest_step;
    }

    /** Largest step taken so far (0 before the first step). */
    double
    max_step() const
    {
      return largest_step;
    }

    /** The system integrated. */
    const MechanicalSystem &
    mechanical_system() const
    {
      return system;
    }

  protected:
    /** Record the end of one step of length t - t_previous. */
    void
    count_step();

    /**
     * Dense output of a step-based scheme: the cubic Hermite interpolant of
     * (q_old, v_old) at t_previous and (q, v) at t (third order), with the
     * energies at time @p time if @p with_energies. It takes the kept
     * coordinates (MechanicalSystem::kept_coordinates()) and completes the
     * snapshot: collective.
     */
    Snapshot
    hermite_dense_output(const double  time,
                         const Vector &q_old,
                         const Vector &v_old,
                         const bool    with_energies = true) const;

    const MechanicalSystem &system;
    double                  t          = 0.;
    double                  t_previous = 0.;
    Vector                  q, v;
    std::uint64_t           steps         = 0;
    double                  smallest_step = 0.;
    double                  largest_step  = 0.;

  private:
    std::vector<std::string> unread_settings;
  };

  /**
   * |b - a| relative to |a|, or absolute where a is zero on the scale @p scale
   * (|a| <= 1e-14 scale): the drift of a conserved quantity from @p a to @p b.
   */
  double
  relative_drift(const double a, const double b, const double scale);

  /** Thrown when a run becomes unstable (non-finite or exploding state). */
  class UnstableRun : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /** Thrown when an integrator cannot advance (its event search gave up at
   * round-off); the run ends with status stalled. */
  class StalledRun : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };
} // namespace estep

#endif
