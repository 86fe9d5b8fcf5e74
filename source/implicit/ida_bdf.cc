#include <deal.II/base/parameter_handler.h>

#include <estep/implicit/ida_bdf.h>
#include <estep/implicit/implicit_parameters.h>
#include <estep/implicit/shifted_stiffness_solver.h>
#include <estep/time_integration/integrator_registry.h>

#include "sundials_support.h"
#include <idas/idas.h>
#include <idas/idas_ls.h>

#include <cmath>
#include <stdexcept>

namespace estep
{
  struct IdaBdf::Implementation
  {
    Implementation(const MechanicalSystem   &system,
                   const ImplicitParameters &parameters)
      : system(system)
      , n(system.n_dofs())
      , linear_solver(system, parameters)
      , q(n)
      , v(n)
      , g(n)
      , rhs(n)
      , dq(n)
    {}

    ~Implementation()
    {
      if (ida_memory != nullptr)
        IDAFree(&ida_memory);
      if (y != nullptr)
        N_VDestroy(y);
      if (yp != nullptr)
        N_VDestroy(yp);
      if (sun_solver != nullptr)
        SUNLinSolFree(sun_solver);
    }

    /** F = (q' - v, v' + M^-1 grad V(q)). */
    static int
    residual(double, N_Vector yy, N_Vector yyp, N_Vector rr, void *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      return internal::guarded_callback(im.callback_error, -1, [&] {
        ++im.residual_evaluations;
        internal::copy_out(yy, 0, im.q);
        if (!std::isfinite(im.system.energy(im.q)))
          return 1; // inadmissible (an inverted cell): retry a smaller step
        im.system.gradient(im.q, im.g);
        const Vector &inverse_mass = im.system.inverse_mass();
        const double *y_data       = internal::data(yy),
                     *yp_data      = internal::data(yyp);
        double *r                  = internal::data(rr);
        for (unsigned int i = 0; i < im.n; ++i)
          {
            r[i]        = yp_data[i] - y_data[im.n + i];
            r[im.n + i] = yp_data[im.n + i] + inverse_mass[i] * im.g[i];
          }
        return 0;
      });
    }

    /** Assemble and factorise c_j^2 M + H(q). */
    static int
    setup(double, N_Vector yy, N_Vector, N_Vector, double c_j, void *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      return internal::guarded_callback(im.callback_error, -1, [&] {
        internal::copy_out(yy, 0, im.q);
        if (!std::isfinite(im.system.energy(im.q)))
          return 1;
        im.linear_solver.setup(im.q, c_j * c_j);
        im.c_j_setup = c_j;
        return 0;
      });
    }

    /** (dq, dv) with (c_j^2 M + H) dq = M (r_v + c_j r_q), dv = c_j dq - r_q
     * (c_j of the last setup). */
    static int
    solve(double,
          N_Vector,
          N_Vector,
          N_Vector,
          N_Vector r,
          N_Vector z,
          double,
          double,
          void *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      // A failure is recoverable: IDA may retry with a fresh setup.
      return internal::guarded_callback(im.callback_error, 1, [&] {
        const Vector &inverse_mass = im.system.inverse_mass();
        const double  c            = im.c_j_setup;
        const double *r_data       = internal::data(r);
        double       *z_data       = internal::data(z);
        for (unsigned int i = 0; i < im.n; ++i)
          im.rhs[i] = (r_data[im.n + i] + c * r_data[i]) / inverse_mass[i];
        im.linear_solver.solve(im.rhs, im.dq);
        for (unsigned int i = 0; i < im.n; ++i)
          {
            z_data[i]        = im.dq[i];
            z_data[im.n + i] = c * im.dq[i] - r_data[i];
          }
        return 0;
      });
    }

    const MechanicalSystem   &system;
    const unsigned int        n;
    internal::SundialsContext context;
    ShiftedStiffnessSolver    linear_solver;
    void                     *ida_memory = nullptr;
    N_Vector                  y = nullptr, yp = nullptr;
    SUNLinearSolver           sun_solver = nullptr;
    Vector                    q, v, g, rhs, dq;
    double                    c_j_setup            = 0.;
    std::uint64_t             residual_evaluations = 0;
    std::string               sundials_error, callback_error;
  };



  IdaBdf::IdaBdf(const MechanicalSystem   &system,
                 const ImplicitParameters &parameters,
                 const double              initial_step)
    : ImplicitIntegrator(system, parameters)
    , implementation(std::make_unique<Implementation>(system, settings))
  {
    if (!(initial_step > 0.) || !std::isfinite(initial_step))
      throw std::invalid_argument(
        "ida bdf: the initial step must be positive and finite.");
    Implementation &im = *implementation;
    im.y               = N_VNew_Serial(2 * im.n, im.context);
    im.yp              = N_VNew_Serial(2 * im.n, im.context);
    N_VConst(0., im.y);
    N_VConst(0., im.yp);
    im.ida_memory = IDACreate(im.context);
    im.sun_solver = internal::make_preconditioner_solver(im.context);
    bool ok       = im.ida_memory != nullptr;
    ok            = ok &&
         IDAInit(im.ida_memory, &Implementation::residual, 0., im.y, im.yp) ==
           IDA_SUCCESS;
    ok = ok && IDASetUserData(im.ida_memory, &im) == IDA_SUCCESS;
    ok = ok && IDASetErrHandlerFn(im.ida_memory,
                                  &internal::store_error_message,
                                  &im.sundials_error) == IDA_SUCCESS;
    ok = ok && IDASStolerances(im.ida_memory,
                               settings.relative_tolerance,
                               settings.absolute_tolerance) == IDA_SUCCESS;
    ok = ok && IDASetLinearSolver(im.ida_memory, im.sun_solver, nullptr) ==
                 IDALS_SUCCESS;
    ok = ok && IDASetPreconditioner(im.ida_memory,
                                    &Implementation::setup,
                                    &Implementation::solve) == IDALS_SUCCESS;
    ok = ok &&
         IDASetMaxOrd(im.ida_memory, settings.maximum_bdf_order) == IDA_SUCCESS;
    ok = ok && IDASetMaxNonlinIters(im.ida_memory,
                                    settings.maximum_newton_iterations) ==
                 IDA_SUCCESS;
    ok = ok && IDASetInitStep(im.ida_memory, initial_step) == IDA_SUCCESS;
    ok =
      ok && IDASetMinStep(im.ida_memory, settings.minimum_step) == IDA_SUCCESS;
    if (!ok)
      throw std::runtime_error("ida bdf: could not set up IDA. " +
                               im.sundials_error);
  }



