#include <deal.II/base/parameter_handler.h>

#include <estep/implicit/arkode_runge_kutta.h>
#include <estep/implicit/implicit_parameters.h>
#include <estep/implicit/shifted_stiffness_solver.h>
#include <estep/time_integration/integrator_registry.h>

#include "sundials_support.h"
#include <arkode/arkode_arkstep.h>
#include <arkode/arkode_butcher.h>

#include <cmath>
#include <stdexcept>

namespace estep
{
  struct ArkodeRungeKutta::Implementation
  {
    Implementation(const MechanicalSystem   &system,
                   const ImplicitParameters &parameters)
      : system(system)
      , n(system.n_dofs())
      , linear_solver(system, parameters)
      , q(n)
      , g(n)
      , rhs(n)
      , dq(n)
    {}

    ~Implementation()
    {
      if (arkode_memory != nullptr)
        ARKStepFree(&arkode_memory);
      if (y != nullptr)
        N_VDestroy(y);
      if (sun_solver != nullptr)
        SUNLinSolFree(sun_solver);
      if (table != nullptr)
        ARKodeButcherTable_Free(table);
    }

    /** y' = (v, -M^-1 grad V(q)). */
    static int
    right_hand_side(double, N_Vector yy, N_Vector ydot, void *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      return internal::guarded_callback(im.callback_error, -1, [&] {
        internal::copy_out(yy, 0, im.q);
        if (!std::isfinite(im.system.energy(im.q)))
          return 1; // inadmissible (an inverted cell): recoverable
        im.system.gradient(im.q, im.g);
        const Vector &inverse_mass = im.system.inverse_mass();
        const double *y_data       = internal::data(yy);
        double       *d            = internal::data(ydot);
        for (unsigned int i = 0; i < im.n; ++i)
          {
            d[i]        = y_data[im.n + i];
            d[im.n + i] = -inverse_mass[i] * im.g[i];
          }
        return 0;
      });
    }

    /** Prepare M / gamma^2 + H(q) (reusing H if ARKode allows it). */
    static int
    setup(double,
          N_Vector yy,
          N_Vector,
          booleantype  jacobian_ok,
          booleantype *jacobian_current,
          double       gamma,
          void        *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      return internal::guarded_callback(im.callback_error, -1, [&] {
        if (jacobian_ok)
          {
            im.linear_solver.reshift(1. / (gamma * gamma));
            *jacobian_current = SUNFALSE;
          }
        else
          {
            internal::copy_out(yy, 0, im.q);
            if (!std::isfinite(im.system.energy(im.q)))
              return 1;
            im.linear_solver.setup(im.q, 1. / (gamma * gamma));
            *jacobian_current = SUNTRUE;
          }
        im.gamma_setup = gamma;
        return 0;
      });
    }

    /** (dq, dv): (M / gamma^2 + H) dq = M (r_q + gamma r_v) / gamma^2,
     * dv = (dq - r_q) / gamma. */
    static int
    solve(double,
          N_Vector,
          N_Vector,
          N_Vector r,
          N_Vector z,
          double,
          double,
          int,
          void *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      return internal::guarded_callback(im.callback_error, 1, [&] {
        const Vector &inverse_mass = im.system.inverse_mass();
        const double  gamma        = im.gamma_setup;
        const double *r_data       = internal::data(r);
        double       *z_data       = internal::data(z);
        for (unsigned int i = 0; i < im.n; ++i)
          im.rhs[i] = (r_data[i] + gamma * r_data[im.n + i]) /
                      (inverse_mass[i] * gamma * gamma);
        im.linear_solver.solve(im.rhs, im.dq);
        for (unsigned int i = 0; i < im.n; ++i)
          {
            z_data[i]        = im.dq[i];
            z_data[im.n + i] = (im.dq[i] - r_data[i]) / gamma;
          }
        return 0;
      });
    }

    const MechanicalSystem   &system;
    const unsigned int        n;
    internal::SundialsContext context;
    ShiftedStiffnessSolver    linear_solver;
    void                     *arkode_memory = nullptr;
    N_Vector                  y             = nullptr;
    SUNLinearSolver           sun_solver    = nullptr;
    ARKodeButcherTable        table         = nullptr;
    Vector                    q, g, rhs, dq;
    double                    gamma_setup = 1.;
    std::string               sundials_error, callback_error;
  };



