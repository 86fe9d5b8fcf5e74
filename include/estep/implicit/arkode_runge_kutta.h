#ifndef estep_implicit_arkode_runge_kutta_h
#define estep_implicit_arkode_runge_kutta_h

#include <estep/implicit/implicit_integrator.h>

#include <memory>

namespace estep
{
  /**
   * Diagonally implicit Runge-Kutta methods (SUNDIALS ARKode, ARKStep, fully
   * implicit) on the first-order form
   * @f[ q' = v, \qquad v' = -M^{-1} \nabla V(q). @f]
   * The Newton matrix I - gamma J of each stage is solved exactly by
   * eliminating the velocity correction: (M / gamma^2 + H) dq = M (r_q + gamma
   * r_v) / gamma^2, dv = (dq - r_q) / gamma (ShiftedStiffnessSolver; the
   * system must have a Hessian).
   *
   * Two methods:
   * - Method::midpoint, the implicit midpoint rule as a custom one-stage
   *   Butcher table (A = 1/2, b = 1, c = 1/2) at the fixed step given to the
   *   constructor (the last step is shortened to end on the limit time). It is
   *   symplectic and symmetric: the energy stays bounded (no drift) and linear
   *   and angular momentum (linear and quadratic invariants) are conserved up
   *   to the Newton tolerance (ImplicitParameters::newton_tolerance).
   * - Method::dirk, ARKode's default adaptive DIRK method of order
   *   ImplicitParameters::arkode_order with an embedded error estimate and
   *   local error control (relative_tolerance, absolute_tolerance); the
   *   constructor's step is the first one tried. Not symplectic: the energy
   *   drifts (L-stable tables dissipate).
   *
   * One step() is one internal ARKode step (ARK_ONE_STEP with the limit time
   * as stop time). The SUNDIALS C API is used directly (deal.II 9.4's
   * SUNDIALS::ARKode has no one-step mode and no counters). Failures (Newton,
   * step size below minimum_step) throw ImplicitSolverFailure.
   */
  class ArkodeRungeKutta : public ImplicitIntegrator
  {
  public:
    /** The Runge-Kutta method. */
    enum class Method
    {
      /** The implicit midpoint rule at a fixed step ("arkode midpoint"). */
      midpoint,
      /** An adaptive SDIRK/ESDIRK method of ARKode ("arkode irk"). */
      dirk
    };

    /**
     * For @p system with the settings @p parameters; @p time_step > 0 is the
     * fixed step (midpoint) or the first step tried (dirk).
     */
    ArkodeRungeKutta(const MechanicalSystem   &system,
                     const ImplicitParameters &parameters,
                     const Method              method,
                     const double              time_step);

    ~ArkodeRungeKutta() override;

    /** "arkode midpoint" or "arkode irk". */
    std::string
    name() const override;

    void
    initialize(const double t0, const Vector &q0, const Vector &v0) override;

    /** One internal ARKode step, never past @p t_limit. */
    void
    step(const double t_limit) override;

    /**
     * steps, residual evaluations (evaluations of the implicit right-hand side,
     * one gradient each), Newton iterations, linear iterations, Jacobian
     * setups, error test failures, Newton convergence failures.
     */
    std::vector<Counter>
    counters() const override;

  private:
    const Method method;
    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace estep

#endif
