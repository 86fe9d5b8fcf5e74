#include <estep/base/distributed_blocks.h>
#include <estep/contact/penalty_contact.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace estep
{
  namespace contact
  {
    namespace
    {
      // gradient += w^T dX/d(vertices) for the end point X produced by source
      // s.
      void
      add_end_point_gradient(const SegmentEndPoint &s,
                             const Triangle3       &T0,
                             const Triangle3       &T1,
                             const Point3          &w,
                             double                *gradient)
      {
        const unsigned int ke = s.edge_triangle, kf = 1 - ke;
        const Triangle3   &E = (ke == 0) ? T0 : T1;
        const Triangle3   &F = (kf == 0) ? T0 : T1;
        const Point3      &a = E[s.edge[0]], &b = E[s.edge[1]];
        const Point3       f1 = minus(F[1], F[0]), f2 = minus(F[2], F[0]);
        const Point3       n  = cross(f1, f2);
        const Point3       ap = minus(a, F[0]), bp = minus(b, F[0]);
        const double       da = dot(n, ap), db = dot(n, bp);
        const double       denom = da - db;
        if (denom == 0.)
          return; // cannot happen for a generating edge
        const double t    = da / denom;
        const double c    = dot(w, minus(b, a));
        const double ct_a = -c * db / (denom * denom);
        const double ct_b = c * da / (denom * denom);

        double *ga = gradient + 9 * ke + 3 * s.edge[0];
        double *gb = gradient + 9 * ke + 3 * s.edge[1];
        double *gp = gradient + 9 * kf;
        double *gq = gp + 3, *gr = gp + 6;
        Point3  m;
        for (unsigned int k = 0; k < 3; ++k)
          m[k] = ct_a * ap[k] + ct_b * bp[k];
        const Point3 dq = cross(f2, m), dr = cross(m, f1);
        for (unsigned int k = 0; k < 3; ++k)
          {
            ga[k] += w[k] * (1. - t) + ct_a * n[k];
            gb[k] += w[k] * t + ct_b * n[k];
            gp[k] += -(ct_a + ct_b) * n[k] - dq[k] - dr[k];
            gq[k] += dq[k];
            gr[k] += dr[k];
          }
      }

    } // namespace



    double
    squared_intersection_length(const Triangle3        &T0,
                                const Triangle3        &T1,
                                std::array<double, 18> *gradient)
    {
      if (gradient != nullptr)
        gradient->fill(0.);
      const TriangleIntersection r = intersect_triangles(T0, T1);
      if (r.kind != IntersectionKind::segment)
        return 0.;
      const Point3 d = minus(r.A, r.B);
      if (gradient != nullptr)
        {
          const Point3 w = {{2. * d[0], 2. * d[1], 2. * d[2]}};
          add_end_point_gradient(r.source[0], T0, T1, w, gradient->data());
          add_end_point_gradient(
            r.source[1], T0, T1, {{-w[0], -w[1], -w[2]}}, gradient->data());
        }
      return dot(d, d);
    }



    PenaltyContact::PenaltyContact(std::vector<TriangleIndices> triangles,
                                   const double                 eps)
      : eps(eps)
      , bvh(std::move(triangles))
    {
      bvh.set_rebuild_interval(64);
      if (!(eps > 0.) || !std::isfinite(eps))
        throw std::invalid_argument(
          "PenaltyContact: the penalty parameter eps must be "
          "positive and finite, got " +
          std::to_string(eps));
      const auto &t = bvh.get_triangles();
      for (std::size_t i = 0; i < t.size(); ++i)
        if (t[i][0] == t[i][1] || t[i][1] == t[i][2] || t[i][0] == t[i][2])
          throw std::invalid_argument("PenaltyContact: surface triangle " +
                                      std::to_string(i) +
                                      " repeats a vertex index");
    }



    void
    PenaltyContact::set_exclusion_groups(std::vector<unsigned int> groups)
    {
      bvh.set_exclusion_groups(std::move(groups));
    }



    double
    PenaltyContact::evaluate(const double     *q,
                             const std::size_t n,
                             double           *g,
                             unsigned int     *count) const
    {
      bvh.refit(q, n);
      bvh.find_pairs(pairs);
      // The order of the sum below must not depend on the tree's history
      // (built here or refitted since): a resumed run, which builds it
      // afresh, then sums exactly as the uninterrupted one.
      for (auto &[i, j] : pairs)
        if (i > j)
          std::swap(i, j);
      std::sort(pairs.begin(), pairs.end());

      const auto &tris  = bvh.get_triangles();
      double      total = 0.;
      for (const auto &[i, j] : pairs)
        {
          const Triangle3        T0 = triangle_at(q, tris[i]);
          const Triangle3        T1 = triangle_at(q, tris[j]);
          std::array<double, 18> grad;
          const double           gap =
            squared_intersection_length(T0, T1, g != nullptr ? &grad : nullptr);
          if (gap == 0.)
            continue;
          total += gap;
          if (count != nullptr)
            ++*count;
          if (g != nullptr)
            for (unsigned int v = 0; v < 3; ++v)
              for (unsigned int k = 0; k < 3; ++k)
                {
                  g[3 * tris[i][v] + k] += grad[3 * v + k] / (2. * eps);
                  g[3 * tris[j][v] + k] += grad[9 + 3 * v + k] / (2. * eps);
                }
        }
      return total / (2. * eps);
    }



    double
    PenaltyContact::energy(const double *q, const std::size_t n) const
    {
      return evaluate(q, n, nullptr, nullptr);
    }



    double
    PenaltyContact::add_gradient(const double     *q,
                                 const std::size_t n,
                                 double           *g) const
    {
      return evaluate(q, n, g, nullptr);
    }



    unsigned int
    PenaltyContact::n_intersecting_pairs(const double     *q,
                                         const std::size_t n) const
    {
      unsigned int count = 0;
      evaluate(q, n, nullptr, &count);
      return count;
    }



    PenaltyContact::Flight
    PenaltyContact::flight(const double     *q,
                           const double     *v,
                           const std::size_t n,
                           const double      s_max) const
    {
      if (!(s_max >= 0.) || !std::isfinite(s_max))
        throw std::invalid_argument(
          "PenaltyContact::flight: s_max must be finite and >= 0");
      Flight f;
      f.contact = this;
      f.q.assign(q, q + n);
      f.v.assign(v, v + n);
      f.s_max = s_max;
      BoundingVolumeHierarchy swept(bvh.get_triangles(),
                                    bvh.get_exclusion_groups());
      swept.build_swept(q, v, n, s_max);
      swept.find_pairs(f.pairs);
      return f;
    }



    double
    PenaltyContact::sum_along_line(
      const std::vector<std::pair<unsigned int, unsigned int>> &pairs,
      const double                                             *q,
      const double                                             *v,
      const double                                              s,
      double                                                   *derivative,
      unsigned int                                             *count) const
    {
      // Blocks of pairs (a fixed number each) on the threads and ranks,
      // their sums added in block order.
      struct Sums
      {
        double       total, slope;
        unsigned int count;
        Sums &
        operator+=(const Sums &other)
        {
          total += other.total;
          slope += other.slope;
          count += other.count;
          return *this;
        }
      };
      const auto &tris = get_triangles();
      const Sums  sums = sum_over_shared_blocks<Sums>(
        std::max(1u, n_blocks(pairs.size(), pairs_per_block)),
        [&](const unsigned int b) {
          const BlockRange block =
            block_range(b, pairs.size(), pairs_per_block);
          Sums      sums{0., 0., 0};
          Triangle3 T[2];
          for (unsigned int k = block.begin; k < block.end; ++k)
            {
              const auto [i, j]           = pairs[k];
              const TriangleIndices *t[2] = {&tris[i], &tris[j]};
              for (unsigned int m = 0; m < 2; ++m)
                for (unsigned int a = 0; a < 3; ++a)
                  for (unsigned int c = 0; c < 3; ++c)
                    {
                      const unsigned int index = 3 * (*t[m])[a] + c;
                      T[m][a][c]               = q[index] + s * v[index];
                    }
              std::array<double, 18> grad;
              const double           gap = squared_intersection_length(
                T[0], T[1], derivative != nullptr ? &grad : nullptr);
              if (gap == 0.)
                continue;
              sums.total += gap;
              ++sums.count;
              if (derivative != nullptr)
                for (unsigned int m = 0; m < 2; ++m)
                  for (unsigned int a = 0; a < 3; ++a)
                    for (unsigned int c = 0; c < 3; ++c)
                      sums.slope +=
                        grad[9 * m + 3 * a + c] * v[3 * (*t[m])[a] + c];
            }
          return sums;
        });
      const double total = sums.total, slope = sums.slope;
      if (count != nullptr)
        *count += sums.count;
      const double scale = 1. / (2. * eps);
      if (derivative != nullptr)
        *derivative = slope * scale;
      return total * scale;
    }



    double
    PenaltyContact::Flight::evaluate(const double  s,
                                     double       *derivative,
                                     unsigned int *count) const
    {
      return contact->sum_along_line(
        pairs, q.data(), v.data(), s, derivative, count);
    }



    double
    PenaltyContact::Flight::value(const double s) const
    {
      return evaluate(s, nullptr, nullptr);
    }



    std::pair<double, double>
    PenaltyContact::Flight::value_and_derivative(const double s) const
    {
      double       d     = 0.;
      const double value = evaluate(s, &d, nullptr);
      return {value, d};
    }



    unsigned int
    PenaltyContact::Flight::n_intersecting_pairs(const double s) const
    {
      unsigned int count = 0;
      evaluate(s, nullptr, &count);
      return count;
    }
  } // namespace contact
} // namespace estep
