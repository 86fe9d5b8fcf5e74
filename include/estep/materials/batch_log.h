#ifndef estep_materials_batch_log_h
#define estep_materials_batch_log_h

#include <cstddef>

namespace estep
{
  /**
   * y[i] = log(x[i]) for i < n, the natural logarithm of many numbers at once.
   *
   * On x86-64 this calls glibc's vector logarithm (libmvec: 8 lanes with
   * AVX-512, 4 with AVX2, 2 otherwise, as the CPU has them); elsewhere it loops
   * over std::log.
   * The vector logarithm is accurate to a few units in the last place (glibc
   * documents at most 4 ulp); callers that need rigorous bounds widen by
   * batch_log_ulp() ulps. Special values follow std::log: log(0) = -infinity,
   * log(x < 0) = NaN. @p x and @p y may be the same array.
   */
  void
  batch_log(const double *x, double *y, const std::size_t n);

  /** The reference path of batch_log(): y[i] = std::log(x[i]) (used by tests).
   */
  void
  batch_log_scalar(const double *x, double *y, const std::size_t n);

  /** Error bound of batch_log() in units of the last place of the result (a
   * safe margin). */
  constexpr double
  batch_log_ulp()
  {
    return 8.;
  }

  /** Name of the path batch_log() takes on this machine ("avx512 libmvec",
   * "avx2 libmvec", "sse2 libmvec" or "scalar"). */
  const char *
  batch_log_path();
} // namespace estep

#endif
