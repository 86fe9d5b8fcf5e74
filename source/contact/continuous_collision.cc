// The round-off bound below assumes that every operation is rounded separately.
#pragma GCC optimize("fp-contract=off")

#include <estep/contact/continuous_collision.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace estep
{
  namespace contact
  {
    namespace
    {
      struct Box
      {
        double t0, t1, u0, u1, v0, v1;
      };

      struct LaterStart
      {
        bool
        operator()(const Box &a, const Box &b) const
        {
          // Earliest start first; among equal starts the smaller box (depth
          // first).
          if (a.t0 != b.t0)
            return a.t0 > b.t0;
          return (a.t1 - a.t0) + (a.u1 - a.u0) + (a.v1 - a.v0) >
                 (b.t1 - b.t0) + (b.u1 - b.u0) + (b.v1 - b.v0);
        }
      };

      // F(t, u, v) = base(t) + u e1(t) + v e2(t) where base, e1, e2 are
      // differences of the four moving points; for vertex-face base = p - a, e1
      // = a - b, e2 = a - c; for edge-edge base = a0 - b0, e1 = a1 - a0, e2 =
      // b0 - b1.
      template <bool vertex_face>
      CcdResult
      inclusion_ccd(const std::array<Point3, 4> &x0,
                    const std::array<Point3, 4> &x1,
                    const CcdSettings           &settings)
      {
        double M = 0.;
        Point3 d[4];
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int k = 0; k < 3; ++k)
            {
              M = std::max(M, std::max(std::abs(x0[i][k]), std::abs(x1[i][k])));
              d[i][k] = x1[i][k] - x0[i][k];
            }
        // Round-off bound of one corner value (doc/contact.md: at most about 50
        // u M).
        const double error = 0x1p-46 * M + std::numeric_limits<double>::min();
        const double delta = settings.tolerance;

        // Range of F over a box: returns -1 if 0 is excluded, 1 if the range
        // lies within the tolerance, 0 otherwise; w receives how much F varies
        // along t, u and v.
        const auto classify = [&](const Box &b, double w[3]) {
          double       f[2][2][2][3];
          const double ts[2] = {b.t0, b.t1}, us[2] = {b.u0, b.u1},
                       vs[2] = {b.v0, b.v1};
          for (unsigned int it = 0; it < 2; ++it)
            {
              Point3 p[4];
              for (unsigned int i = 0; i < 4; ++i)
                for (unsigned int k = 0; k < 3; ++k)
                  p[i][k] = x0[i][k] + ts[it] * d[i][k];
              for (unsigned int k = 0; k < 3; ++k)
                {
                  double base, e1, e2;
                  if (vertex_face)
                    {
                      base = p[0][k] - p[1][k];
                      e1   = p[1][k] - p[2][k];
                      e2   = p[1][k] - p[3][k];
                    }
                  else
                    {
                      base = p[0][k] - p[2][k];
                      e1   = p[1][k] - p[0][k];
                      e2   = p[2][k] - p[3][k];
                    }
                  for (unsigned int iu = 0; iu < 2; ++iu)
                    {
                      const double bu = base + us[iu] * e1;
                      for (unsigned int iv = 0; iv < 2; ++iv)
                        f[it][iu][iv][k] = bu + vs[iv] * e2;
                    }
                }
            }
          bool inside = true;
          for (unsigned int k = 0; k < 3; ++k)
            {
              double lo = f[0][0][0][k], hi = lo;
              for (unsigned int c = 1; c < 8; ++c)
                {
                  const double x = f[c >> 2][(c >> 1) & 1][c & 1][k];
                  lo             = std::min(lo, x);
                  hi             = std::max(hi, x);
                }
              if (lo > error || hi < -error)
                return -1;
              inside =
                inside && (hi + error <= delta) && (lo - error >= -delta);
            }
          if (inside)
            return 1;
          w[0] = w[1] = w[2] = 0.;
          for (unsigned int a = 0; a < 2; ++a)
            for (unsigned int c = 0; c < 2; ++c)
              for (unsigned int k = 0; k < 3; ++k)
                {
                  w[0] =
                    std::max(w[0], std::abs(f[1][a][c][k] - f[0][a][c][k]));
                  w[1] =
                    std::max(w[1], std::abs(f[a][1][c][k] - f[a][0][c][k]));
                  w[2] =
                    std::max(w[2], std::abs(f[a][c][1][k] - f[a][c][0][k]));
                }
          return 0;
        };

        CcdResult                            result;
        static thread_local std::vector<Box> heap;
        heap.clear();
        heap.push_back(Box{0., 1., 0., 1., 0., 1.});
        while (!heap.empty())
          {
            std::pop_heap(heap.begin(), heap.end(), LaterStart());
            const Box b = heap.back();
            heap.pop_back();
            if (vertex_face && b.u0 + b.v0 > 1.)
              continue; // outside the triangle u + v <= 1
            ++result.n_iterations;
            double    w[3];
            const int c = classify(b, w);
            if (c < 0)
              continue;
            if (c > 0 || result.n_iterations >= settings.max_iterations)
              {
                // All remaining boxes start no earlier than b: b.t0 is a safe
                // contact time.
                result.hit    = true;
                result.time   = b.t0;
                result.capped = (c == 0);
                return result;
              }
            // Split where F varies most (the corner values measure it exactly).
            const double wt = w[0], wu = w[1], wv = w[2];
            Box          lower = b, upper = b;
            if (wt >= wu && wt >= wv)
              lower.t1 = upper.t0 = 0.5 * (b.t0 + b.t1);
            else if (wu >= wv)
              lower.u1 = upper.u0 = 0.5 * (b.u0 + b.u1);
            else
              lower.v1 = upper.v0 = 0.5 * (b.v0 + b.v1);
            heap.push_back(lower);
            std::push_heap(heap.begin(), heap.end(), LaterStart());
            heap.push_back(upper);
            std::push_heap(heap.begin(), heap.end(), LaterStart());
          }
        return result;
      }
    } // namespace



    CcdResult
    vertex_face_ccd(const std::array<Point3, 4> &start,
                    const std::array<Point3, 4> &end,
                    const CcdSettings           &settings)
    {
      return inclusion_ccd<true>(start, end, settings);
    }



    CcdResult
    edge_edge_ccd(const std::array<Point3, 4> &start,
                  const std::array<Point3, 4> &end,
                  const CcdSettings           &settings)
    {
      return inclusion_ccd<false>(start, end, settings);
    }
  } // namespace contact
} // namespace estep
