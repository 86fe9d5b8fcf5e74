#ifndef estep_fem_p1_kernels_h
#define estep_fem_p1_kernels_h

// Private inline kernels of the P1 elastic body (not installed).

#include <estep/base/lanes.h>
#include <estep/base/parallel_blocks.h>
#include <estep/fem/p1_cell_data.h>

#include <algorithm>

namespace estep
{
  namespace internal
  {
    /**
     * F = [x_1 - x_0 | x_2 - x_0 | x_3 - x_0] B of cell @p e for point-major
     * positions @p x (row-major F[3 i + j]).
     */
    inline void
    deformation_gradient(const double      *x,
                         const P1CellData  &d,
                         const unsigned int e,
                         double            *F)
    {
      const unsigned int h  = d.at(e);
      const unsigned int p0 = 3 * d.point[0][h], p1 = 3 * d.point[1][h],
                         p2 = 3 * d.point[2][h], p3 = 3 * d.point[3][h];
      double B[9];
      for (unsigned int k = 0; k < 9; ++k)
        B[k] = d.shape_gradient[k][h];
      for (unsigned int i = 0; i < 3; ++i)
        {
          const double x0 = x[p0 + i];
          const double d1 = x[p1 + i] - x0, d2 = x[p2 + i] - x0,
                       d3 = x[p3 + i] - x0;
          for (unsigned int j = 0; j < 3; ++j)
            F[3 * i + j] = d1 * B[j] + d2 * B[3 + j] + d3 * B[6 + j];
        }
    }

    /**
     * F of the four cells @p e, ..., @p e + 3 (e a multiple of 4; the cell
     * arrays are padded to whole batches), one Lanes per entry. @p x must have
     * one readable double after its last point (see load_triples()).
     */
    ESTEP_LANE_INLINE void
    deformation_gradient(const double      *x,
                         const P1CellData  &d,
                         const unsigned int e,
                         Lanes             *F)
    {
      const unsigned int h = d.at(e);
      Lanes              B[9];
      for (unsigned int k = 0; k < 9; ++k)
        B[k] = load_lanes(d.shape_gradient[k].data() + h);
      Lanes x0[3], x1[3], x2[3], x3[3];
      load_triples(x, d.point[0].data() + h, x0);
      load_triples(x, d.point[1].data() + h, x1);
      load_triples(x, d.point[2].data() + h, x2);
      load_triples(x, d.point[3].data() + h, x3);
      for (unsigned int i = 0; i < 3; ++i)
        {
          const Lanes d1 = x1[i] - x0[i], d2 = x2[i] - x0[i],
                      d3 = x3[i] - x0[i];
          for (unsigned int j = 0; j < 3; ++j)
            F[3 * i + j] = d1 * B[j] + d2 * B[3 + j] + d3 * B[6 + j];
        }
    }

    /**
     * Copy the @p n point-major values @p x to @p copy, which holds n + 1, and
     * set the last to zero: the lane kernels load four doubles per point. In
     * parallel blocks; only the ranges @p kept if given (the coordinates an
     * MPI rank keeps, MechanicalSystem::kept_coordinates(), which hold every
     * point of the cells it computes).
     */
    inline void
    copy_padded(const double                  *x,
                const unsigned int             n,
                double                        *copy,
                const std::vector<BlockRange> *kept = nullptr)
    {
      const auto copy_range = [&](const BlockRange range) {
        std::copy(x + range.begin, x + range.end, copy + range.begin);
      };
      if (kept)
        for_each_block(kept->size(),
                       [&](const unsigned int i) { copy_range((*kept)[i]); });
      else
        for_each_block(n_blocks(n), [&](const unsigned int b) {
          copy_range(block_range(b, n));
        });
      copy[n] = 0.;
    }

    /** Cofactor matrix C = d det F / dF (row-major); T is double or Lanes. */
    template <typename T>
    ESTEP_LANE_INLINE void
    cofactor(const T *F, T *C)
    {
      C[0] = F[4] * F[8] - F[5] * F[7];
      C[1] = F[5] * F[6] - F[3] * F[8];
      C[2] = F[3] * F[7] - F[4] * F[6];
      C[3] = F[2] * F[7] - F[1] * F[8];
      C[4] = F[0] * F[8] - F[2] * F[6];
      C[5] = F[1] * F[6] - F[0] * F[7];
      C[6] = F[1] * F[5] - F[2] * F[4];
      C[7] = F[2] * F[3] - F[0] * F[5];
      C[8] = F[0] * F[4] - F[1] * F[3];
    }

    /** det F by the first row and its cofactors. */
    template <typename T>
    ESTEP_LANE_INLINE T
    determinant(const T *F, const T *C)
    {
      return F[0] * C[0] + F[1] * C[1] + F[2] * C[2];
    }

    /** A : B for 3x3 matrices. */
    template <typename T>
    ESTEP_LANE_INLINE T
    contract(const T *A, const T *B)
    {
      T s = A[0] * B[0];
      for (unsigned int k = 1; k < 9; ++k)
        s += A[k] * B[k];
      return s;
    }
  } // namespace internal
} // namespace estep

#endif
