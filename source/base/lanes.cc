#include <estep/base/lanes.h>

#include <cstring>
#include <stdexcept>
#include <string>

namespace estep
{
#ifdef ESTEP_LANE_LEVELS
  namespace
  {
    /** The x86-64 level of this processor: 4, 3, 2 or 1. */
    int
    processor_level()
    {
      return __builtin_cpu_supports("x86-64-v4") ? 4 :
             __builtin_cpu_supports("x86-64-v3") ? 3 :
             __builtin_cpu_supports("x86-64-v2") ? 2 :
                                                   1;
    }
  } // namespace
#endif

  int
  widest_lane_level()
  {
    // The level in the name: "x86-64-v3" 3, "x86-64" 1.
    const char *suffix = std::strstr(ESTEP_SIMD, "-v");
    return std::strcmp(ESTEP_SIMD, "auto") == 0 ? 4 :
           suffix != nullptr                    ? suffix[2] - '0' :
                                                  1;
  }

  const char *
  lane_kernel_target()
  {
#ifdef ESTEP_LANE_LEVELS
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
#if defined(ESTEP_LANE_LEVELS) && defined(ESTEP_SIMD_FIXED)
    if (processor_level() < widest_lane_level())
      throw std::runtime_error(
        std::string("estep was built for the instruction set ") + ESTEP_SIMD +
        " (CMake's ESTEP_SIMD), which this processor does not have; "
        "configure with -DESTEP_SIMD=auto.");
#endif
  }
} // namespace estep