  ArkodeRungeKutta::ArkodeRungeKutta(const MechanicalSystem   &system,
                                     const ImplicitParameters &parameters,
                                     const Method              method,
                                     const double              time_step)
    : ImplicitIntegrator(system, parameters)
    , method(method)
    , implementation(std::make_unique<Implementation>(system, settings))
  {
    if (!(time_step > 0.) || !std::isfinite(time_step))
      throw std::invalid_argument(name() +
                                  ": the time step must be positive and "
                                  "finite.");
    Implementation &im = *implementation;
    im.y               = N_VNew_Serial(2 * im.n, im.context);
    N_VConst(0., im.y);
    im.arkode_memory = ARKStepCreate(
      nullptr, &Implementation::right_hand_side, 0., im.y, im.context);
    im.sun_solver = internal::make_preconditioner_solver(im.context);
    void *mem     = im.arkode_memory;
    bool  ok      = mem != nullptr;
    ok            = ok && ARKStepSetUserData(mem, &im) == ARK_SUCCESS;
    ok            = ok && ARKStepSetErrHandlerFn(mem,
                                      &internal::store_error_message,
                                      &im.sundials_error) == ARK_SUCCESS;
    ok            = ok &&
         ARKStepSetLinearSolver(mem, im.sun_solver, nullptr) == ARKLS_SUCCESS;
    ok =
      ok && ARKStepSetPreconditioner(mem,
                                     &Implementation::setup,
                                     &Implementation::solve) == ARKLS_SUCCESS;
    if (method == Method::midpoint)
      {
        // The implicit midpoint rule: one stage, A = 1/2, b = 1, c = 1/2,
        // order 2, no embedding (fixed step).
        double A[1] = {0.5}, b[1] = {1.}, c[1] = {0.5};
        im.table = ARKodeButcherTable_Create(1, 2, 0, c, A, b, nullptr);
        ok       = ok && im.table != nullptr;
        ok =
          ok && ARKStepSStolerances(mem,
                                    settings.newton_tolerance,
                                    settings.newton_tolerance) == ARK_SUCCESS;
        ok =
          ok && ARKStepSetTables(mem, 2, 0, im.table, nullptr) == ARK_SUCCESS;
        ok = ok && ARKStepSetFixedStep(mem, time_step) == ARK_SUCCESS;
      }
    else
      {
        ok =
          ok && ARKStepSStolerances(mem,
                                    settings.relative_tolerance,
                                    settings.absolute_tolerance) == ARK_SUCCESS;
        ok = ok && ARKStepSetOrder(mem, settings.arkode_order) == ARK_SUCCESS;
        ok = ok && ARKStepSetInitStep(mem, time_step) == ARK_SUCCESS;
        ok = ok && ARKStepSetMinStep(mem, settings.minimum_step) == ARK_SUCCESS;
      }
    ok =
      ok && ARKStepSetMaxNonlinIters(mem, settings.maximum_newton_iterations) ==
              ARK_SUCCESS;
    ok =
      ok && ARKStepSetLSetupFrequency(mem, settings.jacobian_update_interval) ==
              ARK_SUCCESS;
    if (!ok)
      throw std::runtime_error(name() + ": could not set up ARKode. " +
                               im.sundials_error);
  }



  ArkodeRungeKutta::~ArkodeRungeKutta() = default;



  std::string
  ArkodeRungeKutta::name() const
  {
    return method == Method::midpoint ? "arkode midpoint" : "arkode irk";
  }



  void
  ArkodeRungeKutta::initialize(const double  t0,
                               const Vector &q0,
                               const Vector &v0)
  {
    Implementation &im = *implementation;
    AssertDimension(q0.size(), im.n);
    t = t_previous = t0;
    q = q_old = q0;
    v = v_old = v0;
    internal::copy_in(q0, im.y, 0);
    internal::copy_in(v0, im.y, im.n);
    if (ARKStepReInit(im.arkode_memory,
                      nullptr,
                      &Implementation::right_hand_side,
                      t0,
                      im.y) != ARK_SUCCESS)
      throw std::runtime_error(name() + ": ARKStepReInit failed. " +
                               im.sundials_error);
  }



