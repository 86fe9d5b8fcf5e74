// The cost of an energy-stepping step on the spinning cube (12,288
// cells), as ratios taken in one run: step / gradient evaluation, step /
// free-flight value evaluation, and the work counted per step (point
// evaluations and enclosures along the flight, gradients).
//
// Usage: build/benchmarks/benchmark_time_integration_spinning_cube [end time,
// default 8]
#include <deal.II/grid/tria.h>

#include <estep/fem/elastic_body.h>
#include <estep/fem/meshes.h>
#include <estep/materials/neo_hookean.h>
#include <estep/time_integration/energy_stepping.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace
{
  template <typename Work>
  double
  seconds_per_call(const unsigned int n, Work &&work)
  {
    const auto start = std::chrono::steady_clock::now();
    for (unsigned int i = 0; i < n; ++i)
      work();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
             .count() /
           n;
  }
} // namespace

int
main(int argc, char **argv)
{
  const double             end_time = argc > 1 ? std::atof(argv[1]) : 8.;
  dealii::Triangulation<3> tria;
  estep::make_seed_cube_mesh(tria, 8);
  const estep::ElasticBody body(
    tria, std::make_shared<estep::NeoHookean>(0.0100, 0.0066), 0.100, "cube");
  const estep::Vector q = body.reference_configuration();
  const estep::Vector v =
    body.rigid_velocity(q, {{0., 0., 0.}}, {{0., 0., 1.}}, {{0.5, 0.5, 0.5}});

  // An energy-stepping run, h = 1e-5.
  estep::EnergyStepping stepping(body, 1e-5);
  stepping.initialize(0., q, v);
  const auto start = std::chrono::steady_clock::now();
  while (stepping.time() < end_time)
    stepping.step(end_time);
  const double run_seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
      .count();
  const double n_steps = stepping.n_steps();

  // The unit costs, at the state the run ended in.
  estep::Vector g(q.size());
  const double  gradient =
    seconds_per_call(200, [&] { body.gradient(stepping.position(), g); });
  const auto flight =
    body.free_flight(stepping.position(), stepping.velocity());
  const double value = seconds_per_call(500, [&] { flight->value(1e-3); });
  const double enclose =
    seconds_per_call(100, [&] { flight->enclose(0., 1e-2); });
  const double build = seconds_per_call(100, [&] {
    body.free_flight(stepping.position(), stepping.velocity());
  });

  double evaluations = 0., enclosures = 0., gradients = 0.;
  for (const auto &[name, count] : stepping.counters())
    {
      if (name == "energy evaluations")
        evaluations = count;
      else if (name == "enclosures")
        enclosures = count;
      else if (name == "gradient evaluations")
        gradients = count;
    }
  const double step = run_seconds / n_steps;
  std::printf(
    "spinning cube, energy-stepping h = 1e-5 to t = %g: %.0f steps in %.3f s\n",
    end_time,
    n_steps,
    run_seconds);
  std::printf(
    "per cell: gradient %.1f ns, free-flight value %.1f ns, enclosure %.1f ns, "
    "building the flight %.1f ns\n",
    1e9 * gradient / body.n_cells(),
    1e9 * value / body.n_cells(),
    1e9 * enclose / body.n_cells(),
    1e9 * build / body.n_cells());
  std::printf(
    "one step = %.2f gradient evaluations = %.1f free-flight values\n",
    step / gradient,
    step / value);
  std::printf(
    "per step: %.2f point evaluations, %.2f enclosures, %.2f gradients\n",
    evaluations / n_steps,
    enclosures / n_steps,
    gradients / n_steps);
  return 0;
}
