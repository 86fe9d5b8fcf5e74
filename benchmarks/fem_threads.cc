// Energy-stepping on several threads: the centred spinning cube (h = 1e-5)
// at 1,536, 12,288, 98,304 and 786,432 cells, each run on 1 thread and on
// every thread of the machine (or the number given), in one run of this
// program, each three times in turn (the fastest of the three counts). Printed
// per size: the steps, the wall time per step and per step
// and cell on each thread count, their ratio (the speedup), and whether the
// two runs ended in the same state to the last bit. Then the same for a
// ball meshed by gmsh (mesh size 0.05, 152,424 cells, spinning about its
// centre, 40 steps) with its cells in gmsh's order and along the Hilbert
// curve of the mesh factory (order_cells_along_hilbert_curve()), with the
// ratios of the two orders' times on 1 and on N threads, and the cells each
// of 2 MPI ranks would hold (and compute the gradient of) relative to its
// own (chunks_held_by_ranks()).
//
// Usage: build/benchmarks/benchmark_fem_threads [threads, default: all cores]
//        [largest subdivision, default 32] [end time of the 98,304-cell
//        run, default 1]
#include <deal.II/base/multithread_info.h>
#include <deal.II/grid/tria.h>

#include <estep/base/parallel_blocks.h>
#include <estep/fem/meshes.h>

#include "centred_cube_run.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace
{
  using benchmark_cube::body_on;
  using benchmark_cube::Run;

  /** The run of benchmark_cube::run() on @p threads threads. */
  Run
  run(const estep::ElasticBody    &body,
      const unsigned int           threads,
      const double                 end_time,
      const unsigned int           max_steps,
      const std::array<double, 3> &centre = {{0.5, 0.5, 0.5}})
  {
    estep::set_thread_count(threads);
    return benchmark_cube::run(body, end_time, max_steps, centre);
  }

  /** The fastest of three runs of @p body on 1 and on @p threads threads,
   * in turn. */
  std::pair<Run, Run>
  serial_and_parallel(const estep::ElasticBody    &body,
                      const unsigned int           threads,
                      const double                 end_time,
                      const unsigned int           max_steps,
                      const std::array<double, 3> &centre = {{0.5, 0.5, 0.5}})
  {
    Run serial   = run(body, 1, end_time, max_steps, centre);
    Run parallel = run(body, threads, end_time, max_steps, centre);
    for (unsigned int repetition = 1; repetition < 3; ++repetition)
      {
        serial.seconds =
          std::min(serial.seconds,
                   run(body, 1, end_time, max_steps, centre).seconds);
        parallel.seconds =
          std::min(parallel.seconds,
                   run(body, threads, end_time, max_steps, centre).seconds);
      }
    return {serial, parallel};
  }
} // namespace

int
main(int argc, char **argv)
{
  const unsigned int threads =
    argc > 1 ? std::atoi(argv[1]) : dealii::MultithreadInfo::n_cores();
  const unsigned int largest  = argc > 2 ? std::atoi(argv[2]) : 32;
  const double       end_time = argc > 3 ? std::atof(argv[3]) : 1.;
  std::printf("energy-stepping, centred spinning cube, h = 1e-5; 1 against "
              "%u threads\n",
              threads);
  std::printf("%9s %6s %7s %13s %13s %15s %15s %8s %9s\n",
              "cells",
              "steps",
              "t",
              "1: s/step",
              "N: s/step",
              "1: ns/step/cell",
              "N: ns/step/cell",
              "speedup",
              "same bits");
  for (unsigned int n = 4; n <= largest; n *= 2)
    {
      dealii::Triangulation<3> tria;
      estep::make_seed_cube_mesh(tria, n);
      const estep::ElasticBody body = body_on(tria, "cube");
      // To the end time, the largest cube (786,432 cells) for 40 steps.
      const unsigned int max_steps = n > 16 ? 40 : 1000000;
      const auto [serial, parallel] =
        serial_and_parallel(body, threads, end_time, max_steps);
      const double cells = body.n_cells();
      std::printf("%9.0f %6u %7.3g %13.3e %13.3e %15.1f %15.1f %8.2f %9s\n",
                  cells,
                  serial.steps,
                  serial.time,
                  serial.seconds / serial.steps,
                  parallel.seconds / parallel.steps,
                  1e9 * serial.seconds / serial.steps / cells,
                  1e9 * parallel.seconds / parallel.steps / cells,
                  serial.seconds / parallel.seconds,
                  benchmark_cube::same_end(serial, parallel) ? "yes" : "NO");
    }

  benchmark_cube::compare_cell_orders(
    [&](const estep::ElasticBody    &body,
        const std::array<double, 3> &centre,
        const unsigned int           steps) {
      return serial_and_parallel(body, threads, 1e9, steps, centre);
    },
    "1 thread",
    "N",
    true);
  return 0;
}
