#ifndef estep_time_integration_explicit_newmark_h
#define estep_time_integration_explicit_newmark_h

#include <estep/time_integration/time_integrator.h>

namespace estep
{
  /**
   * Explicit Newmark, beta = 0 and gamma = 1/2 (velocity Verlet):
   *   a_n = -M^-1 grad V(q_n),
   *   q_{n+1} = q_n + dt v_n + dt^2 / 2 a_n,
   *   v_{n+1} = v_n + dt / 2 (a_n + a_{n+1}).
   * Second order, symplectic, momentum conserving; stable for dt < 2 /
   * omega_max. A step that would pass the limit time is shortened to end on it.
   * Dense output is the cubic Hermite interpolant of positions and velocities
   * at the ends of the step (third order, so it does not spoil the second-order
   * accuracy of the scheme).
   */
  class ExplicitNewmark : public TimeIntegrator
  {
  public:
    /** @param time_step The step dt > 0 (time units of the system). */
    ExplicitNewmark(const MechanicalSystem &system, const double time_step);

    std::string
    name() const override;

    void
    initialize(const double t0, const Vector &q0, const Vector &v0) override;

    /** One step; throws UnstableRun if the new state is not finite. */
    void
    step(const double t_limit) override;

    /** The position, velocity, acceleration and previous state, each of
     * which a rank keeps only in part where the system shares its state
     * among MPI ranks (MechanicalSystem::kept_coordinates()). Collective. */
    void
    complete_state() override;

    Snapshot
    dense_output(const double t) const override;

    Snapshot
    dense_state(const double t) const override;

    std::vector<Counter>
    counters() const override;

    /** Also the acceleration, the previous state and the counter. */
    void
    save_state(StateWriter &out) const override;

    void
    load_state(StateReader &in) override;

  private:
    /** a = -M^-1 grad V(x). */
    void
    compute_acceleration(const Vector &x, Vector &acceleration);

    const double  dt;
    Vector        acceleration, q_old, v_old, gradient_buffer;
    std::uint64_t n_gradients = 0;
  };
} // namespace estep

#endif
