// Shared helpers of the tests of the implicit integrators: the spinning cube
// with a Hessian and a run to a final time that records energy and momentum.
#ifndef estep_tests_implicit_implicit_test_support_h
#define estep_tests_implicit_implicit_test_support_h

#include <deal.II/grid/tria.h>

#include <estep/fem/meshes.h>
#include <estep/fem/tangent_stiffness.h>
#include <estep/materials/neo_hookean.h>
#include <estep/time_integration/time_loop.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace estep_test
{
  /** The spinning-cube body (n^3 hexahedra of 24 tets) with a Hessian.
   */
  inline std::unique_ptr<estep::ElasticBodyWithHessian>
  cube_with_hessian(const unsigned int n)
  {
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, n);
    return std::make_unique<estep::ElasticBodyWithHessian>(
      tria, std::make_shared<estep::NeoHookean>(0.0100, 0.0066), 0.100, "cube");
  }

  /** Energy and angular momentum at the output times of a run. */
  struct Record : public estep::RunObserver
  {
    explicit Record(const estep::MechanicalSystem &system)
      : system(system)
    {}

    void
    observe(const estep::Snapshot &s) override
    {
      t.push_back(s.t);
      energy.push_back(s.kinetic_energy + s.potential_energy);
      const auto m = estep::compute_momenta(system, s.q, s.v);
      Lz.push_back(m.angular[2]);
      Lx.push_back(m.angular[0]);
      Px.push_back(m.linear[0]);
    }

    /** max |E(t) - E(0)| / E(0). */
    double
    energy_drift() const
    {
      double d = 0.;
      for (const double e : energy)
        d = std::max(d, std::abs(e - energy.front()));
      return d / std::abs(energy.front());
    }

    /** max |Lz(t) - Lz(0)| / |Lz(0)|. */
    double
    angular_momentum_drift() const
    {
      double d = 0.;
      for (const double l : Lz)
        d = std::max(d, std::abs(l - Lz.front()));
      return d / std::abs(Lz.front());
    }

    const estep::MechanicalSystem &system;
    std::vector<double>            t, energy, Lz, Lx, Px;
  };

  /** The result of run_cube(). */
  struct CubeRun
  {
    estep::TimeLoopResult       result;
    std::vector<estep::Counter> counters;
    double                      energy_drift, momentum_drift;
    double                      E0, E_end;
    double                      wall_seconds;
  };

  /** Spin the cube about z (omega0 = 1) and integrate to @p t_end. */
  inline CubeRun
  run_cube(const estep::ElasticBodyWithHessian &body,
           estep::TimeIntegrator               &integrator,
           const double                         t_end,
           const double                         output_interval = 0.5)
  {
    const estep::Vector q0 = body.reference_configuration();
    const estep::Vector v0 = body.rigid_velocity(q0,
                                                 {{0., 0., 0.}},
                                                 {{0., 0., 1.}},
                                                 {{0.5, 0.5, 0.5}});
    integrator.initialize(0., q0, v0);
    estep::TimeLoopSettings settings;
    settings.start_time      = 0.;
    settings.end_time        = t_end;
    settings.output_interval = output_interval;
    Record     record(body);
    const auto start = std::chrono::steady_clock::now();
    CubeRun    run;
    run.result = estep::run_time_loop(integrator, settings, {&record});
    run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    run.counters       = integrator.counters();
    run.energy_drift   = record.energy_drift();
    run.momentum_drift = record.angular_momentum_drift();
    run.E0             = record.energy.front();
    run.E_end          = record.energy.back();
    return run;
  }

  /** A random vector of length @p n with entries in [-1, 1]. */
  inline estep::Vector
  random_direction(const unsigned int n, const unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-1., 1.);
    estep::Vector                          w(n);
    for (auto &x : w)
      x = u(rng);
    return w;
  }

  /** The value of the counter @p name. */
  inline std::uint64_t
  counter(const std::vector<estep::Counter> &counters, const std::string &name)
  {
    for (const auto &c : counters)
      if (c.first == name)
        return c.second;
    return 0;
  }
} // namespace estep_test

#endif
