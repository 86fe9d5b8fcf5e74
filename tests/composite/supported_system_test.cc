// Supports: a small neo-Hookean cube (2 x 2 x 2 hexahedra of 24 tets) with
// the points of its face x = 0 fixed, as a SupportedSystem. Gradient and
// Hessian against central differences, expand/restrict, observables; an
// energy-stepping run conserving the terraced energy with its flights on
// their terraces and the supports exactly in place; explicit Newmark and the
// implicit midpoint rule run through it; the errors.

#include <deal.II/grid/tria.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <estep/composite/supported_system.h>
#include <estep/fem/meshes.h>
#include <estep/fem/tangent_stiffness.h>
#include <estep/implicit/arkode_runge_kutta.h>
#include <estep/materials/neo_hookean.h>
#include <estep/time_integration/energy_stepping.h>
#include <estep/time_integration/explicit_newmark.h>
#include <estep/time_integration/time_loop.h>

#include <gtest/gtest.h>

#include "../terrace_audit.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using estep::SupportedSystem;
using estep::Vector;

namespace
{
  /** The cube [0, 1]^3, n = 2, with a Hessian; it tracks the points at the
   * centres of its faces x = 0 (fixed) and x = 1 (free). */
  std::shared_ptr<estep::ElasticBodyWithHessian>
  make_cube()
  {
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, 2);
    auto body = std::make_shared<estep::ElasticBodyWithHessian>(
      tria, std::make_shared<estep::NeoHookean>(0.0100, 0.0066), 0.100, "cube");
    body->track_point("support", {{0., 0.5, 0.5}});
    body->track_point("tip", {{1., 0.5, 0.5}});
    return body;
  }

  /** The points of @p body on the face x = 0. */
  std::vector<unsigned int>
  face_points(const estep::ElasticBody &body)
  {
    const Vector              X = body.reference_configuration();
    std::vector<unsigned int> points;
    for (unsigned int i = 0; i < body.n_vertices(); ++i)
      if (X[3 * i] == 0.)
        points.push_back(i);
    return points;
  }

  /** The cube clamped at x = 0 in its reference configuration (built once).
   */
  const SupportedSystem &
  clamped_cube()
  {
    static const auto system = []() {
      const auto body = make_cube();
      return std::make_shared<const SupportedSystem>(
        body, face_points(*body), body->reference_configuration());
    }();
    return *system;
  }

  const estep::ElasticBody &
  cube_of(const SupportedSystem &system)
  {
    return dynamic_cast<const estep::ElasticBody &>(system.base());
  }

  /** A random vector of length @p n with entries in [-amplitude, amplitude].
   */
  Vector
  random_vector(const unsigned int n,
                const double       amplitude,
                const unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    Vector                                 v(n);
    for (auto &x : v)
      x = u(rng);
    return v;
  }

  /** Free positions of a bent and stretched clamped cube: the free points
   * of X + (0.1 x^2 (0.3 - z), 0.05 x y, 0.2 x^2) plus noise of @p noise.
   */
  Vector
  deformed(const SupportedSystem &system, const double noise)
  {
    Vector       q = cube_of(system).reference_configuration();
    const Vector r = random_vector(q.size(), noise, 11);
    for (unsigned int i = 0; i < q.size() / 3; ++i)
      {
        const double x = q[3 * i], y = q[3 * i + 1], z = q[3 * i + 2];
        q[3 * i] += 0.1 * x * x * (0.3 - z) + r[3 * i];
        q[3 * i + 1] += 0.05 * x * y + r[3 * i + 1];
        q[3 * i + 2] += 0.2 * x * x + r[3 * i + 2];
      }
    return system.restrict(q);
  }

  /** Velocities of the free points: a swing of the free end, x (0, -0.1,
   * 0.2), plus noise. */
  Vector
  swinging(const SupportedSystem &system)
  {
    const Vector X = system.restrict(cube_of(system).reference_configuration());
    Vector       v = random_vector(X.size(), 0.02, 12);
    for (unsigned int k = 0; k < X.size() / 3; ++k)
      {
        v[3 * k + 1] -= 0.1 * X[3 * k];
        v[3 * k + 2] += 0.2 * X[3 * k];
      }
    return v;
  }

  /** Whether the fixed points of @p full sit exactly at their reference
   * positions (bit for bit). */
  bool
  supports_in_place(const SupportedSystem &system, const Vector &full)
  {
    const Vector X = cube_of(system).reference_configuration();
    for (const unsigned int i : system.fixed_points())
      for (unsigned int c = 0; c < 3; ++c)
        if (full[3 * i + c] != X[3 * i + c])
          return false;
    return true;
  }

  TEST(SupportedSystem, LayoutAndExpansion)
  {
    const SupportedSystem    &system = clamped_cube();
    const estep::ElasticBody &body   = cube_of(system);
    // 3 x 3 grid points and 4 face centres on the face x = 0.
    EXPECT_EQ(system.n_fixed_points(), 13u);
    EXPECT_EQ(system.n_dofs(), body.n_dofs() - 3 * 13);
    EXPECT_EQ(system.spatial_dimension(), 3u);
    EXPECT_EQ(system.fixed_points().size() + system.free_points().size(),
              body.n_vertices());
    EXPECT_TRUE(std::is_sorted(system.fixed_points().begin(),
                               system.fixed_points().end()));
    ASSERT_EQ(system.inverse_mass().size(), system.n_dofs());
    for (unsigned int k = 0; k < system.n_dofs(); ++k)
      EXPECT_EQ(system.inverse_mass()[k],
                body.inverse_mass()[3 * system.free_points()[k / 3] + k % 3]);

    // restrict(expand(q)) = q exactly; expand(restrict(full)) = full on the
    // free points and the supports' positions on the fixed ones.
    const Vector q = deformed(system, 1e-3);
    EXPECT_EQ(system.restrict(system.expand(q)), q);
    Vector full = body.reference_configuration();
    full.add(1., random_vector(full.size(), 0.1, 5));
    const Vector expanded = system.expand(system.restrict(full));
    EXPECT_TRUE(supports_in_place(system, expanded));
    for (const unsigned int i : system.free_points())
      for (unsigned int c = 0; c < 3; ++c)
        EXPECT_EQ(expanded[3 * i + c], full[3 * i + c]);
    const Vector v  = swinging(system);
    const Vector vf = system.expand_velocity(v);
    for (const unsigned int i : system.fixed_points())
      for (unsigned int c = 0; c < 3; ++c)
        EXPECT_EQ(vf[3 * i + c], 0.);
    EXPECT_EQ(system.restrict(vf), v);

    // Energy, flight and observables are the base's at the expanded state.
    EXPECT_EQ(system.energy(q), body.energy(system.expand(q)));
    EXPECT_GT(system.energy(q), 0.);
    const auto flight = system.free_flight(q, v);
    for (const double s : {0., 0.1, 0.5})
      {
        Vector qs = q;
        qs.add(s, v);
        EXPECT_NEAR(flight->value(s),
                    system.energy(qs),
                    1e-12 * system.energy(qs));
      }
    EXPECT_EQ(system.observable_names(), body.observable_names());
    const std::vector<double> observed = system.observables(q, v);
    const std::vector<double> expected =
      body.observables(system.expand(q), system.expand_velocity(v));
    EXPECT_EQ(observed, expected);
    ASSERT_EQ(observed.size(), 6u);
    EXPECT_EQ(observed[0], 0.); // the support's x
    EXPECT_NE(observed[3], 1.); // the tip's x moved
  }

  TEST(SupportedSystem, GradientMatchesCentralDifferences)
  {
    const SupportedSystem &system = clamped_cube();
    const Vector           q      = deformed(system, 1e-3);
    Vector                 g;
    system.gradient(q, g);
    ASSERT_EQ(g.size(), system.n_dofs());
    // Every component.
    const double d     = 1e-6;
    double       worst = 0.;
    Vector       qd    = q;
    for (unsigned int k = 0; k < q.size(); ++k)
      {
        qd[k]           = q[k] + d;
        const double Vp = system.energy(qd);
        qd[k]           = q[k] - d;
        const double Vm = system.energy(qd);
        qd[k]           = q[k];
        worst = std::max(worst, std::abs((Vp - Vm) / (2. * d) - g[k]));
      }
    worst /= g.linfty_norm();
    std::cout << "gradient vs central differences: worst error / max |g| "
              << worst << " (|g| max " << g.linfty_norm() << ")\n";
    RecordProperty("gradient_error", std::to_string(worst));
    EXPECT_LT(worst, 1e-6);
    // The supports carry reaction forces: the base's gradient on the fixed
    // points is not zero, so the restriction is not trivial.
    Vector full_g;
    cube_of(system).gradient(system.expand(q), full_g);
    double reaction = 0.;
    for (const unsigned int i : system.fixed_points())
      reaction = std::max(reaction, std::abs(full_g[3 * i]));
    EXPECT_GT(reaction, 1e-2 * g.linfty_norm());
  }

  TEST(SupportedSystem, HessianMatchesCentralDifferences)
  {
    const SupportedSystem &system = clamped_cube();
    ASSERT_TRUE(system.has_hessian());
    const dealii::SparsityPattern &pattern = system.hessian_sparsity();
    ASSERT_EQ(pattern.n_rows(), system.n_dofs());
    ASSERT_EQ(pattern.n_cols(), system.n_dofs());
    dealii::SparseMatrix<double> H(pattern);
    const Vector                 q = deformed(system, 1e-3);
    system.hessian(q, H);

    // Every column: H e_j against (g(q + d e_j) - g(q - d e_j)) / 2d.
    const unsigned int n = system.n_dofs();
    Vector             gp(n), gm(n), qd(q), column(n), e(n);
    const double       d         = 1e-6;
    double             max_error = 0., max_entry = 0., asymmetry = 0.;
    for (unsigned int j = 0; j < n; ++j)
      {
        qd[j] = q[j] + d;
        system.gradient(qd, gp);
        qd[j] = q[j] - d;
        system.gradient(qd, gm);
        qd[j] = q[j];
        e     = 0.;
        e[j]  = 1.;
        H.vmult(column, e);
        for (unsigned int i = 0; i < n; ++i)
          {
            max_error =
              std::max(max_error,
                       std::abs((gp[i] - gm[i]) / (2. * d) - column[i]));
            max_entry = std::max(max_entry, std::abs(column[i]));
            asymmetry = std::max(asymmetry, std::abs(H.el(i, j) - H.el(j, i)));
          }
      }
    std::cout << "Hessian vs central differences: worst error / max entry "
              << max_error / max_entry << ", asymmetry " << asymmetry << "\n";
    RecordProperty("hessian_error", std::to_string(max_error / max_entry));
    EXPECT_LT(max_error, 1e-6 * max_entry);
    EXPECT_LT(asymmetry, 1e-14 * max_entry);

    // A matrix of another pattern is refused.
    dealii::SparseMatrix<double> wrong(cube_of(system).hessian_sparsity());
    EXPECT_THROW(system.hessian(q, wrong), std::invalid_argument);
  }

  /** Checks every step of an energy-stepping run: terraced energy, terrace
   * audit, supports. */
  struct SteppingAudit : public estep::RunObserver
  {
    SteppingAudit(const SupportedSystem &system, const estep::EnergyStepping &s)
      : system(system)
      , stepping(s)
    {}

    void
    after_step(const estep::TimeIntegrator &) override
    {
      energy_error = std::max(energy_error,
                              std::abs(stepping.terraced_energy() -
                                       stepping.initial_terraced_energy()) /
                                std::abs(stepping.initial_terraced_energy()));
      excursion =
        std::max(excursion, estep_test::terrace_excursion(stepping, 16));
      supports &= supports_in_place(system, system.expand(stepping.position()));
    }

    const SupportedSystem       &system;
    const estep::EnergyStepping &stepping;
    double                       energy_error = 0., excursion = -1.;
    bool                         supports = true;
  };

  TEST(SupportedSystem, EnergySteppingConservesTerracedEnergy)
  {
    const SupportedSystem &system = clamped_cube();
    const Vector           q0     = deformed(system, 1e-3);
    const Vector           v0     = swinging(system);
    const double E0 = estep::kinetic_energy(system, v0) + system.energy(q0);
    const double h  = 5e-3 * E0;
    estep::EnergyStepping stepping(system, h);
    stepping.initialize(0., q0, v0);
    estep::TimeLoopSettings settings;
    settings.end_time        = 10.;
    settings.output_interval = 0.5;
    SteppingAudit audit(system, stepping);
    const auto    result = estep::run_time_loop(stepping, settings, {&audit});
    ASSERT_EQ(result.status, estep::RunStatus::completed) << result.message;
    std::cout << "energy stepping, h = " << h << " (E0 = " << E0
              << "): " << stepping.n_steps() << " steps; terraced energy drift "
              << audit.energy_error << ", largest excursion beyond a level "
              << audit.excursion << " h\n";
    for (const auto &c : stepping.counters())
      std::cout << "  " << c.first << ": " << c.second << "\n";
    RecordProperty("steps", std::to_string(stepping.n_steps()));
    RecordProperty("energy_drift", std::to_string(audit.energy_error));
    EXPECT_GT(stepping.n_steps(), 200u);
    EXPECT_LT(stepping.n_steps(), 1000u);
    EXPECT_LT(audit.energy_error, 1e-12);
    EXPECT_LT(audit.excursion, 1e-8);
    EXPECT_TRUE(audit.supports);
    // The final state: supports exactly in place, the rest moved.
    const Vector q_end = system.expand(stepping.position());
    EXPECT_TRUE(supports_in_place(system, q_end));
    Vector dq = stepping.position();
    dq -= q0;
    EXPECT_GT(dq.linfty_norm(), 1e-2);
    // The flights climbed and descended terraces.
    for (const auto &c : stepping.counters())
      {
        if (c.first == "climbs" || c.first == "descents")
          {
            EXPECT_GT(c.second, 50u) << c.first;
          }
      }
  }

  /** Energy at every output time and supports checked after every step. */
  struct EnergyRecord : public estep::RunObserver
  {
    explicit EnergyRecord(const SupportedSystem &system)
      : system(system)
    {}

    void
    observe(const estep::Snapshot &s) override
    {
      energy.push_back(s.kinetic_energy + s.potential_energy);
    }

    void
    after_step(const estep::TimeIntegrator &integrator) override
    {
      supports &=
        supports_in_place(system, system.expand(integrator.position()));
    }

    double
    drift() const
    {
      double d = 0.;
      for (const double e : energy)
        d = std::max(d, std::abs(e - energy.front()));
      return d / std::abs(energy.front());
    }

    const SupportedSystem &system;
    std::vector<double>    energy;
    bool                   supports = true;
  };

  TEST(SupportedSystem, ExplicitNewmarkRuns)
  {
    const SupportedSystem &system = clamped_cube();
    estep::ExplicitNewmark integrator(system, 0.01);
    integrator.initialize(0., deformed(system, 1e-3), swinging(system));
    estep::TimeLoopSettings settings;
    settings.end_time        = 2.;
    settings.output_interval = 0.1;
    EnergyRecord record(system);
    const auto   result = estep::run_time_loop(integrator, settings, {&record});
    ASSERT_EQ(result.status, estep::RunStatus::completed) << result.message;
    std::cout << "explicit Newmark, dt = 0.01: " << integrator.n_steps()
              << " steps, energy drift " << record.drift() << "\n";
    EXPECT_EQ(integrator.n_steps(), 200u);
    EXPECT_LT(record.drift(), 1e-4);
    EXPECT_TRUE(record.supports);
  }

  TEST(SupportedSystem, ImplicitMidpointRuns)
  {
    const SupportedSystem    &system = clamped_cube();
    estep::ImplicitParameters parameters;
    parameters.newton_tolerance = 1e-10;
    estep::ArkodeRungeKutta integrator(
      system, parameters, estep::ArkodeRungeKutta::Method::midpoint, 0.05);
    integrator.initialize(0., deformed(system, 1e-3), swinging(system));
    estep::TimeLoopSettings settings;
    settings.end_time        = 2.;
    settings.output_interval = 0.1;
    EnergyRecord record(system);
    const auto   result = estep::run_time_loop(integrator, settings, {&record});
    ASSERT_EQ(result.status, estep::RunStatus::completed) << result.message;
    std::cout << "implicit midpoint, dt = 0.05: " << integrator.n_steps()
              << " steps, energy drift " << record.drift() << "\n";
    for (const auto &c : integrator.counters())
      std::cout << "  " << c.first << ": " << c.second << "\n";
    EXPECT_EQ(integrator.n_steps(), 40u);
    EXPECT_LT(record.drift(), 1e-4);
    EXPECT_TRUE(record.supports);
  }

  /** The message of the std::invalid_argument thrown by @p f ("" if none). */
  template <typename F>
  std::string
  invalid_argument_message(const F &f)
  {
    try
      {
        f();
      }
    catch (const std::invalid_argument &e)
      {
        return e.what();
      }
    return "";
  }

  TEST(SupportedSystem, Errors)
  {
    const auto         body = make_cube();
    const Vector       X    = body->reference_configuration();
    const unsigned int n    = body->n_vertices();

    const std::string out_of_range = invalid_argument_message([&]() {
      const SupportedSystem s(body, {0, 3, n}, X);
    });
    std::cout << out_of_range << "\n";
    EXPECT_NE(out_of_range.find("out of range"), std::string::npos);
    EXPECT_NE(out_of_range.find(std::to_string(n)), std::string::npos);

    std::vector<unsigned int> all(n);
    for (unsigned int i = 0; i < n; ++i)
      all[i] = n - 1 - i;
    const std::string nothing_free = invalid_argument_message(
      [&]() { const SupportedSystem s(body, all, X); });
    std::cout << nothing_free << "\n";
    EXPECT_NE(nothing_free.find("free"), std::string::npos);

    const std::string wrong_size = invalid_argument_message(
      [&]() { const SupportedSystem s(body, {0}, Vector(X.size() - 3)); });
    EXPECT_NE(wrong_size.find("configuration"), std::string::npos);

    EXPECT_THROW(const SupportedSystem s(nullptr, {0}, X),
                 std::invalid_argument);

    // Unsorted with repetitions is accepted; one point free is enough.
    all.pop_back();
    all.push_back(3);
    const SupportedSystem one_free(body, all, X);
    EXPECT_EQ(one_free.n_fixed_points(), n - 1);
    EXPECT_EQ(one_free.n_dofs(), 3u);
    EXPECT_EQ(one_free.free_points(), std::vector<unsigned int>{0});

    // Vectors of the wrong size.
    const SupportedSystem &system = clamped_cube();
    EXPECT_THROW(system.energy(X), std::invalid_argument);
    EXPECT_THROW(system.restrict(Vector(3)), std::invalid_argument);
  }
} // namespace
