#include <estep/base/lanes.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace estep
{
  namespace
  {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
  defined(__linux__)
    /** The x86-64 level of this processor: 4, 3, 2 or 1. */
    int
    processor_level()
    {
      return __builtin_cpu_supports("x86-64-v4") ? 4 :
             __builtin_cpu_supports("x86-64-v3") ? 3 :
             __builtin_cpu_supports("x86-64-v2") ? 2 :
                                                   1;
    }
#endif
  } // namespace

  const char *
  lane_kernel_target()
  {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
  defined(__linux__)
#  ifdef ESTEP_SIMD_FIXED
    return ESTEP_SIMD;
#  else
    // The clones of ESTEP_LANE_KERNEL and the level the loader's choice
    // rests on.
    const int level = processor_level();
    return level >= 4 ? "x86-64-v4" : level == 3 ? "x86-64-v3" : "x86-64";
#  endif
#else
    return "portable C++";
#endif
  }

  void
  check_lane_kernel_target()
  {
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
  defined(__linux__) && defined(ESTEP_SIMD_FIXED)
    // The level of the name: "x86-64-v3" 3, "x86-64" 1.
    const char *suffix = std::strstr(ESTEP_SIMD, "-v");
    if (processor_level() < (suffix != nullptr ? suffix[2] - '0' : 1))
      throw std::runtime_error(
        std::string("estep was built for the instruction set ") + ESTEP_SIMD +
        " (CMake's ESTEP_SIMD), which this processor does not have; "
        "configure with -DESTEP_SIMD=auto.");
#endif
  }
} // namespace estep
