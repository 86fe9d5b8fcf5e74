#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parallel.h>

#include <estep/base/parallel_blocks.h>

namespace estep
{
  void
  set_thread_count(const unsigned int n)
  {
    dealii::MultithreadInfo::set_thread_limit(
      n == 0 ? dealii::MultithreadInfo::n_cores() : n);
  }



  unsigned int
  thread_count()
  {
    return dealii::MultithreadInfo::n_threads();
  }



  void
  for_each_block(const unsigned int                       n_blocks,
                 const std::function<void(unsigned int)> &work)
  {
    if (n_blocks <= 1 || thread_count() == 1)
      {
        for (unsigned int b = 0; b < n_blocks; ++b)
          work(b);
        return;
      }
    // One block per task at least: the blocks are already worth a task.
    dealii::parallel::apply_to_subranges(
      0u,
      n_blocks,
      [&](const unsigned int begin, const unsigned int end) {
        for (unsigned int b = begin; b < end; ++b)
          work(b);
      },
      1);
  }
} // namespace estep
