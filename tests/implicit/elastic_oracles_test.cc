// The implicit integrators on a nonlinear system, the smallest cube mesh (24
// neo-Hookean tets) in a large-strain motion, against a converged reference
// computed by a different method (velocity Verlet at a tiny step); the
// energy-momentum scheme's discrete gradient against its defining identities;
// and the shifted stiffness solver against the matrix it claims to invert.
#include <deal.II/lac/sparse_matrix.h>

#include <estep/implicit/arkode_runge_kutta.h>
#include <estep/implicit/energy_momentum.h>
#include <estep/implicit/ida_bdf.h>
#include <estep/implicit/shifted_stiffness_solver.h>
#include <estep/time_integration/explicit_newmark.h>

#include <gtest/gtest.h>

#include "../fitted_slope.h"
#include "implicit_test_support.h"

#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace
{
  using estep::Vector;

  const estep::ElasticBodyWithHessian &
  tiny_cube()
  {
    static const auto body = estep_test::cube_with_hessian(1);
    return *body;
  }

  /**
   * The initial state: the reference configuration, spinning about z, with
   * a superposed stretching and shearing velocity field that strains the
   * cube by some 30 % within the first time units.
   */
  void
  initial_state(Vector &q0, Vector &v0)
  {
    const estep::ElasticBody &body = tiny_cube();
    q0                             = body.reference_configuration();
    v0                             = body.rigid_velocity(q0,
                             {{0.1, 0., 0.}},
                             {{0., 0., 1.}},
                             {{0.5, 0.5, 0.5}});
    for (unsigned int i = 0; i < q0.size(); i += 3)
      {
        const double x = q0[i] - 0.5, y = q0[i + 1] - 0.5, z = q0[i + 2] - 0.5;
        v0[i] += 0.3 * x + 0.2 * z;
        v0[i + 1] += -0.25 * y;
        v0[i + 2] += 0.35 * z - 0.15 * x;
      }
  }

  /** 1/2 v^T M v + V(q), with the kinetic energy summed here. */
  double
  total_energy(const Vector &q, const Vector &v)
  {
    double kinetic = 0.;
    for (unsigned int i = 0; i < v.size(); ++i)
      kinetic += 0.5 * v[i] * v[i] / tiny_cube().inverse_mass()[i];
    return kinetic + tiny_cube().energy(q);
  }

  /** The final state of @p integrator started from initial_state(). */
  struct FinalState
  {
    Vector q, v;
    /** Extremes of (E(t) - E(0)) / E(0) at the step ends. */
    double energy_min = 0., energy_max = 0.;
    /** max |Lz(t) - Lz(0)| / |Lz(0)| at the step ends. */
    double                      momentum_error = 0.;
    std::vector<estep::Counter> counters;
    double                      steps = 0.;
  };

  /**
   * Integrate from initial_state() to @p t_end; a run that needs more than
   * @p max_steps steps (a collapsing step size) fails.
   */
  FinalState
  integrate(estep::TimeIntegrator &integrator,
            const double           t_end,
            const double           max_steps = 2e4)
  {
    Vector q0, v0;
    initial_state(q0, v0);
    const double E0  = total_energy(q0, v0);
    const double Lz0 = estep::compute_momenta(tiny_cube(), q0, v0).angular[2];
    integrator.initialize(0., q0, v0);
    FinalState result;
    while (integrator.time() < t_end)
      {
        integrator.step(t_end);
        const double dE =
          (total_energy(integrator.position(), integrator.velocity()) - E0) /
          E0;
        result.energy_min = std::min(result.energy_min, dE);
        result.energy_max = std::max(result.energy_max, dE);
        const double Lz   = estep::compute_momenta(tiny_cube(),
                                                 integrator.position(),
                                                 integrator.velocity())
                            .angular[2];
        result.momentum_error =
          std::max(result.momentum_error, std::abs(Lz - Lz0) / std::abs(Lz0));
        if (integrator.n_steps() > max_steps)
          {
            ADD_FAILURE() << integrator.name() << ": more than " << max_steps
                          << " steps, stopped at t = " << integrator.time();
            break;
          }
        if (integrator.n_steps() % 100 == 0 &&
            estep_test::counter(integrator.counters(),
                                "newton convergence failures") > 50)
          {
            ADD_FAILURE() << integrator.name()
                          << ": more than 50 Newton convergence failures, "
                             "stopped at t = "
                          << integrator.time();
            break;
          }
      }
    EXPECT_EQ(integrator.time(), t_end);
    result.q        = integrator.position();
    result.v        = integrator.velocity();
    result.counters = integrator.counters();
    result.steps    = integrator.n_steps();
    return result;
  }

  constexpr double t_end = 4.;

  /** The reference motion: velocity Verlet with dt = 2.5e-4 (16,000 steps).
   */
  const FinalState &
  reference()
  {
    static const FinalState state = [] {
      estep::ExplicitNewmark newmark(tiny_cube(), 2.5e-4);
      return integrate(newmark, t_end, 1e5);
    }();
    return state;
  }

  /** max(|q - q_ref|_inf, |v - v_ref|_inf). */
  double
  distance_to_reference(const FinalState &s)
  {
    Vector dq = s.q, dv = s.v;
    dq -= reference().q;
    dv -= reference().v;
    return std::max(dq.linfty_norm(), dv.linfty_norm());
  }

  void
  print(const std::string &label, const FinalState &s)
  {
    std::cout << label << ": " << s.steps << " steps, error "
              << distance_to_reference(s) << ", energy error in ["
              << s.energy_min << ", " << s.energy_max
              << "], angular momentum error " << s.momentum_error
              << ", Newton iterations per step "
              << estep_test::counter(s.counters, "newton iterations") / s.steps
              << ", Jacobian setups "
              << estep_test::counter(s.counters, "jacobian setups") << '\n';
  }

  /** The motion is nonlinear (large strains) and the reference converged. */
  TEST(ElasticOracles, ReferenceMotionIsConvergedAndStrained)
  {
    estep::ExplicitNewmark newmark(tiny_cube(), 5e-4);
    const FinalState       coarser = integrate(newmark, t_end);
    // Velocity Verlet is second order: the reference's own error is about a
    // third of this difference.
    const double difference = distance_to_reference(coarser);
    std::cout << "reference: difference to dt = 5e-4 " << difference
              << ", energy error in [" << reference().energy_min << ", "
              << reference().energy_max << "]\n";
    EXPECT_LT(difference, 1e-6);
    Vector q0, v0;
    initial_state(q0, v0);
    EXPECT_GT(tiny_cube().energy(reference().q), 0.05 * total_energy(q0, v0));
  }

  /**
   * The energy-momentum scheme: second order against the reference, energy
   * and angular momentum conserved to the Newton tolerance, both ways.
   */
  TEST(ElasticOracles, EnergyMomentumIsSecondOrderAndConserves)
  {
    std::vector<double> steps, errors;
    for (const double dt : {0.2, 0.1, 0.05, 0.025})
      {
        estep::ImplicitParameters parameters;
        parameters.newton_tolerance = 1e-11;
        estep::EnergyMomentum integrator(tiny_cube(), parameters, dt);
        const FinalState      s = integrate(integrator, t_end);
        print("energy momentum, dt " + std::to_string(dt), s);
        steps.push_back(dt);
        errors.push_back(distance_to_reference(s));
        EXPECT_LT(s.energy_max, 1e-9);
        EXPECT_GT(s.energy_min, -1e-9);
        EXPECT_LT(s.momentum_error, 1e-9);
        EXPECT_LE(estep_test::counter(s.counters, "newton iterations"),
                  6. * s.steps);
      }
    const double order = estep_test::fitted_slope(steps, errors);
    std::cout << "energy momentum: observed order " << order << '\n';
    EXPECT_GT(order, 1.8);
    EXPECT_LT(order, 2.2);
    EXPECT_LT(errors.back(), 2e-3);
  }

  /**
   * The implicit midpoint rule on the nonlinear body: second order, the
   * energy error O(dt^2) both ways (bounded, no drift), angular momentum (a
   * quadratic invariant) conserved, the Newton matrix set up every
   * jacobian_update_interval steps and no Newton failure (but at the largest
   * step).
   */
  TEST(ElasticOracles, ArkodeMidpointIsSecondOrder)
  {
    std::vector<double> steps, errors;
    for (const double dt : {0.2, 0.1, 0.05, 0.025})
      {
        estep::ImplicitParameters parameters;
        parameters.newton_tolerance = 1e-11;
        estep::ArkodeRungeKutta integrator(
          tiny_cube(),
          parameters,
          estep::ArkodeRungeKutta::Method::midpoint,
          dt);
        const FinalState s = integrate(integrator, t_end);
        print("midpoint, dt " + std::to_string(dt), s);
        steps.push_back(dt);
        errors.push_back(distance_to_reference(s));
        EXPECT_LT(s.energy_max, 0.15 * dt * dt);
        EXPECT_GT(s.energy_min, -0.15 * dt * dt);
        EXPECT_LT(s.momentum_error, 1e-9);
        // At the largest step the Newton matrix of the last setup may go
        // stale: a failed iteration, retried with a fresh matrix.
        const std::uint64_t failures =
          estep_test::counter(s.counters, "newton convergence failures");
        EXPECT_LE(failures, dt > 0.1 ? 3u : 0u);
        EXPECT_LE(estep_test::counter(s.counters, "jacobian setups"),
                  s.steps / parameters.jacobian_update_interval + 1 + failures);
      }
    const double order = estep_test::fitted_slope(steps, errors);
    std::cout << "midpoint: observed order " << order << '\n';
    EXPECT_GT(order, 1.8);
    EXPECT_LT(order, 2.2);
    EXPECT_LT(errors.back(), 2e-3);
  }

  /**
   * IDA's BDF and ARKode's DIRK on the nonlinear body at the tolerances 1e-6
   * and 1e-8: the final state within a few hundred tolerances of the
   * reference and a hundred times closer at the tighter tolerance, energy
   * and angular momentum within stated bounds both ways, and Newton
   * converging fast (the Newton matrix follows the state).
   */
  TEST(ElasticOracles, AdaptiveMethodsMatchTheReference)
  {
    struct Method
    {
      std::string name;
      std::function<std::unique_ptr<estep::TimeIntegrator>(
        const estep::ImplicitParameters &)>
        create;
      /** Bounds of |E - E0| / E0 and of the angular momentum error at 1e-6,
       * Newton iterations per step. */
      double energy_bound, energy_growth, momentum_bound, newton_per_step;
    };
    const std::vector<Method> methods = {
      {"ida",
       [](const estep::ImplicitParameters &parameters) {
         return std::unique_ptr<estep::TimeIntegrator>(
           std::make_unique<estep::IdaBdf>(tiny_cube(), parameters, 1e-3));
       },
       2e-5,
       2e-5,
       5e-5,
       3.},
      {"dirk",
       [](const estep::ImplicitParameters &parameters) {
         return std::unique_ptr<estep::TimeIntegrator>(
           std::make_unique<estep::ArkodeRungeKutta>(
             tiny_cube(),
             parameters,
             estep::ArkodeRungeKutta::Method::dirk,
             1e-3));
       },
       2e-4,
       1e-10,
       1e-4,
       11.}};
    for (const Method &method : methods)
      {
        std::vector<double> errors;
        for (const double tolerance : {1e-6, 1e-8})
          {
            estep::ImplicitParameters parameters;
            parameters.relative_tolerance = tolerance;
            parameters.absolute_tolerance = tolerance;
            const auto       integrator   = method.create(parameters);
            const FinalState s            = integrate(*integrator, t_end);
            print(method.name + ", tolerance " + std::to_string(tolerance), s);
            errors.push_back(distance_to_reference(s));
            EXPECT_LT(errors.back(), 300. * tolerance) << method.name;
            // The bounds at 1e-6 hold at 1e-8 a fortiori.
            EXPECT_GT(s.energy_min, -method.energy_bound) << method.name;
            EXPECT_LT(s.energy_max, method.energy_growth) << method.name;
            EXPECT_LT(s.momentum_error, method.momentum_bound) << method.name;
            EXPECT_LE(estep_test::counter(s.counters, "newton iterations"),
                      method.newton_per_step * s.steps)
              << method.name;
          }
        EXPECT_GT(errors[0] / errors[1], 30.) << method.name;
      }
  }

  /**
   * A configuration of the tiny cube far from its reference state: a finite
   * rotation and stretch of the reference positions plus random noise of
   * amplitude @p noise (every cell stays positive).
   */
  Vector
  deformed_configuration(const double noise, const unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-noise, noise);
    Vector q = tiny_cube().reference_configuration();
    for (unsigned int i = 0; i < q.size(); i += 3)
      {
        const double x = q[i], y = q[i + 1], z = q[i + 2];
        q[i]     = 0.8 * x - 0.6 * y + u(rng);
        q[i + 1] = 0.6 * x + 0.8 * y + 0.1 * z + u(rng);
        q[i + 2] = 1.2 * z + u(rng);
      }
    return q;
  }

  /** On the diagonal the discrete gradient is the gradient. */
  TEST(DiscreteGradient, IsTheGradientOnTheDiagonal)
  {
    const estep::EnergyMomentum scheme(tiny_cube(), {}, 0.1);
    const Vector                q = deformed_configuration(0.05, 1);
    Vector                      f, g;
    scheme.discrete_gradient(q, q, f);
    tiny_cube().gradient(q, g);
    f -= g;
    EXPECT_LT(f.linfty_norm(), 1e-12 * g.linfty_norm());
  }

  /**
   * The defining identities of the discrete gradient for two distant
   * configurations: the chain rule f . (q1 - q0) = V(q1) - V(q0) (which
   * makes the scheme conserve energy), no net force, and no net torque about
   * the origin at the midpoint configuration (which makes it conserve linear
   * and angular momentum).
   */
  TEST(DiscreteGradient, SatisfiesTheDiscreteChainRuleAndBalances)
  {
    const estep::EnergyMomentum scheme(tiny_cube(), {}, 0.1);
    for (const unsigned int seed : {2u, 3u, 4u})
      {
        const Vector q0 = tiny_cube().reference_configuration();
        const Vector q1 = deformed_configuration(0.04, seed);
        for (const auto &[a, b] : {std::pair{&q0, &q1}, std::pair{&q1, &q0}})
          {
            Vector f;
            scheme.discrete_gradient(*a, *b, f);
            Vector dq = *b;
            dq -= *a;
            const double dV = tiny_cube().energy(*b) - tiny_cube().energy(*a);
            EXPECT_NEAR(f * dq, dV, 1e-12 * std::abs(dV) + 1e-15)
              << "seed " << seed;
            double force[3] = {0., 0., 0.}, torque[3] = {0., 0., 0.};
            for (unsigned int i = 0; i < f.size(); i += 3)
              {
                double x[3];
                for (unsigned int c = 0; c < 3; ++c)
                  {
                    force[c] += f[i + c];
                    x[c] = 0.5 * ((*a)[i + c] + (*b)[i + c]);
                  }
                torque[0] += x[1] * f[i + 2] - x[2] * f[i + 1];
                torque[1] += x[2] * f[i] - x[0] * f[i + 2];
                torque[2] += x[0] * f[i + 1] - x[1] * f[i];
              }
            for (unsigned int c = 0; c < 3; ++c)
              {
                EXPECT_NEAR(force[c], 0., 1e-13 * f.linfty_norm());
                EXPECT_NEAR(torque[c], 0., 1e-13 * f.linfty_norm());
              }
          }
      }
  }

  /**
   * Consistency: f(q - d/2, q + d/2) - grad V(q) = O(|d|^2), the midpoint
   * gradient to second order (halving d divides the difference by 4).
   */
  TEST(DiscreteGradient, ApproximatesTheMidpointGradientToSecondOrder)
  {
    const estep::EnergyMomentum scheme(tiny_cube(), {}, 0.1);
    const Vector                q = deformed_configuration(0.03, 5);
    const Vector                w = estep_test::random_direction(q.size(), 6);
    Vector                      g;
    tiny_cube().gradient(q, g);
    std::vector<double> differences;
    for (const double s : {0.04, 0.02, 0.01})
      {
        Vector q0 = q, q1 = q, f;
        q0.add(-0.5 * s, w);
        q1.add(0.5 * s, w);
        scheme.discrete_gradient(q0, q1, f);
        f -= g;
        differences.push_back(f.linfty_norm());
      }
    for (unsigned int k = 1; k < differences.size(); ++k)
      {
        const double ratio = differences[k - 1] / differences[k];
        std::cout << "discrete gradient: difference ratio " << ratio << '\n';
        EXPECT_GT(ratio, 3.5);
        EXPECT_LT(ratio, 4.5);
      }
  }

  /** The Newton solves: S x = b with S = a M + H(q) assembled here. */
  TEST(ShiftedStiffnessSolver, SolvesWithTheShiftedStiffness)
  {
    const estep::ElasticBodyWithHessian &body = tiny_cube();
    estep::ShiftedStiffnessSolver        solver(body, {});
    const Vector                         q = deformed_configuration(0.03, 7);
    dealii::SparseMatrix<double>         H(body.hessian_sparsity());
    body.hessian(q, H);
    const Vector b = estep_test::random_direction(q.size(), 8);
    Vector       x(q.size()), Sx(q.size());
    solver.setup(q, 40.);
    for (const double a : {40., 3.})
      {
        if (a != 40.)
          solver.reshift(a);
        EXPECT_EQ(solver.shift(), a);
        solver.solve(b, x);
        H.vmult(Sx, x);
        for (unsigned int i = 0; i < q.size(); ++i)
          Sx[i] += a / body.inverse_mass()[i] * x[i];
        Sx -= b;
        EXPECT_LT(Sx.linfty_norm(), 1e-10 * b.linfty_norm()) << "a = " << a;
      }
    EXPECT_EQ(solver.n_setups(), 2u);
    EXPECT_EQ(solver.n_solves(), 2u);
  }
} // namespace
