#include <estep/base/distributed_blocks.h>
#include <estep/base/interruption.h>

#include <csignal>
#include <string>

namespace estep
{
  namespace
  {
    /** Set by request_interruption() (from a signal handler). */
    volatile std::sig_atomic_t interruption = 0;
  } // namespace



  void
  request_interruption(const int signal) noexcept
  {
    interruption = signal;
  }



  int
  requested_interruption()
  {
    return largest_over_ranks(interruption);
  }



  StepInterrupted::StepInterrupted(const int signal)
    : std::runtime_error("a step abandoned for signal " +
                         std::to_string(signal))
    , signal(signal)
  {}



  void
  abandon_step_if_interrupted()
  {
    if (const int signal = requested_interruption(); signal != 0)
      throw StepInterrupted(signal);
  }
} // namespace estep