  IdaBdf::~IdaBdf() = default;



  std::string
  IdaBdf::name() const
  {
    return "ida bdf";
  }



  void
  IdaBdf::initialize(const double t0, const Vector &q0, const Vector &v0)
  {
    Implementation &im = *implementation;
    AssertDimension(q0.size(), im.n);
    t = t_previous = t0;
    q = q_old = q0;
    v = v_old = v0;
    // Consistent initial derivatives: q' = v, v' = -M^-1 grad V(q).
    system.gradient(q0, im.g);
    const Vector &inverse_mass = system.inverse_mass();
    internal::copy_in(q0, im.y, 0);
    internal::copy_in(v0, im.y, im.n);
    internal::copy_in(v0, im.yp, 0);
    double *yp = internal::data(im.yp);
    for (unsigned int i = 0; i < im.n; ++i)
      yp[im.n + i] = -inverse_mass[i] * im.g[i];
    if (IDAReInit(im.ida_memory, t0, im.y, im.yp) != IDA_SUCCESS)
      throw std::runtime_error("ida bdf: IDAReInit failed. " +
                               im.sundials_error);
  }



  void
  IdaBdf::step(const double t_limit)
  {
    if (!(t_limit > t))
      return;
    Implementation &im = *implementation;
    begin_step();
    im.callback_error.clear();
    im.sundials_error.clear();
    IDASetStopTime(im.ida_memory, t_limit);
    double    t_reached = t;
    const int flag =
      IDASolve(im.ida_memory, t_limit, &t_reached, im.y, im.yp, IDA_ONE_STEP);
    if (flag < 0)
      {
        double h = 0.;
        IDAGetCurrentStep(im.ida_memory, &h);
        std::string reason =
          flag == IDA_CONV_FAIL ?
            "the Newton iteration did not converge (Maximum Newton "
            "iterations = " +
              std::to_string(settings.maximum_newton_iterations) +
              ") after repeated step cuts" :
          flag == IDA_ERR_FAIL ?
            "the local error test failed repeatedly (tolerances tighter "
            "than double precision reaches, or a step at the Minimum step)" :
            "IDA failed with flag " + std::to_string(flag);
        throw ImplicitSolverFailure(internal::solver_failure_message(
          name(), t, h, reason, im.sundials_error, im.callback_error));
      }
    internal::copy_out(im.y, 0, q);
    internal::copy_out(im.y, im.n, v);
    t_previous = t;
    t          = (flag == IDA_TSTOP_RETURN) ? t_limit : t_reached;
    count_step();
    check_finite();
  }



  int
  IdaBdf::last_order() const
  {
    int order = 0;
    IDAGetLastOrder(implementation->ida_memory, &order);
    return order;
  }



  std::vector<Counter>
  IdaBdf::counters() const
  {
    const Implementation &im = *implementation;
    long int newton = 0, error_failures = 0, convergence_failures = 0;
    IDAGetNumNonlinSolvIters(im.ida_memory, &newton);
    IDAGetNumErrTestFails(im.ida_memory, &error_failures);
    IDAGetNumNonlinSolvConvFails(im.ida_memory, &convergence_failures);
    return with_resumed_counts(
      {{"steps", steps},
       {"residual evaluations", im.residual_evaluations},
       {"newton iterations", static_cast<std::uint64_t>(newton)},
       {"linear iterations", im.linear_solver.n_linear_iterations()},
       {"jacobian setups", im.linear_solver.n_setups()},
       {"error test failures", static_cast<std::uint64_t>(error_failures)},
       {"newton convergence failures",
        static_cast<std::uint64_t>(convergence_failures)}});
  }


  namespace
  {
    std::unique_ptr<TimeIntegrator>
    create_ida_bdf(dealii::ParameterHandler &prm,
                   const MechanicalSystem   &system)
    {
      const ImplicitParameters parameters = parse_implicit_parameters(prm);
      parameters.check_adaptive();
      return std::make_unique<IdaBdf>(system, parameters, parameters.time_step);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_INTEGRATOR(
  "ida bdf",
  "SUNDIALS IDA's variable-order, variable-step BDF method with local error "
  "control (subsection Implicit integrators).",
  estep::declare_implicit_parameters,
  estep::create_ida_bdf)
