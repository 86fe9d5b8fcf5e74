#ifndef estep_implicit_shifted_stiffness_solver_h
#define estep_implicit_shifted_stiffness_solver_h

#include <estep/implicit/implicit_parameters.h>
#include <estep/systems/mechanical_system.h>

#include <cstdint>
#include <memory>

namespace estep
{
  /**
   * Solves the linear systems of the Newton iterations of all implicit
   * integrators: after the elimination of the velocity unknowns each of them
   * reduces to
   * @f[ S x = b, \qquad S = a M + H(q), @f]
   * with M the lumped mass, H the Hessian (tangent stiffness) of the system and
   * a > 0 a method-dependent shift (c_j^2 for IDA, 1/gamma^2 for ARKode, 4/h^2
   * for the energy-momentum scheme). S is symmetric; for the shifts of
   * ordinary step sizes it is positive definite.
   *
   * setup() assembles H through MechanicalSystem::hessian() and factorises S
   * (UMFPACK) or builds the AMG preconditioner (Trilinos ML); solve() then
   * solves with that S. Counts setups, solves and linear iterations (a direct
   * solve counts as one iteration).
   */
  class ShiftedStiffnessSolver
  {
  public:
    /**
     * For @p system (which must have a Hessian: has_hessian()), with the
     * linear solver settings of @p parameters. Throws std::invalid_argument if
     * the system has no Hessian, std::runtime_error if "cg amg" is selected
     * and MPI is not initialised.
     */
    ShiftedStiffnessSolver(const MechanicalSystem   &system,
                           const ImplicitParameters &parameters);

    ~ShiftedStiffnessSolver();

    /** Assemble H(q) and prepare the solver for S = a M + H(q). Throws
     * std::domain_error if q is inadmissible. */
    void
    setup(const Vector &q, const double a);

    /** Prepare the solver for S = a M + H with the H of the last setup(). */
    void
    reshift(const double a);

    /** The shift a of the current S. */
    double
    shift() const;

    /** x = S^-1 b. Throws std::runtime_error if CG does not converge. */
    void
    solve(const Vector &b, Vector &x);

    /** Number of setup() and reshift() calls (Newton-matrix setups). */
    std::uint64_t
    n_setups() const;

    /** Number of solve() calls. */
    std::uint64_t
    n_solves() const;

    /** Linear iterations: CG iterations, or one per direct solve. */
    std::uint64_t
    n_linear_iterations() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace estep

#endif
