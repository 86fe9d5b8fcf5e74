#ifndef estep_implicit_implicit_integrator_h
#define estep_implicit_implicit_integrator_h

#include <estep/implicit/implicit_parameters.h>
#include <estep/time_integration/time_integrator.h>

#include <string>

namespace estep
{
  /**
   * Thrown by the implicit integrators when a nonlinear solve fails (Newton
   * does not converge, the step size collapses below the minimum step, or a
   * SUNDIALS call fails). It is an UnstableRun, so run_time_loop() ends the
   * run with status "unstable" and this message; catch this type to tell a
   * solver failure from a blow-up.
   */
  class ImplicitSolverFailure : public UnstableRun
  {
  public:
    /** The failure with the message @p message. */
    explicit ImplicitSolverFailure(std::string message)
      : UnstableRun(std::move(message))
    {}
  };

  /**
   * The common part of the implicit integrators of the area "implicit": the
   * state at both ends of the last step, dense output by cubic Hermite
   * interpolation of positions and velocities between them (third order, as
   * ExplicitNewmark does), and the parameters.
   */
  class ImplicitIntegrator : public TimeIntegrator
  {
  public:
    /** For @p system with the settings @p parameters (checked). */
    ImplicitIntegrator(const MechanicalSystem   &system,
                       const ImplicitParameters &parameters);

    /** Cubic Hermite interpolation between the ends of the last step. */
    Snapshot
    dense_output(const double t) const override;

    Snapshot
    dense_state(const double t) const override;

    /** The settings. */
    const ImplicitParameters &
    parameters() const;

    /** Also the state at the start of the last step and the work counters.
     */
    void
    save_state(StateWriter &out) const override;

    /**
     * Restores the state and restarts the solver there, as initialize() does
     * (SUNDIALS keeps no state that could be restored: the step-size and
     * order history of ARKode and IDA start afresh, so their continuation is
     * not bit-identical; the energy-momentum step depends on the state alone
     * and continues exactly). The work counters continue from their stored
     * values.
     */
    void
    load_state(StateReader &in) override;

  protected:
    /** @p counts plus what the counters had reached at the checkpoint a run
     * was resumed from (the steps excepted: they are restored). */
    std::vector<Counter>
    with_resumed_counts(std::vector<Counter> counts) const;

    /** Store the current state as the start of the next step. */
    void
    begin_step();

    /** Throw UnstableRun if the current state is not finite. */
    void
    check_finite() const;

    ImplicitParameters settings;
    Vector             q_old, v_old;

  private:
    /** The counters at the checkpoint a run was resumed from, minus their
     * values after the solver's restart. */
    std::vector<Counter> resumed_counts;
  };
} // namespace estep

#endif
