#ifndef estep_implicit_ida_bdf_h
#define estep_implicit_ida_bdf_h

#include <estep/implicit/implicit_integrator.h>

#include <memory>

namespace estep
{
  /**
   * Variable-step, variable-order BDF (SUNDIALS IDA) on the first-order form
   * y = (q, v) of the equations of motion, written as the residual
   * @f[ F(t, y, y') = \begin{pmatrix} q' - v \\ v' + M^{-1} \nabla V(q)
   *     \end{pmatrix} = 0 . @f]
   * The Newton matrix dF/dy + c_j dF/dy' is solved exactly by eliminating the
   * velocity correction: (c_j^2 M + H) dq = M (r_v + c_j r_q), dv = c_j dq -
   * r_q (ShiftedStiffnessSolver; H the Hessian of the system, which must have
   * one).
   *
   * Local error control with ImplicitParameters::relative_tolerance and
   * absolute_tolerance, maximum order maximum_bdf_order; one step() is one
   * internal IDA step (IDA_ONE_STEP with the limit time as stop time). BDF of
   * order > 1 is not symplectic: the energy decays (numerical dissipation),
   * while linear and angular momentum are conserved to the Newton tolerance
   * (both are linear or quadratic invariants preserved by linear multistep
   * formulas only approximately; in practice their drift is at the level of the
   * local error tolerance).
   *
   * The SUNDIALS C API is used directly: deal.II 9.4's SUNDIALS::IDA only
   * integrates a whole interval (solve_dae()), while estep's time loop asks for
   * one step at a time. Failures (Newton, step size below minimum_step) throw
   * ImplicitSolverFailure.
   */
  class IdaBdf : public ImplicitIntegrator
  {
  public:
    /**
     * For @p system with the settings @p parameters; @p initial_step > 0 is
     * the first step IDA tries.
     */
    IdaBdf(const MechanicalSystem   &system,
           const ImplicitParameters &parameters,
           const double              initial_step);

    ~IdaBdf() override;

    /** "ida bdf". */
    std::string
    name() const override;

    void
    initialize(const double t0, const Vector &q0, const Vector &v0) override;

    /** One internal IDA step, never past @p t_limit. */
    void
    step(const double t_limit) override;

    /**
     * steps, residual evaluations, Newton iterations, linear iterations,
     * Jacobian setups, error test failures, Newton convergence failures.
     */
    std::vector<Counter>
    counters() const override;

    /** The order of the last step. */
    int
    last_order() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace estep

#endif
