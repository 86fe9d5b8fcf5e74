// for_each_block() and sum_over_blocks() on several threads: every block
// runs once, loops inside blocks, exceptions, sums in block order, and the
// blocks really running at the same time.
#include <estep/base/parallel_blocks.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace
{
  /** Restores one thread at the end of a test. */
  struct ThreadCount
  {
    explicit ThreadCount(const unsigned int n)
    {
      estep::set_thread_count(n);
    }
    ~ThreadCount()
    {
      estep::set_thread_count(1);
    }
  };

  /** Calls of each block, counted. */
  std::unique_ptr<std::atomic<unsigned int>[]>
  counters(const unsigned int n) {
    std::unique_ptr<std::atomic<unsigned int>[]> c(
      new std::atomic<unsigned int>[n]);
    for (unsigned int b = 0; b < n; ++b)
      c[b] = 0;
    return c;
  }
} // namespace

TEST(ParallelBlocks, EveryBlockRunsOnceOnAnyNumberOfThreads)
{
  for (const unsigned int threads : {1u, 2u, 3u, 5u})
    {
      ThreadCount count(threads);
      for (const unsigned int n : {0u, 1u, 2u, 7u, 1000u})
        for (unsigned int repetition = 0; repetition < 50; ++repetition)
          {
            const auto calls = counters(n);
            estep::for_each_block(n, [&](const unsigned int b) {
              ASSERT_LT(b, n);
              ++calls[b];
            });
            // Every call has returned when the loop returns.
            for (unsigned int b = 0; b < n; ++b)
              ASSERT_EQ(calls[b], 1u) << "block " << b << " of " << n << " on "
                                      << threads << " threads";
          }
    }
}

TEST(ParallelBlocks, LoopsInsideBlocksRunEveryInnerBlockOnce)
{
  // Three levels, as a contact system's bodies side by side run their own
  // loops, with fewer and more outer blocks than threads.
  for (const unsigned int threads : {2u, 3u})
    for (const unsigned int outer : {2u, 5u})
      {
        ThreadCount        count(threads);
        const unsigned int middle = 3, inner = 17;
        const auto         calls = counters(outer * middle * inner);
        for (unsigned int repetition = 0; repetition < 20; ++repetition)
          estep::for_each_block(outer, [&](const unsigned int i) {
            estep::for_each_block(middle, [&](const unsigned int j) {
              estep::for_each_block(inner, [&](const unsigned int k) {
                ++calls[(i * middle + j) * inner + k];
              });
            });
          });
        for (unsigned int b = 0; b < outer * middle * inner; ++b)
          ASSERT_EQ(calls[b], 20u) << "inner block " << b;
      }
}

TEST(ParallelBlocks, BlocksRunAtTheSameTime)
{
  // Block 0 waits until block 1 has started: on one thread, in order, it
  // would wait forever (here: until the deadline), so the loop shows that a
  // second thread takes blocks while the first is busy.
  ThreadCount       count(2);
  std::atomic<bool> started{false};
  std::atomic<bool> timed_out{false};
  const auto        deadline =
    std::chrono::steady_clock::now() + std::chrono::seconds(10);
  for (unsigned int repetition = 0; repetition < 100 && !timed_out;
       ++repetition)
    {
      started = false;
      estep::for_each_block(2, [&](const unsigned int b) {
        if (b == 1)
          started = true;
        else
          while (!started && !timed_out)
            if (std::chrono::steady_clock::now() > deadline)
              timed_out = true;
      });
    }
  EXPECT_FALSE(timed_out) << "the blocks of a loop never ran side by side";
}

TEST(ParallelBlocks, AnExceptionOfABlockReachesTheCaller)
{
  for (const unsigned int threads : {1u, 2u, 3u})
    {
      ThreadCount count(threads);
      for (const unsigned int thrower : {0u, 5u, 63u})
        {
          const auto calls = counters(64);
          try
            {
              estep::for_each_block(64, [&](const unsigned int b) {
                ++calls[b];
                if (b == thrower)
                  throw std::runtime_error("block " + std::to_string(b));
              });
              ADD_FAILURE() << "no exception";
            }
          catch (const std::runtime_error &e)
            {
              EXPECT_EQ(std::string(e.what()),
                        "block " + std::to_string(thrower));
            }
          // The blocks after it may have been left out, but none ran twice;
          // and the next loop runs normally.
          EXPECT_EQ(calls[thrower], 1u);
          for (unsigned int b = 0; b < 64; ++b)
            EXPECT_LE(calls[b], 1u);
          std::atomic<unsigned int> total{0};
          estep::for_each_block(64, [&](const unsigned int) { ++total; });
          EXPECT_EQ(total, 64u);
        }
    }
}

TEST(ParallelBlocks, SumsAreTheSameToTheLastBitOnAnyNumberOfThreads)
{
  // Terms of very different sizes, whose sum depends on the order.
  const auto term = [](const unsigned int b) {
    return std::ldexp(1. + 1e-3 * b, static_cast<int>((b * 37) % 101) - 50);
  };
  double reference = 0.;
  for (const unsigned int threads : {1u, 2u, 3u, 4u})
    {
      ThreadCount  count(threads);
      const double sum = estep::sum_over_blocks<double>(997, term);
      if (threads == 1)
        {
          for (unsigned int b = 0; b < 997; ++b)
            reference += term(b);
        }
      EXPECT_EQ(std::memcmp(&sum, &reference, sizeof(double)), 0)
        << threads << " threads";
    }
}

TEST(ParallelBlocks, ThreadCountChangesBetweenLoops)
{
  for (const unsigned int threads : {3u, 1u, 2u, 4u, 2u})
    {
      estep::set_thread_count(threads);
      EXPECT_EQ(estep::thread_count(), threads);
      std::atomic<unsigned int> total{0};
      estep::for_each_block(100, [&](const unsigned int) { ++total; });
      EXPECT_EQ(total, 100u);
    }
  estep::set_thread_count(1);
}
