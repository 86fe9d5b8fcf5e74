// The latency of one MPI_Allreduce of a few doubles (the global sum an
// evaluation of a distributed energy, slope or enclosure would need), for the
// cost model of doc/parallel.md.
//
// Usage: mpirun -np P build/benchmarks/benchmark_base_mpi_allreduce [calls,
//        default 100000]
#include <deal.II/base/mpi.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int calls = argc > 1 ? std::atoi(argv[1]) : 100000;
  const int ranks = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  for (const int n : {1, 4, 16})
    {
      double local[16], global[16];
      for (int k = 0; k < n; ++k)
        local[k] = k + 1.;
      // A few calls to warm up, then the timed ones.
      for (unsigned int i = 0; i < 100; ++i)
        MPI_Allreduce(local, global, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
      MPI_Barrier(MPI_COMM_WORLD);
      const auto start = std::chrono::steady_clock::now();
      for (unsigned int i = 0; i < calls; ++i)
        MPI_Allreduce(local, global, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        std::printf("%d ranks, MPI_Allreduce of %2d doubles: %.2f us per call "
                    "(%u calls)\n",
                    ranks,
                    n,
                    1e6 * seconds / calls,
                    calls);
    }
  return 0;
}
