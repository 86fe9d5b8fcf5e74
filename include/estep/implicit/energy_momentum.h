#ifndef estep_implicit_energy_momentum_h
#define estep_implicit_energy_momentum_h

#include <estep/implicit/implicit_integrator.h>

#include <memory>

namespace estep
{
  class ElasticBody;

  /**
   * The energy-momentum conserving midpoint scheme of Gonzalez (discrete
   * gradient in the right Cauchy-Green tensor C; O. Gonzalez, "Exact energy and
   * momentum conserving algorithms for general models in nonlinear
   * elasticity", CMAME 190 (2000) 1763-1783) for a P1 elastic body, at a fixed
   * step h:
   * @f[ q_{n+1} - q_n = \frac{h}{2} (v_n + v_{n+1}), \qquad
   *     M (v_{n+1} - v_n) = -h\, f(q_n, q_{n+1}), @f]
   * with the internal force of cell e on its vertex a
   * f_a = |Omega_e| F_m S_alg dN_a/dX, F_m = (F_n + F_{n+1}) / 2 and the
   * algorithmic second Piola-Kirchhoff stress
   * @f[ S_{alg} = 2 \partial_C W(C_m) + 2 \frac{W(C_{n+1}) - W(C_n) -
   *     \partial_C W(C_m) : \Delta C}{\Delta C : \Delta C} \Delta C ,
   *     \quad C_m = (C_n + C_{n+1}) / 2, \ \Delta C = C_{n+1} - C_n . @f]
   * Since S_alg : Delta C / 2 = W(C_{n+1}) - W(C_n) exactly, the total energy
   * 1/2 v^T M v + V(q) is conserved to the accuracy of the nonlinear solve; F_m
   * S_alg with S_alg symmetric exerts no net force or torque, so linear and
   * angular momentum are conserved too. The correction term is dropped where
   * Delta C : Delta C < 1e-10 (there it is O(|Delta C|) and would be
   * round-off; this costs an energy error of order |Delta C|^3 per cell).
   *
   * Each step solves for q_{n+1} with KINSOL (SUNDIALS C API, plain Newton):
   * residual r = (2/h)(q_{n+1} - q_n) - 2 v_n + h M^-1 f(q_n, q_{n+1}) (units
   * of velocity) with the approximate Jacobian (h/2) M^-1 (4/h^2 M + H(q_m))
   * (the tangent stiffness at the midpoint, ShiftedStiffnessSolver; exact up
   * to the derivative of the discrete-gradient correction). Convergence:
   * max |r| <= newton_tolerance (1 + max |v_n|), or, where that is larger
   * (tiny steps, at which the tolerance alone could not be met), the
   * residual's round-off 16 eps (2/h) max |q_n|, eps the machine epsilon. A
   * failed solve throws ImplicitSolverFailure.
   */
  class EnergyMomentum : public ImplicitIntegrator
  {
  public:
    /**
     * For @p body (which must have a Hessian, e.g. an ElasticBodyWithHessian)
     * with the settings @p parameters and the fixed step @p time_step > 0 (the
     * last step is shortened to end on the limit time).
     */
    EnergyMomentum(const ElasticBody        &body,
                   const ImplicitParameters &parameters,
                   const double              time_step);

    ~EnergyMomentum() override;

    /** "energy momentum". */
    std::string
    name() const override;

    void
    initialize(const double t0, const Vector &q0, const Vector &v0) override;

    /** One step of the scheme (one KINSOL solve). */
    void
    step(const double t_limit) override;

    /** steps, residual evaluations, Newton iterations, linear iterations,
     * Jacobian setups. */
    std::vector<Counter>
    counters() const override;

    /**
     * The discrete-gradient internal force f(q0, q1) (see the class
     * documentation) into @p f; with q0 = q1 it is the gradient of V.
     * Both configurations must be admissible (throws std::domain_error).
     */
    void
    discrete_gradient(const Vector &q0, const Vector &q1, Vector &f) const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace estep

#endif
