#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <estep/base/mpi_session.h>
#include <estep/implicit/shifted_stiffness_solver.h>

#include <memory>
#include <stdexcept>

namespace estep
{
  struct ShiftedStiffnessSolver::Implementation
  {
    Implementation(const MechanicalSystem   &system,
                   const ImplicitParameters &parameters)
      : system(system)
      , parameters(parameters)
    {}

    /** S = a M + H from the stored H, then factorise or build the AMG. */
    void
    prepare(const double a)
    {
      shift = a;
      S.copy_from(H);
      const Vector &inverse_mass = system.inverse_mass();
      for (unsigned int i = 0; i < S.m(); ++i)
        S.diag_element(i) += a / inverse_mass[i];
      if (parameters.linear_solver == ImplicitLinearSolver::direct)
        {
          direct.initialize(S);
        }
      else
        {
          // Trilinos objects talk to MPI already when constructed: only here.
          if (!trilinos_S)
            {
              trilinos_S =
                std::make_unique<dealii::TrilinosWrappers::SparseMatrix>();
              amg =
                std::make_unique<dealii::TrilinosWrappers::PreconditionAMG>();
            }
          trilinos_S->reinit(S);
          dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
          data.elliptic              = true;
          data.higher_order_elements = false;
          data.smoother_sweeps       = 2;
          data.aggregation_threshold = 0.02;
          // The three translations: constant modes of each component (the
          // coordinates are point-major, 3 per point).
          const unsigned int dim = system.spatial_dimension();
          data.constant_modes.assign(dim, std::vector<bool>(S.m(), false));
          for (unsigned int i = 0; i < S.m(); ++i)
            data.constant_modes[i % dim][i] = true;
          amg->initialize(*trilinos_S, data);
        }
      ++setups;
    }

    const MechanicalSystem                                    &system;
    const ImplicitParameters                                   parameters;
    dealii::SparseMatrix<double>                               H, S;
    dealii::SparseDirectUMFPACK                                direct;
    std::unique_ptr<dealii::TrilinosWrappers::SparseMatrix>    trilinos_S;
    std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
    double                                                     shift = 0.;
    std::uint64_t setups = 0, solves = 0, iterations = 0;
  };



  ShiftedStiffnessSolver::ShiftedStiffnessSolver(
    const MechanicalSystem   &system,
    const ImplicitParameters &parameters)
    : implementation(std::make_unique<Implementation>(system, parameters))
  {
    if (!system.has_hessian())
      throw std::invalid_argument(
        "The implicit integrators need the Hessian (tangent stiffness) of the "
        "system, and the system <" +
        system.name() +
        "> provides none (for an elastic body use ElasticBodyWithHessian).");
    if (parameters.linear_solver == ImplicitLinearSolver::cg_amg)
      start_mpi(); // Trilinos talks to MPI
    implementation->H.reinit(system.hessian_sparsity());
    implementation->S.reinit(system.hessian_sparsity());
  }



  ShiftedStiffnessSolver::~ShiftedStiffnessSolver() = default;



  void
  ShiftedStiffnessSolver::setup(const Vector &q, const double a)
  {
    implementation->system.hessian(q, implementation->H);
    implementation->prepare(a);
  }



  void
  ShiftedStiffnessSolver::reshift(const double a)
  {
    implementation->prepare(a);
  }



  double
  ShiftedStiffnessSolver::shift() const
  {
    return implementation->shift;
  }



  void
  ShiftedStiffnessSolver::solve(const Vector &b, Vector &x)
  {
    Implementation &im = *implementation;
    ++im.solves;
    if (im.parameters.linear_solver == ImplicitLinearSolver::direct)
      {
        im.direct.vmult(x, b);
        ++im.iterations;
        return;
      }
    if (b.l2_norm() == 0.)
      {
        x = 0.;
        return;
      }
    dealii::SolverControl    control(im.parameters.maximum_linear_iterations,
                                  im.parameters.linear_tolerance * b.l2_norm(),
                                  false,
                                  false);
    dealii::SolverCG<Vector> cg(control);
    x = 0.;
    try
      {
        cg.solve(*im.trilinos_S, x, b, *im.amg);
      }
    catch (const dealii::SolverControl::NoConvergence &e)
      {
        im.iterations += control.last_step();
        throw std::runtime_error("CG with AMG did not converge in " +
                                 std::to_string(control.last_step()) +
                                 " iterations (residual " +
                                 std::to_string(e.last_residual) + ").");
      }
    im.iterations += control.last_step();
  }



  std::uint64_t
  ShiftedStiffnessSolver::n_setups() const
  {
    return implementation->setups;
  }



  std::uint64_t
  ShiftedStiffnessSolver::n_solves() const
  {
    return implementation->solves;
  }



  std::uint64_t
  ShiftedStiffnessSolver::n_linear_iterations() const
  {
    return implementation->iterations;
  }
} // namespace estep
