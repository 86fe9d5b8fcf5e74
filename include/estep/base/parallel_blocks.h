#ifndef estep_base_parallel_blocks_h
#define estep_base_parallel_blocks_h

#include <functional>
#include <vector>

/**
 * @file
 * The per-cell loops of estep run over fixed blocks of cells, on as many
 * threads as the run allows. A block is a range of block_size consecutive
 * cells (or points); which thread takes which block is left to the scheduler,
 * but a loop that produces a sum gives one partial result per block and adds
 * them in block order. So a sum, and with it the whole trajectory, is the same
 * to the last bit on any number of threads: the blocks do not depend on it.
 */

namespace estep
{
  /** Items (cells, points) per block: a multiple of the chunk sizes of the
   * cell kernels (128 and 256 cells), large enough to be worth a task. */
  constexpr unsigned int block_size = 1024;

  /** The number of blocks of @p n items, @p size per block. */
  constexpr unsigned int
  n_blocks(const unsigned int n, const unsigned int size = block_size)
  {
    return (n + size - 1) / size;
  }

  /** The items [begin, end) of a block. */
  struct BlockRange
  {
    unsigned int begin, end;
  };

  /** The items of block @p b of @p n items, @p size per block. */
  constexpr BlockRange
  block_range(const unsigned int b,
              const unsigned int n,
              const unsigned int size = block_size)
  {
    return {b * size, (b + 1) * size < n ? (b + 1) * size : n};
  }

  /**
   * Let the loops use @p n threads (0: one per core). Also deal.II's limit
   * (MultithreadInfo), so that its own task-based loops follow.
   */
  void
  set_thread_count(const unsigned int n);

  /** The number of threads the loops use. */
  unsigned int
  thread_count();

  /**
   * Call @p work(b) once for every b < @p n_blocks, on up to thread_count()
   * threads (in order on the calling thread when that is one, or there is one
   * block). Returns when every call has returned; an exception of a call is
   * thrown again here.
   */
  void
  for_each_block(const unsigned int                       n_blocks,
                 const std::function<void(unsigned int)> &work);

  /**
   * The sum of @p term(b) over b < @p n_blocks (at least one), with the terms
   * computed in parallel and added in the order of b. T needs +=.
   */
  template <typename T, typename Term>
  T
  sum_over_blocks(const unsigned int n_blocks, const Term &term)
  {
    std::vector<T> terms(n_blocks);
    for_each_block(n_blocks, [&](const unsigned int b) { terms[b] = term(b); });
    T total = terms[0];
    for (unsigned int b = 1; b < n_blocks; ++b)
      total += terms[b];
    return total;
  }
} // namespace estep

#endif