  void
  ArkodeRungeKutta::step(const double t_limit)
  {
    if (!(t_limit > t))
      return;
    Implementation &im = *implementation;
    begin_step();
    im.callback_error.clear();
    im.sundials_error.clear();
    ARKStepSetStopTime(im.arkode_memory, t_limit);
    double    t_reached = t;
    const int flag =
      ARKStepEvolve(im.arkode_memory, t_limit, im.y, &t_reached, ARK_ONE_STEP);
    if (flag < 0)
      {
        double h = 0.;
        ARKStepGetCurrentStep(im.arkode_memory, &h);
        std::string reason =
          flag == ARK_CONV_FAILURE ?
            "the Newton iteration did not converge (Maximum Newton "
            "iterations = " +
              std::to_string(settings.maximum_newton_iterations) +
              (method == Method::midpoint ? ") at the fixed step" :
                                            ") after repeated step cuts") :
          flag == ARK_ERR_FAILURE ?
            "the local error test failed repeatedly (tolerances tighter "
            "than double precision reaches, or a step at the Minimum step)" :
            "ARKode failed with flag " + std::to_string(flag);
        throw ImplicitSolverFailure(internal::solver_failure_message(
          name(), t, h, reason, im.sundials_error, im.callback_error));
      }
    internal::copy_out(im.y, 0, q);
    internal::copy_out(im.y, im.n, v);
    t_previous = t;
    t          = (flag == ARK_TSTOP_RETURN) ? t_limit : t_reached;
    count_step();
    check_finite();
  }



  std::vector<Counter>
  ArkodeRungeKutta::counters() const
  {
    const Implementation &im  = *implementation;
    long int              nfe = 0, nfi = 0, newton = 0, error_failures = 0,
             convergence_failures = 0;
    ARKStepGetNumRhsEvals(im.arkode_memory, &nfe, &nfi);
    ARKStepGetNumNonlinSolvIters(im.arkode_memory, &newton);
    ARKStepGetNumErrTestFails(im.arkode_memory, &error_failures);
    ARKStepGetNumNonlinSolvConvFails(im.arkode_memory, &convergence_failures);
    return with_resumed_counts(
      {{"steps", steps},
       {"residual evaluations", static_cast<std::uint64_t>(nfi)},
       {"newton iterations", static_cast<std::uint64_t>(newton)},
       {"linear iterations", im.linear_solver.n_linear_iterations()},
       {"jacobian setups", im.linear_solver.n_setups()},
       {"error test failures", static_cast<std::uint64_t>(error_failures)},
       {"newton convergence failures",
        static_cast<std::uint64_t>(convergence_failures)}});
  }


  namespace
  {
    template <ArkodeRungeKutta::Method method>
    std::unique_ptr<TimeIntegrator>
    create_arkode(dealii::ParameterHandler &prm, const MechanicalSystem &system)
    {
      const ImplicitParameters parameters = parse_implicit_parameters(prm);
      if (method == ArkodeRungeKutta::Method::midpoint)
        require_resolvable_time_step(prm,
                                     "Implicit integrators/Time step",
                                     parameters.time_step);
      if (method == ArkodeRungeKutta::Method::dirk)
        parameters.check_adaptive();
      return std::make_unique<ArkodeRungeKutta>(system,
                                                parameters,
                                                method,
                                                parameters.time_step);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_INTEGRATOR(
  "arkode midpoint",
  "the implicit midpoint rule (symplectic, second order) through SUNDIALS "
  "ARKode at the fixed time step (subsection Implicit integrators).",
  estep::declare_implicit_parameters,
  estep::create_arkode<estep::ArkodeRungeKutta::Method::midpoint>)

ESTEP_REGISTER_INTEGRATOR(
  "arkode irk",
  "SUNDIALS ARKode's adaptive diagonally implicit Runge-Kutta method "
  "(subsection Implicit integrators).",
  estep::declare_implicit_parameters,
  estep::create_arkode<estep::ArkodeRungeKutta::Method::dirk>)
