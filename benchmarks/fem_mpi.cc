// Energy-stepping on several MPI processes: the centred spinning cube
// (h = 1e-5) at 1,536, 12,288, 98,304 and 786,432 cells, each run by the
// first process alone (the others wait, asleep) and by all processes
// sharing the blocks of cells, one thread each, three times in turn (the
// fastest of the three counts), in one run of this program. Printed per
// size: the steps, the wall time per step and per step and cell of each,
// their ratio (the speedup), and whether the two runs ended in the same
// state to the last bit. Then the same for a ball meshed by gmsh (mesh
// size 0.05, 152,424 cells, spinning about its centre, 40 steps) with its
// cells in gmsh's order and along the Hilbert curve of the mesh factory
// (order_cells_along_hilbert_curve()), with the ratios of the two orders'
// times on 1 and on P processes, and the cells each of 2 ranks holds (and
// computes the gradient of) relative to its own (chunks_held_by_ranks()).
//
// Usage: mpirun -np 2 build/benchmarks/benchmark_fem_mpi [largest
//        subdivision, default 32] [end time, default 1]
#include <deal.II/base/mpi.h>
#include <deal.II/grid/tria.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/meshes.h>

#include "centred_cube_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <thread>

namespace
{
  using benchmark_cube::Run;
  using benchmark_cube::run;

  /** The first process runs alone; the others sleep until it is done (a
   * rank waiting in MPI polls, which would take a core from it). */
  Run
  run_alone(const estep::ElasticBody    &body,
            const double                 end_time,
            const unsigned int           max_steps,
            const std::array<double, 3> &centre)
  {
    estep::distribute_blocks_over_mpi_ranks(false);
    Run result{};
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      result = run(body, end_time, max_steps, centre);
    MPI_Request request;
    MPI_Ibarrier(MPI_COMM_WORLD, &request);
    for (int done = 0; !done;)
      {
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (!done)
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    estep::distribute_blocks_over_mpi_ranks(true);
    return result;
  }

  /** The fastest of three runs of @p body by the first process alone and by
   * all of them, in turn. */
  std::pair<Run, Run>
  alone_and_shared(const estep::ElasticBody    &body,
                   const double                 end_time,
                   const unsigned int           max_steps,
                   const std::array<double, 3> &centre = {{0.5, 0.5, 0.5}})
  {
    Run alone  = run_alone(body, end_time, max_steps, centre);
    Run shared = run(body, end_time, max_steps, centre);
    for (unsigned int repetition = 1; repetition < 3; ++repetition)
      {
        alone.seconds =
          std::min(alone.seconds,
                   run_alone(body, end_time, max_steps, centre).seconds);
        shared.seconds =
          std::min(shared.seconds,
                   run(body, end_time, max_steps, centre).seconds);
      }
    return {alone, shared};
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  estep::distribute_blocks_over_mpi_ranks();
  estep::set_thread_count(1);
  const unsigned int ranks    = estep::rank_count();
  const bool         first    = estep::this_rank() == 0;
  const unsigned int largest  = argc > 1 ? std::atoi(argv[1]) : 32;
  const double       end_time = argc > 2 ? std::atof(argv[2]) : 1.;
  if (first)
    {
      std::printf("energy-stepping, centred spinning cube, h = 1e-5; 1 "
                  "against %u MPI processes of 1 thread\n",
                  ranks);
      std::printf("%9s %6s %7s %13s %13s %15s %15s %8s %9s\n",
                  "cells",
                  "steps",
                  "t",
                  "1: s/step",
                  "P: s/step",
                  "1: ns/step/cell",
                  "P: ns/step/cell",
                  "speedup",
                  "same bits");
    }
  for (unsigned int n = 4; n <= largest; n *= 2)
    {
      dealii::Triangulation<3> tria;
      estep::make_seed_cube_mesh(tria, n);
      const estep::ElasticBody body = benchmark_cube::body_on(tria, "cube");
      // To the end time, the largest cube (786,432 cells) for 40 steps.
      const unsigned int max_steps = n > 16 ? 40 : 1000000;
      const auto [alone, shared] = alone_and_shared(body, end_time, max_steps);
      if (!first)
        continue;
      const double cells = body.n_cells();
      std::printf("%9.0f %6u %7.3g %13.3e %13.3e %15.1f %15.1f %8.2f %9s\n",
                  cells,
                  alone.steps,
                  alone.time,
                  alone.seconds / alone.steps,
                  shared.seconds / shared.steps,
                  1e9 * alone.seconds / alone.steps / cells,
                  1e9 * shared.seconds / shared.steps / cells,
                  alone.seconds / shared.seconds,
                  benchmark_cube::same_end(alone, shared) ? "yes" : "NO");
    }

  // Every process meshes the ball: gmsh, on one thread with a fixed seed,
  // makes the same mesh on each.
  benchmark_cube::compare_cell_orders(
    [](const estep::ElasticBody    &body,
       const std::array<double, 3> &centre,
       const unsigned int           steps) {
      return alone_and_shared(body, 1e9, steps, centre);
    },
    "1 process",
    "P",
    first);
  return 0;
}
