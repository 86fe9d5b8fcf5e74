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
 * every x86-64 level. By default (CMake's ESTEP_SIMD = auto) a function marked
 * ESTEP_LANE_KERNEL is compiled three times, for x86-64-v4 (AVX-512: the same
 * four lanes, but 32 registers instead of 16, so that the matrices a cell
 * kernel keeps live spill far less), x86-64-v3 (AVX2, FMA) and the baseline,
 * and the dynamic loader picks the version the CPU runs: the binaries stay
 * portable and use what the processor has. ESTEP_SIMD = x86-64-v4, x86-64-v3
 * or x86-64 compiles the one version of that level instead (to measure a path
 * on a machine that has a wider one). Results of the versions may differ in
 * the last bits (fused multiply-adds); the kernels' rounding bounds hold for
 * all.
 */

#include <estep/base/config.h>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
  defined(__linux__)
#  define ESTEP_LANE_LEVELS 1 // the kernels are built for x86-64 levels
#  ifdef ESTEP_SIMD_FIXED
#    define ESTEP_LANE_KERNEL __attribute__((target("arch=" ESTEP_SIMD)))
#  else
#    define ESTEP_LANE_KERNEL \
      __attribute__((         \
        target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#  endif
#else
#  define ESTEP_LANE_KERNEL
#endif

/** For the small helpers of the lane kernels: inlined into each compiled
 * version of a kernel (a call would reach the baseline version). */
#define ESTEP_LANE_INLINE inline __attribute__((always_inline))

namespace estep
{
  /**
   * The instruction set the ESTEP_LANE_KERNEL functions run with on this
   * machine ("x86-64-v4", "x86-64-v3", "x86-64", or "portable C++" where they
   * are not multiversioned).
   */
  const char *
  lane_kernel_target();

  /**
   * The widest x86-64 level (4, 3 or 1) the build lets the kernels and the
   * vector logarithm use: that of ESTEP_SIMD, or 4 for auto.
   */
  int
  widest_lane_level();

  /**
   * Throws an exception naming the instruction set if the kernels were built
   * for one (ESTEP_SIMD) that this processor lacks: a clear error instead of
   * an illegal instruction.
   */
  void
  check_lane_kernel_target();

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

  // The shuffles below are __builtin_shufflevector (GCC 12 and Clang; GCC's
  // older __builtin_shuffle is unknown to Clang).

  /**
   * The triples x[3 index[k] + c], c = 0, 1, 2, of four entries k as three
   * Lanes (xyz[c][k]), from one load of four doubles per entry and a
   * transposition: @p x must have one readable double after its last triple.
   */
  ESTEP_LANE_INLINE void
  load_triples(const double *x, const unsigned int *index, Lanes *xyz)
  {
    const Lanes r0 = load_lanes(x + 3 * index[0]),
                r1 = load_lanes(x + 3 * index[1]),
                r2 = load_lanes(x + 3 * index[2]),
                r3 = load_lanes(x + 3 * index[3]);
    const Lanes t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6),
                t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7),
                t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6),
                t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
    xyz[0]         = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
    xyz[1]         = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    xyz[2]         = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  }

  /**
   * y[3 index[k] + c] += xyz[c][k] for the four entries k in turn (so repeated
   * indices accumulate), by a transposition and one addition of four doubles
   * per entry (the fourth adds 0): @p y must have one writable double after
   * its last triple.
   */
  ESTEP_LANE_INLINE void
  add_triples(double *y, const unsigned int *index, const Lanes *xyz)
  {
    const Lanes zero    = lanes(0.);
    const Lanes t0      = __builtin_shufflevector(xyz[0], xyz[1], 0, 4, 1, 5),
                t1      = __builtin_shufflevector(xyz[0], xyz[1], 2, 6, 3, 7),
                t2      = __builtin_shufflevector(xyz[2], zero, 0, 4, 1, 5),
                t3      = __builtin_shufflevector(xyz[2], zero, 2, 6, 3, 7);
    const Lanes rows[4] = {__builtin_shufflevector(t0, t2, 0, 1, 4, 5),
                           __builtin_shufflevector(t0, t2, 2, 3, 6, 7),
                           __builtin_shufflevector(t1, t3, 0, 1, 4, 5),
                           __builtin_shufflevector(t1, t3, 2, 3, 6, 7)};
    for (unsigned int k = 0; k < n_lanes; ++k)
      {
        double *row = y + 3 * index[k];
        store_lanes(row, load_lanes(row) + rows[k]);
      }
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
} // namespace estep

#endif
