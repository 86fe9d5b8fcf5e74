#ifndef estep_implicit_implicit_parameters_h
#define estep_implicit_implicit_parameters_h

#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace estep
{
  /** The linear solver of the Newton iterations of the implicit integrators.
   */
  enum class ImplicitLinearSolver
  {
    /** Sparse direct: deal.II SparseDirectUMFPACK (the default). */
    direct,
    /** Trilinos CG preconditioned with ML algebraic multigrid (needs MPI
       initialised, e.g. by dealii::Utilities::MPI::MPI_InitFinalize). */
    cg_amg
  };

  /**
   * The settings of the implicit (SUNDIALS) integrators: the entries of the
   * subsection "Implicit integrators" (see declare_implicit_parameters()).
   * Tolerances are absolute in the units of q (length) and v (length / time)
   * unless said otherwise.
   */
  struct ImplicitParameters
  {
    /** The fixed step of "arkode midpoint" and "energy momentum"; the initial
     * step of the adaptive methods. */
    double time_step = 1e-3;

    /** Relative local error tolerance of the adaptive methods ("ida bdf",
     * "arkode irk"). */
    double relative_tolerance = 1e-6;
    /** Absolute local error tolerance of the adaptive methods. */
    double absolute_tolerance = 1e-8;
    /** Maximum BDF order of IDA (1-5). */
    unsigned int maximum_bdf_order = 5;
    /** Order of the adaptive ARKode DIRK method (2-5). */
    unsigned int arkode_order = 3;
    /**
     * Newton tolerance of the fixed-step methods ("arkode midpoint": relative
     * and absolute tolerance of ARKode's nonlinear solver test; "energy
     * momentum": KINSOL's residual tolerance, relative to 1 + max |v|).
     */
    double newton_tolerance = 1e-10;
    /** Maximum Newton iterations per nonlinear solve (per stage or step). */
    unsigned int maximum_newton_iterations = 10;
    /** ARKode: maximum number of steps between two Newton-matrix setups. */
    unsigned int jacobian_update_interval = 5;
    /** Smallest step the adaptive methods may take; below it the run fails. */
    double minimum_step = 1e-8;
    /** The linear solver. */
    ImplicitLinearSolver linear_solver = ImplicitLinearSolver::direct;
    /** Relative residual tolerance of CG (cg amg only). */
    double linear_tolerance = 1e-10;
    /** Maximum CG iterations per linear solve (cg amg only). */
    unsigned int maximum_linear_iterations = 1000;

    /** The entries of the subsection that the chosen method or linear
     * solver does not read but the input changed from their defaults, as
     * warnings (entries_unread_by_type()). */
    std::vector<std::string> unread_entries;

    /** Check the settings across entries; throws std::invalid_argument with a
     * clear message. */
    void
    check() const;

    /** check() and what only the adaptive methods (ida bdf, arkode irk)
     * need: a minimum step not above their initial step. */
    void
    check_adaptive() const;
  };

  /**
   * Declare the subsection "Implicit integrators" of @p prm (at the current
   * level of @p prm): every entry of ImplicitParameters, documented and
   * bounded by Patterns.
   */
  void
  declare_implicit_parameters(dealii::ParameterHandler &prm);

  /**
   * Read the subsection "Implicit integrators" of @p prm (declared by
   * declare_implicit_parameters(), at the current level of @p prm, that of
   * the entry `Method`), checked, with the entries the method does not read.
   */
  ImplicitParameters
  parse_implicit_parameters(const dealii::ParameterHandler &prm);

  /** The text of a linear solver selection ("direct", "cg amg"). */
  std::string
  to_string(const ImplicitLinearSolver solver);
} // namespace estep

#endif
