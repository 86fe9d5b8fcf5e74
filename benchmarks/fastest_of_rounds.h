// The time of a collective call in the MPI benchmarks: the fastest of three
// rounds of repeated calls, each round started by every process together.
#ifndef estep_benchmarks_fastest_of_rounds_h
#define estep_benchmarks_fastest_of_rounds_h

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <limits>

namespace benchmark_mpi
{
  /** Seconds per call of @p call, the fastest of three rounds of @p calls
   * calls, the largest over the processes. Collective. */
  template <typename Call>
  double
  seconds_per_call(const unsigned int calls, const Call &call)
  {
    double fastest = std::numeric_limits<double>::infinity();
    for (unsigned int round = 0; round < 3; ++round)
      {
        MPI_Barrier(MPI_COMM_WORLD);
        const auto start = std::chrono::steady_clock::now();
        for (unsigned int i = 0; i < calls; ++i)
          call();
        const double seconds = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - start)
                                 .count();
        fastest = std::min(fastest, seconds / calls);
      }
    return dealii::Utilities::MPI::max(fastest, MPI_COMM_WORLD);
  }
} // namespace benchmark_mpi

#endif
