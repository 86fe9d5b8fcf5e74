#include <estep/base/lanes.h>
#include <estep/materials/batch_log.h>

#include <cmath>

#if defined(__x86_64__) && defined(__GNUC__) && defined(__linux__)
#  define ESTEP_HAVE_LIBMVEC 1
#  include <immintrin.h>

// glibc's vector logarithms (libmvec, resolved through libm's linker script).
// Calling them directly keeps -ffast-math out of the build: only these calls
// are vectorised. The AVX ones take their arguments in AVX registers: their
// declarations carry the target (clang rejects the calls otherwise).
extern "C" __m128d                                     _ZGVbN2v_log(__m128d);
extern "C" __attribute__((target("avx2,fma"))) __m256d _ZGVdN4v_log(__m256d);
extern "C" __attribute__((target("avx512f"))) __m512d  _ZGVeN8v_log(__m512d);
#endif

namespace estep
{
  namespace
  {
#ifdef ESTEP_HAVE_LIBMVEC
    __attribute__((target("avx2,fma"))) void
    batch_log_avx2(const double *x, double *y, const std::size_t n)
    {
      std::size_t i = 0;
      for (; i + 4 <= n; i += 4)
        _mm256_storeu_pd(y + i, _ZGVdN4v_log(_mm256_loadu_pd(x + i)));
      for (; i < n; ++i)
        y[i] = std::log(x[i]);
    }

    __attribute__((target("avx512f"))) void
    batch_log_avx512(const double *x, double *y, const std::size_t n)
    {
      std::size_t i = 0;
      for (; i + 8 <= n; i += 8)
        _mm512_storeu_pd(y + i, _ZGVeN8v_log(_mm512_loadu_pd(x + i)));
      for (; i < n; ++i)
        y[i] = std::log(x[i]);
    }

    void
    batch_log_sse2(const double *x, double *y, const std::size_t n)
    {
      std::size_t i = 0;
      for (; i + 2 <= n; i += 2)
        _mm_storeu_pd(y + i, _ZGVbN2v_log(_mm_loadu_pd(x + i)));
      for (; i < n; ++i)
        y[i] = std::log(x[i]);
    }

    // The widest logarithm is the processor's, but no wider than the
    // instruction set the build fixed for the cell kernels (ESTEP_SIMD).
    bool
    have_avx512()
    {
      static const bool avx512 =
        __builtin_cpu_supports("avx512f") && widest_lane_level() >= 4;
      return avx512;
    }

    bool
    have_avx2()
    {
      static const bool avx2 = __builtin_cpu_supports("avx2") &&
                               __builtin_cpu_supports("fma") &&
                               widest_lane_level() >= 3;
      return avx2;
    }
#endif
  } // namespace

  void
  batch_log(const double *x, double *y, const std::size_t n)
  {
#ifdef ESTEP_HAVE_LIBMVEC
    if (have_avx512())
      batch_log_avx512(x, y, n);
    else if (have_avx2())
      batch_log_avx2(x, y, n);
    else
      batch_log_sse2(x, y, n);
#else
    batch_log_scalar(x, y, n);
#endif
  }

  void
  batch_log_scalar(const double *x, double *y, const std::size_t n)
  {
    for (std::size_t i = 0; i < n; ++i)
      y[i] = std::log(x[i]);
  }

  const char *
  batch_log_path()
  {
#ifdef ESTEP_HAVE_LIBMVEC
    return have_avx512() ? "avx512 libmvec" :
           have_avx2()   ? "avx2 libmvec" :
                           "sse2 libmvec";
#else
    return "scalar";
#endif
  }
} // namespace estep
