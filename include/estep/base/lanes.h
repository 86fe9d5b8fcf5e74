#ifndef estep_base_lanes_h
#define estep_base_lanes_h

#include <cstddef>
#include <cstring>

/**
 * @file
 * Lanes: four doubles that arithmetic treats element by element. The per-cell
 * kernels of the elastic body and of the materials work on four cells at a
 * time in them (one AVX2 register, or two SSE2 registers).
 *
 * Lanes is the vector extension of GCC and Clang, so one source compiles for
 * every x86-64 level. A function marked ESTEP_LANE_KERNEL is compiled twice,
 * for x86-64-v3 (AVX2, FMA) and for the baseline, and the dynamic loader picks
 * the version the CPU runs: the binaries stay portable and use the wide
 * registers where they exist. Results of the two versions may differ in the
 * last bits (fused multiply-adds); the kernels' rounding bounds hold for both.
 */

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
  defined(__linux__)
#  define ESTEP_LANE_KERNEL \
    __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#  define ESTEP_LANE_KERNEL
#endif

/** For the small helpers of the lane kernels: inlined into each compiled
 * version of a kernel (a call would reach the baseline version). */
#define ESTEP_LANE_INLINE inline __attribute__((always_inline))

namespace estep
{
  /** Four doubles, one per cell of a batch. */
  typedef double Lanes __attribute__((vector_size(4 * sizeof(double))));

  /** The number of doubles in Lanes. */
  constexpr unsigned int n_lanes = 4;

  /** All lanes equal to @p x. */
  ESTEP_LANE_INLINE Lanes
  lanes(const double x)
  {
    return Lanes{x, x, x, x};
  }

  /** p[0], ..., p[3] (no alignment needed). */
  ESTEP_LANE_INLINE Lanes
  load_lanes(const double *p)
  {
    Lanes x;
    std::memcpy(&x, p, sizeof x);
    return x;
  }

  /** p[0], ..., p[count - 1], the remaining lanes set to @p fill (count <= 4).
   */
  ESTEP_LANE_INLINE Lanes
  load_lanes(const double *p, const unsigned int count, const double fill)
  {
    Lanes x = lanes(fill);
    for (unsigned int k = 0; k < count; ++k)
      x[k] = p[k];
    return x;
  }

  /**
   * Batch @p i of an array of length @p n: p[i], ..., p[i + 3], or, for the
   * last, partial batch, the entries below n and @p fill in the other lanes.
   */
  ESTEP_LANE_INLINE Lanes
  load_batch(const double     *p,
             const std::size_t i,
             const std::size_t n,
             const double      fill)
  {
    return i + n_lanes <= n ? load_lanes(p + i) :
                              load_lanes(p + i, n - i, fill);
  }

  /** Writes the four lanes of @p x to p[0], ..., p[3]. */
  ESTEP_LANE_INLINE void
  store_lanes(double *p, const Lanes x)
  {
    std::memcpy(p, &x, sizeof x);
  }

  /** x[i] = base[stride * index[i] + offset] for the four lanes. */
  ESTEP_LANE_INLINE Lanes
  gather_lanes(const double       *base,
               const unsigned int *index,
               const unsigned int  stride,
               const unsigned int  offset)
  {
    return Lanes{base[stride * index[0] + offset],
                 base[stride * index[1] + offset],
                 base[stride * index[2] + offset],
                 base[stride * index[3] + offset]};
  }

  /** |x| per lane. */
  ESTEP_LANE_INLINE Lanes
  abs(const Lanes x)
  {
    return x < 0. ? -x : x;
  }

  /** The smaller of a and b per lane (b where they are unordered). */
  ESTEP_LANE_INLINE Lanes
  min(const Lanes a, const Lanes b)
  {
    return a < b ? a : b;
  }

  /** The larger of a and b per lane (b where they are unordered). */
  ESTEP_LANE_INLINE Lanes
  max(const Lanes a, const Lanes b)
  {
    return a > b ? a : b;
  }

  /** The sum of the four lanes. */
  ESTEP_LANE_INLINE double
  sum(const Lanes x)
  {
    return (x[0] + x[1]) + (x[2] + x[3]);
  }

  /** Whether every lane of @p x is positive (false for NaN). */
  ESTEP_LANE_INLINE bool
  all_positive(const Lanes x)
  {
    return x[0] > 0. && x[1] > 0. && x[2] > 0. && x[3] > 0.;
  }
} // namespace estep

#endif
