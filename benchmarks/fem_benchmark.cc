// Cost per cell of the elastic body's hot loops on the spinning cube (n = 8,
// 12,288 cells): energy + gradient, free-flight value, value and slope,
// enclose(), building the free-flight view and its admissible limit. Prints the
// counts, T0 and Lz of the spinning cube first.
#include <deal.II/grid/tria.h>

#include <estep/fem/elastic_body.h>
#include <estep/fem/elastic_free_flight.h>
#include <estep/fem/meshes.h>
#include <estep/materials/batch_log.h>
#include <estep/materials/neo_hookean.h>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <random>

namespace
{
  struct Setup
  {
    std::unique_ptr<estep::ElasticBody> body;
    estep::Vector                       q, v;

    Setup()
    {
      dealii::Triangulation<3> tria;
      estep::make_seed_cube_mesh(tria, 8);
      body = std::make_unique<estep::ElasticBody>(
        tria,
        std::make_shared<estep::NeoHookean>(0.0100, 0.0066),
        0.100,
        "cube");
      q            = body->reference_configuration();
      v            = body->rigid_velocity(q,
                               {{0., 0., 0.}},
                               {{0., 0., 1.}},
                               {{0.5, 0.5, 0.5}});
      const auto p = estep::compute_momenta(*body, q, v);
      std::printf(
        "spinning cube: %u cells, %u vertices, T0 = %.6e, Lz = %.7e, log path: %s\n",
        body->n_cells(),
        body->n_vertices(),
        estep::kinetic_energy(*body, v),
        p.angular[2],
        estep::batch_log_path());
      // A deformed state with some elastic velocity on top of the spin.
      std::mt19937                           rng(1);
      std::uniform_real_distribution<double> u(-1., 1.);
      for (unsigned int k = 0; k < q.size(); ++k)
        {
          q[k] += 0.004 * u(rng);
          v[k] += 0.05 * u(rng);
        }
    }
  };

  Setup &
  setup()
  {
    static Setup s;
    return s;
  }

  void
  per_cell(benchmark::State &state)
  {
    state.counters["ns_per_cell"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * setup().body->n_cells(),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  }

  void
  energy_and_gradient(benchmark::State &state)
  {
    auto         &s = setup();
    estep::Vector g(s.q.size());
    for (auto _ : state)
      {
        benchmark::DoNotOptimize(s.body->energy(s.q));
        s.body->gradient(s.q, g);
        benchmark::DoNotOptimize(g.data());
      }
    per_cell(state);
  }
  BENCHMARK(energy_and_gradient)->Unit(benchmark::kMicrosecond);

  void
  energy_only(benchmark::State &state)
  {
    auto &s = setup();
    for (auto _ : state)
      benchmark::DoNotOptimize(s.body->energy(s.q));
    per_cell(state);
  }
  BENCHMARK(energy_only)->Unit(benchmark::kMicrosecond);

  void
  free_flight_build(benchmark::State &state)
  {
    auto &s = setup();
    for (auto _ : state)
      benchmark::DoNotOptimize(s.body->free_flight(s.q, s.v));
    per_cell(state);
  }
  BENCHMARK(free_flight_build)->Unit(benchmark::kMicrosecond);

  void
  free_flight_value(benchmark::State &state)
  {
    auto      &s      = setup();
    const auto flight = s.body->free_flight(s.q, s.v);
    double     t      = 0.;
    for (auto _ : state)
      {
        benchmark::DoNotOptimize(flight->value(t));
        t += 1e-6;
      }
    per_cell(state);
  }
  BENCHMARK(free_flight_value)->Unit(benchmark::kMicrosecond);

  void
  free_flight_value_and_derivative(benchmark::State &state)
  {
    auto      &s      = setup();
    const auto flight = s.body->free_flight(s.q, s.v);
    double     t      = 0.;
    for (auto _ : state)
      {
        benchmark::DoNotOptimize(flight->value_and_derivative(t));
        t += 1e-6;
      }
    per_cell(state);
  }
  BENCHMARK(free_flight_value_and_derivative)->Unit(benchmark::kMicrosecond);

  void
  free_flight_enclose(benchmark::State &state)
  {
    auto      &s      = setup();
    const auto flight = s.body->free_flight(s.q, s.v);
    flight->enclose(0., 0.01); // precomputes the critical points
    double t = 0.;
    for (auto _ : state)
      {
        benchmark::DoNotOptimize(flight->enclose(t, t + 0.01));
        t += 1e-6;
      }
    per_cell(state);
  }
  BENCHMARK(free_flight_enclose)->Unit(benchmark::kMicrosecond);

  void
  free_flight_admissible_limit(benchmark::State &state)
  {
    auto &s = setup();
    for (auto _ : state)
      {
        const auto flight = s.body->free_flight(s.q, s.v);
        benchmark::DoNotOptimize(flight->admissible_limit());
      }
    per_cell(state);
  }
  BENCHMARK(free_flight_admissible_limit)->Unit(benchmark::kMicrosecond);
} // namespace

BENCHMARK_MAIN();
