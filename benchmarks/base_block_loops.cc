// The cost of a parallel loop over blocks at the sizes of an energy-stepping
// step: for_each_block() (deal.II's TBB loop) against the plain serial loop,
// in one run of this program. Each block does a fixed amount of
// arithmetic; between two loops the calling thread works alone for a quarter
// of a block's time, as the search does between evaluations. Also loops
// inside loops: two outer blocks each running a loop (the bodies of a
// contact system side by side). Printed: the time of a block, microseconds
// per loop (the fastest of three rounds, the work between loops left out),
// the speedup, and what a loop costs beyond its share of the serial loop's
// time (serial / threads).
//
// Usage: build/benchmarks/benchmark_base_block_loops [threads, default: all
//        cores]
#include <deal.II/base/multithread_info.h>

#include <estep/base/parallel_blocks.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>

namespace
{
  volatile double sink;

  /** Some arithmetic that the compiler cannot drop: @p n multiply-adds. */
  double
  arithmetic(const unsigned int n)
  {
    double x = 0.;
    for (unsigned int i = 0; i < n; ++i)
      x += 1e-9 * i * i;
    return x;
  }

  /** Microseconds per call of @p loop followed by @p between of serial
   * arithmetic, the fastest of three rounds of @p calls. */
  template <typename Loop>
  double
  microseconds_per_loop(const Loop        &loop,
                        const unsigned int between,
                        const unsigned int calls)
  {
    double fastest = std::numeric_limits<double>::infinity();
    for (unsigned int round = 0; round < 3; ++round)
      {
        const auto start = std::chrono::steady_clock::now();
        for (unsigned int i = 0; i < calls; ++i)
          {
            loop();
            sink = arithmetic(between);
          }
        fastest = std::min(fastest,
                           std::chrono::duration<double, std::micro>(
                             std::chrono::steady_clock::now() - start)
                               .count() /
                             calls);
      }
    return fastest;
  }
} // namespace

int
main(int argc, char **argv)
{
  const unsigned int threads =
    argc > 1 ? std::atoi(argv[1]) : dealii::MultithreadInfo::n_cores();
  estep::set_thread_count(threads);
  std::printf("loops over blocks on %u threads: microseconds per loop "
              "(speedup over the serial loop)\n\n",
              estep::thread_count());
  std::printf("| arithmetic per block | us per block | blocks | nested | "
              "serial | for_each_block | speedup | beyond its share |\n"
              "|---:|---:|---:|:--:|---:|---:|---:|---:|\n");
  for (const unsigned int per_block : {1000u, 4000u, 16000u, 64000u})
    for (const unsigned int n_blocks : {2u, 6u, 24u})
      for (const bool nested : {false, true})
        {
          const std::function<void(unsigned int)> block =
            [&](const unsigned int) { sink = arithmetic(per_block); };
          // Nested: two outer blocks, each a loop over half the blocks.
          const unsigned int inner = nested ? n_blocks / 2 : n_blocks;
          const auto         run   = [&](const auto &loop) {
            if (!nested)
              return loop(n_blocks, block);
            loop(2, [&](const unsigned int) { loop(inner, block); });
          };
          const auto serial = [&] {
            run([](const unsigned int                       n,
                   const std::function<void(unsigned int)> &work) {
              for (unsigned int b = 0; b < n; ++b)
                work(b);
            });
          };
          const auto         parallel = [&] { run(estep::for_each_block); };
          const unsigned int between  = per_block / 4;
          const unsigned int calls =
            std::max(200u, 20000000u / (per_block * n_blocks));
          const double alone = microseconds_per_loop([] {}, between, calls);
          const double s =
            microseconds_per_loop(serial, between, calls) - alone;
          const double p =
            microseconds_per_loop(parallel, between, calls) - alone;
          std::printf("| %u | %.2f | %u | %s | %.2f | %.2f | %.2f | %.2f |\n",
                      per_block,
                      s / n_blocks,
                      n_blocks,
                      nested ? "2 x" : "",
                      s,
                      p,
                      s / p,
                      p - s / estep::thread_count());
        }
  return 0;
}
