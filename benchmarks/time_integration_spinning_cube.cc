// The cost of an energy-stepping step on the spinning cube of the reference
// text (12,288 cells), against explicit Newmark, as ratios taken in one run:
// - energy-stepping, h = 1e-5, and Newmark, dt = 0.0082 (about as many steps),
//   both to the end time, alternating, the fastest of the repetitions;
// - one energy-stepping step in gradient evaluations and in free-flight
//   values, and the work counted per step;
// - the per-cell costs of each unit (gradient, value, enclosure, building a
//   flight) and of a step of each method.
//
// Usage: build/benchmarks/benchmark_time_integration_spinning_cube
//          [end time, default 20] [threads, default 1] [repetitions, 3]
// The instruction set of the cell kernels is the build's (ESTEP_SIMD, see
// doc/building_and_testing.md); the first line names it.
#include <deal.II/grid/tria.h>

#include <estep/base/lanes.h>
#include <estep/base/parallel_blocks.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/meshes.h>
#include <estep/materials/batch_log.h>
#include <estep/materials/neo_hookean.h>
#include <estep/time_integration/energy_stepping.h>
#include <estep/time_integration/explicit_newmark.h>

#include "seconds_since.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace
{
  using benchmark_timing::seconds_since;

  template <typename Work>
  double
  seconds_per_call(const unsigned int n, Work &&work)
  {
    const auto start = std::chrono::steady_clock::now();
    for (unsigned int i = 0; i < n; ++i)
      work();
    return seconds_since(start) / n;
  }

  /** Seconds of the time loop of @p integrator from (q, v) to @p end_time. */
  double
  run(estep::TimeIntegrator &integrator,
      const estep::Vector   &q,
      const estep::Vector   &v,
      const double           end_time)
  {
    integrator.initialize(0., q, v);
    const auto start = std::chrono::steady_clock::now();
    while (integrator.time() < end_time)
      integrator.step(end_time);
    return seconds_since(start);
  }
} // namespace

int
main(int argc, char **argv)
{
  const double       end_time    = argc > 1 ? std::atof(argv[1]) : 20.;
  const unsigned int threads     = argc > 2 ? std::atoi(argv[2]) : 1;
  const unsigned int repetitions = argc > 3 ? std::atoi(argv[3]) : 3;
  estep::set_thread_count(threads);

  dealii::Triangulation<3> tria;
  estep::make_seed_cube_mesh(tria, 8);
  const estep::ElasticBody body(
    tria, std::make_shared<estep::NeoHookean>(0.0100, 0.0066), 0.100, "cube");
  const estep::Vector q = body.reference_configuration();
  const estep::Vector v =
    body.rigid_velocity(q, {{0., 0., 0.}}, {{0., 0., 1.}}, {{0.5, 0.5, 0.5}});

  // Fresh integrators for each repetition (their counters add up over
  // initialisations); the last ones are kept for the counts.
  std::unique_ptr<estep::EnergyStepping>  stepping;
  std::unique_ptr<estep::ExplicitNewmark> newmark;
  double stepping_seconds = 1e300, newmark_seconds = 1e300;
  for (unsigned int r = 0; r < repetitions; ++r)
    {
      stepping = std::make_unique<estep::EnergyStepping>(body, 1e-5);
      newmark  = std::make_unique<estep::ExplicitNewmark>(body, 0.0082);
      stepping_seconds =
        std::min(stepping_seconds, run(*stepping, q, v, end_time));
      newmark_seconds =
        std::min(newmark_seconds, run(*newmark, q, v, end_time));
    }

  // The unit costs, at the state the energy-stepping run ended in.
  estep::Vector g(q.size());
  const double  gradient =
    seconds_per_call(200, [&] { body.gradient(stepping->position(), g); });
  const auto flight =
    body.free_flight(stepping->position(), stepping->velocity());
  const double value = seconds_per_call(500, [&] { flight->value(1e-3); });
  const double enclose =
    seconds_per_call(100, [&] { flight->enclose(0., 1e-2); });
  const double build = seconds_per_call(100, [&] {
    body.free_flight(stepping->position(), stepping->velocity());
  });

  double evaluations = 0., enclosures = 0., gradients = 0.;
  for (const auto &[name, count] : stepping->counters())
    {
      if (name == "energy evaluations")
        evaluations = count;
      else if (name == "enclosures")
        enclosures = count;
      else if (name == "gradient evaluations")
        gradients = count;
    }
  const double steps         = stepping->n_steps();
  const double newmark_steps = newmark->n_steps();
  const double step          = stepping_seconds / steps;
  const double newmark_step  = newmark_seconds / newmark_steps;
  const double ns_per_cell   = 1e9 / body.n_cells();
  std::printf("cell kernels: %s, logarithm: %s, %u thread(s), fastest of %u\n",
              estep::lane_kernel_target(),
              estep::batch_log_path(),
              estep::thread_count(),
              repetitions);
  std::printf("spinning cube to t = %g: energy-stepping h = 1e-5 %.0f steps "
              "in %.3f s, Newmark dt = 0.0082 %.0f steps in %.3f s\n",
              end_time,
              steps,
              stepping_seconds,
              newmark_steps,
              newmark_seconds);
  std::printf("energy-stepping / Newmark: run %.2f, step %.2f\n",
              stepping_seconds / newmark_seconds,
              step / newmark_step);
  std::printf("per cell: gradient %.1f ns, free-flight value %.1f ns, "
              "enclosure %.1f ns, building the flight %.1f ns; a step: "
              "energy-stepping %.1f ns, Newmark %.1f ns\n",
              gradient * ns_per_cell,
              value * ns_per_cell,
              enclose * ns_per_cell,
              build * ns_per_cell,
              step * ns_per_cell,
              newmark_step * ns_per_cell);
  std::printf("one energy-stepping step = %.2f gradient evaluations = %.1f "
              "free-flight values\n",
              step / gradient,
              step / value);
  std::printf("per step: %.2f point evaluations, %.2f enclosures, %.2f "
              "gradients\n",
              evaluations / steps,
              enclosures / steps,
              gradients / steps);
  return 0;
}
