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
      // Coplanarity of the four moving points. V(t) = det[x1(t) - x0(t),
      // x2(t) - x0(t), x3(t) - x0(t)] vanishes at every contact (vertex-face:
      // the vertex lies in the face's plane; edge-edge: two crossing lines span
      // a plane). Every column is linear in t, (1 - t) e(0) + t e(1), and the
      // determinant is linear in each column, so V(t) = sum_k S_k (1 - t)^(3 -
      // k) t^k with S_k the sum of the determinants that take k columns at t =
      // 1 and 3 - k at t = 0 (the Bernstein form up to binomial factors). If
      // all four S_k have the same strict sign, V has no root in [0, 1].
      //
      // Round-off: each determinant is evaluated from differences rounded
      // once, as three 2x2 minors and a dot product; every one of its six
      // terms passes at most 8 roundings (3 differences, 2 products, 1
      // subtraction, 2 additions), so its error is at most (8 u + O(u^2)) times
      // its permanent (the same expression with absolute values, computed
      // from the same rounded differences and so at most a few u below the
      // exact one); the at most two additions forming S_k add 2 u times the
      // sum of the permanents. The bound used, 2^-48 = 32 u times the summed
      // permanent (plus the smallest normal number against underflow of that
      // sum), has a factor of about 3 in hand. Valid as long as no product of
      // three differences overflows or underflows (as for orient3d()); NaN or
      // infinite values make every comparison fail, so nothing is rejected.
      struct CoplanarityFunction
      {
        // S_k and the bound on its round-off, k = number of columns at t = 1.
        double sum[4]   = {0., 0., 0., 0.};
        double bound[4] = {0., 0., 0., 0.};
        // The determinant at t = 0 and t = 1.
        double end_determinant[2];
      };

      CoplanarityFunction
      coplanarity_function(const std::array<Point3, 4> &x0,
                           const std::array<Point3, 4> &x1)
      {
        // e[i][s] = x_{i+1} - x_0 at time s (rounded once).
        double e[3][2][3], a[3][2][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int k = 0; k < 3; ++k)
            {
              e[i][0][k] = x0[i + 1][k] - x0[0][k];
              e[i][1][k] = x1[i + 1][k] - x1[0][k];
              a[i][0][k] = std::abs(e[i][0][k]);
              a[i][1][k] = std::abs(e[i][1][k]);
            }
        // Cross products of the second and third columns (and their
        // permanents), shared by the determinants with either first column.
        double cross[2][2][3], abs_cross[2][2][3];
        for (unsigned int s = 0; s < 2; ++s)
          for (unsigned int r = 0; r < 2; ++r)
            for (unsigned int k = 0; k < 3; ++k)
              {
                const unsigned int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
                cross[s][r][k] =
                  e[1][s][k1] * e[2][r][k2] - e[1][s][k2] * e[2][r][k1];
                abs_cross[s][r][k] =
                  a[1][s][k1] * a[2][r][k2] + a[1][s][k2] * a[2][r][k1];
              }
        CoplanarityFunction f;
        double              permanent[4] = {0., 0., 0., 0.};
        for (unsigned int q = 0; q < 2; ++q)
          for (unsigned int s = 0; s < 2; ++s)
            for (unsigned int r = 0; r < 2; ++r)
              {
                const double det = e[0][q][0] * cross[s][r][0] +
                                   e[0][q][1] * cross[s][r][1] +
                                   e[0][q][2] * cross[s][r][2];
                const double per = a[0][q][0] * abs_cross[s][r][0] +
                                   a[0][q][1] * abs_cross[s][r][1] +
                                   a[0][q][2] * abs_cross[s][r][2];
                f.sum[q + s + r] += det;
                permanent[q + s + r] += per;
                if (q == s && s == r)
                  f.end_determinant[q] = det;
              }
        for (unsigned int k = 0; k < 4; ++k)
          f.bound[k] =
            0x1p-48 * permanent[k] + std::numeric_limits<double>::min();
        return f;
      }

      // Whether V(t) provably keeps one strict sign on [0, 1]: then the
      // primitives never touch.
      bool
      never_coplanar(const CoplanarityFunction &f)
      {
        bool positive = true, negative = true;
        for (unsigned int k = 0; k < 4; ++k)
          {
            positive = positive && f.sum[k] > f.bound[k];
            negative = negative && f.sum[k] < -f.bound[k];
          }
        return positive || negative;
      }

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
          // The same test along the common normal of the two directions
          // spanned by F (face normal, or normal to both edges) at the box's
          // middle time: n . F is multilinear as well, so its range is the hull
          // of the corner values, for any fixed n. Along n the range is about
          // the distance from the plane, which excludes 0 long before all three
          // axis-aligned ranges do when the plane is oblique. Round-off: each
          // corner value is within error of F in every component, so n . f is
          // within |n|_1 error of n . F, plus the rounding of the dot product
          // itself (3 u |n|_1 max |f| < 0.2 |n|_1 error, since |f| <= 6 M);
          // 2 |n|_1 error covers both.
          {
            const double tm = 0.5 * b.t0 + 0.5 * b.t1;
            double       e1[3], e2[3];
            for (unsigned int k = 0; k < 3; ++k)
              {
                double p[4];
                for (unsigned int i = 0; i < 4; ++i)
                  p[i] = x0[i][k] + tm * d[i][k];
                e1[k] = vertex_face ? p[1] - p[2] : p[1] - p[0];
                e2[k] = vertex_face ? p[1] - p[3] : p[2] - p[3];
              }
            double       n[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                                 e1[2] * e2[0] - e1[0] * e2[2],
                                 e1[0] * e2[1] - e1[1] * e2[0]};
            const double n_max =
              std::max({std::abs(n[0]), std::abs(n[1]), std::abs(n[2])});
            if (n_max > 0. && n_max < std::numeric_limits<double>::infinity())
              {
                double n_1 = 0.;
                for (double &x : n)
                  {
                    x /= n_max;
                    n_1 += std::abs(x);
                  }
                const double bound = 2. * n_1 * error;
                double lo = std::numeric_limits<double>::infinity(), hi = -lo;
                for (unsigned int c = 0; c < 8; ++c)
                  {
                    const double *x = f[c >> 2][(c >> 1) & 1][c & 1];
                    const double  y = n[0] * x[0] + n[1] * x[1] + n[2] * x[2];
                    lo              = std::min(lo, y);
                    hi              = std::max(hi, y);
                  }
                if (lo > bound || hi < -bound)
                  return -1;
              }
          }
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

        CcdResult result;
        // Sound early rejection (no contact is lost: every contact is a root
        // of V). It decides many misses at once and, unlike the boxes below,
        // also near misses closer than the tolerance that never become
        // coplanar (fewer false positives).
        if (never_coplanar(coplanarity_function(x0, x1)))
          return result;

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
            // A box without contact ends nothing, unless it is the last one
            // the cap allows and others remain.
            if (c < 0 &&
                (result.n_iterations < settings.max_iterations || heap.empty()))
              continue;
            if (c > 0 || result.n_iterations >= settings.max_iterations)
              {
                // All remaining boxes start no earlier than b: b.t0 is a safe
                // contact time.
                result.hit    = true;
                result.time   = b.t0;
                result.capped = (c <= 0);
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



    bool
    ccd_query_is_non_degenerate(const std::array<Point3, 4> &start,
                                const std::array<Point3, 4> &end)
    {
      const CoplanarityFunction f = coplanarity_function(start, end);
      for (unsigned int s = 0; s < 2; ++s)
        {
          const std::array<Point3, 4> &x            = (s == 0 ? start : end);
          double                       longest_edge = 0.;
          for (unsigned int i = 0; i < 4; ++i)
            for (unsigned int j = i + 1; j < 4; ++j)
              {
                double length2 = 0.;
                for (unsigned int k = 0; k < 3; ++k)
                  length2 += (x[i][k] - x[j][k]) * (x[i][k] - x[j][k]);
                longest_edge = std::max(longest_edge, std::sqrt(length2));
              }
          const double scale = longest_edge * longest_edge * longest_edge;
          if (!(std::abs(f.end_determinant[s]) >
                non_degeneracy_threshold * scale))
            return false;
        }
      return true;
    }



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
