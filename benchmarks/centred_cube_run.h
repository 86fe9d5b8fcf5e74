// What the parallel benchmarks share: energy-stepping (h = 1e-5) of the
// spinning cube of the reference text rotating about its centre, timed, and
// the comparison of two final states to the last bit.
#ifndef estep_benchmarks_centred_cube_run_h
#define estep_benchmarks_centred_cube_run_h

#include <estep/fem/elastic_body.h>
#include <estep/time_integration/energy_stepping.h>

#include <chrono>
#include <cstring>

namespace benchmark_cube
{
  struct Run
  {
    double        seconds;
    unsigned int  steps;
    double        time;
    estep::Vector q, v;
  };

  /** Energy-stepping of @p body from the centred rotation to @p end_time or
   * @p max_steps steps, whichever comes first. */
  inline Run
  run(const estep::ElasticBody &body,
      const double              end_time,
      const unsigned int        max_steps)
  {
    const estep::Vector q = body.reference_configuration();
    const estep::Vector v =
      body.rigid_velocity(q, {{0., 0., 0.}}, {{0., 0., 1.}}, {{0.5, 0.5, 0.5}});
    estep::EnergyStepping stepping(body, 1e-5);
    stepping.initialize(0., q, v);
    const auto start = std::chrono::steady_clock::now();
    while (stepping.time() < end_time && stepping.n_steps() < max_steps)
      stepping.step(end_time);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
        .count();
    return {seconds,
            static_cast<unsigned int>(stepping.n_steps()),
            stepping.time(),
            stepping.position(),
            stepping.velocity()};
  }

  /** Whether two runs ended in the same state, to the last bit. */
  inline bool
  same_end(const Run &a, const Run &b)
  {
    const auto same = [](const estep::Vector &x, const estep::Vector &y) {
      return x.size() == y.size() &&
             std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
    };
    return a.steps == b.steps && same(a.q, b.q) && same(a.v, b.v);
  }
} // namespace benchmark_cube

#endif
