// The wall-clock seconds since a moment, for the benchmarks that time single
// runs of a piece of work.
#ifndef estep_benchmarks_seconds_since_h
#define estep_benchmarks_seconds_since_h

#include <chrono>

namespace benchmark_timing
{
  inline double
  seconds_since(const std::chrono::steady_clock::time_point start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
      .count();
  }
} // namespace benchmark_timing

#endif
