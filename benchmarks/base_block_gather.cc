// What a sum over the cells costs in messages now, against what it would
// cost with sums that do not depend on their order. Now each of the ~10 sums
// of a step sends every process the result of every block of 1,024 cells
// (share_block_items(), one MPI_Allgatherv), and each adds them in block
// order, which keeps the bits independent of the number of processes. A
// reproducible accumulation would need one MPI_Allreduce of a result's size
// (a few bins more). For the blocks of the centred cube at 12,288 / 98,304
// / 786,432 cells and results of 24 and 56 bytes (the free flight's
// quadratic sums and its centre terms), this prints the time of each (the
// fastest of three rounds of repeated calls) and their ratio, for the cost
// model of doc/parallel.md.
//
// Usage: mpirun -np P build/benchmarks/benchmark_base_block_gather
//        [calls per round, default 2000]
#include <deal.II/base/mpi.h>

#include <estep/base/distributed_blocks.h>

#include "fastest_of_rounds.h"

#include <cstdio>
#include <cstdlib>
#include <vector>

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  estep::distribute_blocks_over_mpi_ranks();
  const unsigned int calls = argc > 1 ? std::atoi(argv[1]) : 2000;
  const bool         first = estep::this_rank() == 0;
  if (first)
    std::printf("a sum over the cells on %u MPI processes: every block's "
                "result to every process (now) against one MPI_Allreduce\n"
                "%9s %7s %11s %14s %16s %7s\n",
                estep::rank_count(),
                "cells",
                "blocks",
                "item bytes",
                "gather: us",
                "Allreduce: us",
                "ratio");
  for (const unsigned int cells : {12288u, 98304u, 786432u})
    for (const unsigned int doubles : {3u, 7u})
      {
        const unsigned int  blocks = estep::n_blocks(cells);
        std::vector<double> items(std::size_t(blocks) * doubles, 1.);
        std::vector<double> sum(doubles, 0.), total(doubles, 0.);
        const double gather = benchmark_mpi::seconds_per_call(calls, [&]() {
          estep::share_block_items(items.data(),
                                   doubles * sizeof(double),
                                   blocks);
        });
        const double reduce = benchmark_mpi::seconds_per_call(calls, [&]() {
          MPI_Allreduce(sum.data(),
                        total.data(),
                        doubles,
                        MPI_DOUBLE,
                        MPI_SUM,
                        MPI_COMM_WORLD);
        });
        if (first)
          std::printf("%9u %7u %11zu %14.2f %16.2f %7.1f\n",
                      cells,
                      blocks,
                      doubles * sizeof(double),
                      1e6 * gather,
                      1e6 * reduce,
                      gather / reduce);
      }
  return 0;
}
