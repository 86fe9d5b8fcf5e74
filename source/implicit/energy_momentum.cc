#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <estep/fem/elastic_body.h>
#include <estep/fem/p1_cell_data.h>
#include <estep/implicit/energy_momentum.h>
#include <estep/implicit/implicit_parameters.h>
#include <estep/implicit/shifted_stiffness_solver.h>
#include <estep/materials/material.h>
#include <estep/time_integration/integrator_registry.h>

#include "sundials_support.h"
#include <kinsol/kinsol.h>
#include <kinsol/kinsol_ls.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace estep
{
  namespace
  {
    /** Deformation gradient of cell e at the positions q. */
    dealii::Tensor<2, 3>
    deformation_gradient(const Vector      &q,
                         const P1CellData  &data,
                         const unsigned int e,
                         const double (&grad)[4][3])
    {
      dealii::Tensor<2, 3> F;
      for (unsigned int a = 0; a < 4; ++a)
        {
          const unsigned int p = data.point[a][e];
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int I = 0; I < 3; ++I)
              F[i][I] += q[3 * p + i] * grad[a][I];
        }
      return F;
    }
  } // namespace

  struct EnergyMomentum::Implementation
  {
    Implementation(const ElasticBody        &body,
                   const ImplicitParameters &parameters,
                   const double              time_step)
      : body(body)
      , n(body.n_dofs())
      , dt(time_step)
      , linear_solver(body, parameters)
      , q_mid(n)
      , force(n)
      , rhs(n)
      , q1(n)
    {}

    ~Implementation()
    {
      if (kinsol_memory != nullptr)
        KINFree(&kinsol_memory);
      if (u != nullptr)
        N_VDestroy(u);
      if (scale != nullptr)
        N_VDestroy(scale);
      if (sun_solver != nullptr)
        SUNLinSolFree(sun_solver);
    }

    /** r(q1) = (2/h)(q1 - q0) - 2 v0 + h M^-1 f(q0, q1). */
    static int
    residual(N_Vector uu, N_Vector rr, void *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      return internal::guarded_callback(im.callback_error, -1, [&] {
        ++im.residual_evaluations;
        internal::copy_out(uu, 0, im.q1);
        if (!std::isfinite(im.body.energy(im.q1)))
          return 1; // inadmissible: recoverable
        im.owner->discrete_gradient(*im.q0, im.q1, im.force);
        const Vector &inverse_mass = im.body.inverse_mass();
        const double  h            = im.h;
        double       *r            = internal::data(rr);
        for (unsigned int i = 0; i < im.n; ++i)
          r[i] = (2. / h) * (im.q1[i] - (*im.q0)[i]) - 2. * (*im.v0)[i] +
                 h * inverse_mass[i] * im.force[i];
        return 0;
      });
    }

    /** Factorise 4/h^2 M + H((q0 + q1) / 2). */
    static int
    setup(N_Vector uu, N_Vector, N_Vector, N_Vector, void *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      return internal::guarded_callback(im.callback_error, -1, [&] {
        const double *u_data = internal::data(uu);
        for (unsigned int i = 0; i < im.n; ++i)
          im.q_mid[i] = 0.5 * ((*im.q0)[i] + u_data[i]);
        if (!std::isfinite(im.body.energy(im.q_mid)))
          return 1;
        im.linear_solver.setup(im.q_mid, 4. / (im.h * im.h));
        return 0;
      });
    }

    /** x = (4/h^2 M + H)^-1 (2/h) M b, in place. */
    static int
    solve(N_Vector, N_Vector, N_Vector, N_Vector, N_Vector vv, void *data)
    {
      auto &im = *static_cast<Implementation *>(data);
      return internal::guarded_callback(im.callback_error, 1, [&] {
        const Vector &inverse_mass = im.body.inverse_mass();
        double       *b            = internal::data(vv);
        for (unsigned int i = 0; i < im.n; ++i)
          im.rhs[i] = (2. / im.h) * b[i] / inverse_mass[i];
        im.linear_solver.solve(im.rhs, im.force);
        for (unsigned int i = 0; i < im.n; ++i)
          b[i] = im.force[i];
        return 0;
      });
    }

    const ElasticBody        &body;
    const EnergyMomentum     *owner = nullptr;
    const unsigned int        n;
    const double              dt;
    internal::SundialsContext context;
    ShiftedStiffnessSolver    linear_solver;
    void                     *kinsol_memory = nullptr;
    N_Vector                  u = nullptr, scale = nullptr;
    SUNLinearSolver           sun_solver = nullptr;
    Vector                    q_mid, force, rhs, q1;
    /** The start of the current step and its length. */
    const Vector *q0 = nullptr, *v0 = nullptr;
    double        h                    = 0.;
    std::uint64_t residual_evaluations = 0, newton_iterations = 0;
    std::string   sundials_error, callback_error;
  };



  EnergyMomentum::EnergyMomentum(const ElasticBody        &body,
                                 const ImplicitParameters &parameters,
                                 const double              time_step)
    : ImplicitIntegrator(body, parameters)
    , implementation(
        std::make_unique<Implementation>(body, settings, time_step))
  {
    if (!(time_step > 0.) || !std::isfinite(time_step))
      throw std::invalid_argument(
        "energy momentum: the time step must be positive and finite.");
    Implementation &im = *implementation;
    im.owner           = this;
    im.u               = N_VNew_Serial(im.n, im.context);
    im.scale           = N_VNew_Serial(im.n, im.context);
    N_VConst(0., im.u);
    N_VConst(1., im.scale);
    im.kinsol_memory = KINCreate(im.context);
    im.sun_solver    = internal::make_preconditioner_solver(im.context);
    void *mem        = im.kinsol_memory;
    bool  ok         = mem != nullptr;
    ok = ok && KINInit(mem, &Implementation::residual, im.u) == KIN_SUCCESS;
    ok = ok && KINSetUserData(mem, &im) == KIN_SUCCESS;
    ok = ok && KINSetErrHandlerFn(mem,
                                  &internal::store_error_message,
                                  &im.sundials_error) == KIN_SUCCESS;
    ok = ok && KINSetLinearSolver(mem, im.sun_solver, nullptr) == KINLS_SUCCESS;
    ok = ok && KINSetPreconditioner(mem,
                                    &Implementation::setup,
                                    &Implementation::solve) == KINLS_SUCCESS;
    ok = ok && KINSetNumMaxIters(mem, settings.maximum_newton_iterations) ==
                 KIN_SUCCESS;
    // A constant forcing term: no Jacobian-vector products (the linear
    // solves are exact anyway).
    ok = ok && KINSetEtaForm(mem, KIN_ETACONSTANT) == KIN_SUCCESS;
    ok = ok && KINSetScaledStepTol(mem, 1e-30) == KIN_SUCCESS;
    if (!ok)
      throw std::runtime_error("energy momentum: could not set up KINSOL. " +
                               im.sundials_error);
  }



  EnergyMomentum::~EnergyMomentum() = default;



  std::string
  EnergyMomentum::name() const
  {
    return "energy momentum";
  }



  void
  EnergyMomentum::initialize(const double  t0,
                             const Vector &q0,
                             const Vector &v0)
  {
    AssertDimension(q0.size(), implementation->n);
    t = t_previous = t0;
    q = q_old = q0;
    v = v_old = v0;
  }



  void
  EnergyMomentum::discrete_gradient(const Vector &q0,
                                    const Vector &q1,
                                    Vector       &f) const
  {
    const ElasticBody &body     = implementation->body;
    const P1CellData  &data     = body.every_cell_data();
    const Material    &material = body.material();
    const double       c        = material.quadratic_modulus();
    f.reinit(q0.size());
    for (unsigned int e = 0; e < data.n_cells; ++e)
      {
        double grad[4][3];
        for (unsigned int I = 0; I < 3; ++I)
          {
            grad[0][I] = 0.;
            for (unsigned int a = 0; a < 3; ++a)
              {
                grad[a + 1][I] = data.shape_gradient[3 * a + I][e];
                grad[0][I] -= grad[a + 1][I];
              }
          }
        const dealii::Tensor<2, 3> F0 = deformation_gradient(q0, data, e, grad);
        const dealii::Tensor<2, 3> F1 = deformation_gradient(q1, data, e, grad);
        const double J0 = dealii::determinant(F0), J1 = dealii::determinant(F1);
        if (!(J0 > 0.) || !(J1 > 0.))
          throw std::domain_error("energy momentum: cell " + std::to_string(e) +
                                  " is inverted.");
        const dealii::Tensor<2, 3> C0 = dealii::transpose(F0) * F0;
        const dealii::Tensor<2, 3> C1 = dealii::transpose(F1) * F1;
        const dealii::Tensor<2, 3> Cm = 0.5 * (C0 + C1);
        const dealii::Tensor<2, 3> dC = C1 - C0;
        const double               Jm = std::sqrt(dealii::determinant(Cm));
        // dW_vol/dC at C_m: f'(J) J / 2 C^-1.
        const dealii::Tensor<2, 3> G =
          (0.5 * material.volumetric_derivative(Jm) * Jm) * dealii::invert(Cm);
        dealii::Tensor<2, 3> S = 2. * G;
        for (unsigned int i = 0; i < 3; ++i)
          S[i][i] += c;
        const double dd = dealii::scalar_product(dC, dC);
        if (dd > 1e-10)
          S +=
            (2. *
             (material.volumetric_energy(J1) - material.volumetric_energy(J0) -
              dealii::scalar_product(G, dC)) /
             dd) *
            dC;
        const dealii::Tensor<2, 3> P = (0.5 * data.volume[e]) * (F0 + F1) * S;
        for (unsigned int a = 0; a < 4; ++a)
          {
            const unsigned int p = data.point[a][e];
            for (unsigned int i = 0; i < 3; ++i)
              f[3 * p + i] += P[i][0] * grad[a][0] + P[i][1] * grad[a][1] +
                              P[i][2] * grad[a][2];
          }
      }
  }



  void
  EnergyMomentum::step(const double t_limit)
  {
    const double remaining = t_limit - t;
    if (!(remaining > 0.))
      return;
    Implementation &im = *implementation;
    const double    h  = (remaining < im.dt * (1. + 1e-6)) ? remaining : im.dt;
    begin_step();
    im.callback_error.clear();
    im.sundials_error.clear();
    im.q0 = &q_old;
    im.v0 = &v_old;
    im.h  = h;

    // Predictor: a velocity-Verlet step, or free flight if that is
    // inadmissible.
    const Vector &inverse_mass = system.inverse_mass();
    system.gradient(q_old, im.force);
    for (unsigned int i = 0; i < im.n; ++i)
      im.q1[i] =
        q_old[i] + h * v_old[i] - 0.5 * h * h * inverse_mass[i] * im.force[i];
    if (!std::isfinite(system.energy(im.q1)))
      for (unsigned int i = 0; i < im.n; ++i)
        im.q1[i] = q_old[i] + h * v_old[i];
    internal::copy_in(im.q1, im.u, 0);

    // The residual's own round-off bounds the tolerance from below: q1 is
    // known to eps |q1| at best (eps the machine epsilon), which the residual
    // carries as (2/h) eps max |q|; at small steps the Newton tolerance alone
    // lies beneath it and cannot be met. The velocity (2/h)(q1 - q0) - v0
    // has that error whatever the tolerance.
    const double tolerance =
      std::max(settings.newton_tolerance * (1. + v_old.linfty_norm()),
               16. * std::numeric_limits<double>::epsilon() * (2. / h) *
                 q_old.linfty_norm());
    KINSetFuncNormTol(im.kinsol_memory, tolerance);
    const int flag =
      KINSol(im.kinsol_memory, im.u, KIN_NONE, im.scale, im.scale);
    long int iterations = 0;
    KINGetNumNonlinSolvIters(im.kinsol_memory, &iterations);
    im.newton_iterations += static_cast<std::uint64_t>(iterations);
    bool converged = flag == KIN_SUCCESS || flag == KIN_INITIAL_GUESS_OK;
    if (flag == KIN_STEP_LT_STPTOL)
      {
        // Stalled: accept only if the residual is small anyway.
        N_Vector r = N_VClone(im.u);
        converged  = Implementation::residual(im.u, r, &im) == 0 &&
                    N_VMaxNorm(r) <= 10. * tolerance;
        N_VDestroy(r);
      }
    if (!converged)
      {
        std::string reason =
          flag == KIN_MAXITER_REACHED ?
            "the Newton iteration did not converge in " +
              std::to_string(settings.maximum_newton_iterations) +
              " iterations (Maximum Newton iterations)" :
          flag == KIN_STEP_LT_STPTOL ?
            "the Newton steps fell to round-off with the residual above the "
            "tolerance" :
            "KINSOL failed with flag " + std::to_string(flag);
        throw ImplicitSolverFailure(internal::solver_failure_message(
          name(), t, h, reason, im.sundials_error, im.callback_error));
      }
    internal::copy_out(im.u, 0, q);
    for (unsigned int i = 0; i < im.n; ++i)
      v[i] = (2. / h) * (q[i] - q_old[i]) - v_old[i];
    t_previous = t;
    t          = (h == remaining) ? t_limit : t + h;
    count_step();
    check_finite();
  }



  std::vector<Counter>
  EnergyMomentum::counters() const
  {
    const Implementation &im = *implementation;
    return with_resumed_counts(
      {{"steps", steps},
       {"residual evaluations", im.residual_evaluations},
       {"newton iterations", im.newton_iterations},
       {"linear iterations", im.linear_solver.n_linear_iterations()},
       {"jacobian setups", im.linear_solver.n_setups()}});
  }


  namespace
  {
    std::unique_ptr<TimeIntegrator>
    create_energy_momentum(dealii::ParameterHandler &prm,
                           const MechanicalSystem   &system)
    {
      const ImplicitParameters parameters = parse_implicit_parameters(prm);
      require_resolvable_time_step(prm,
                                   "Implicit integrators/Time step",
                                   parameters.time_step);
      const auto *body = dynamic_cast<const ElasticBody *>(&system);
      if (body == nullptr)
        throw std::invalid_argument(
          "Time integration/Method = energy momentum works on a single "
          "elastic body, and the system <" +
          system.name() + "> is not one.");
      return std::make_unique<EnergyMomentum>(*body,
                                              parameters,
                                              parameters.time_step);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_INTEGRATOR(
  "energy momentum",
  "a discrete-gradient energy-momentum scheme of one elastic body, solved by "
  "SUNDIALS KINSOL at the fixed time step (subsection Implicit "
  "integrators).",
  estep::declare_implicit_parameters,
  estep::create_energy_momentum)
