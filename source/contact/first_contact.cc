#include <estep/contact/first_contact.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace contact
  {
    namespace
    {
      constexpr double unit = std::numeric_limits<double>::epsilon() / 2.;

      inline Point3
      unit_normal(const double *x, const TriangleIndices &t)
      {
        Point3       n = cross(minus(point_at(x, t[1]), point_at(x, t[0])),
                         minus(point_at(x, t[2]), point_at(x, t[0])));
        const double l = std::sqrt(dot(n, n));
        if (l > 0.)
          for (double &c : n)
            c /= l;
        return n;
      }

      /** One primitive query: the points and an orientation hint. */
      struct Query
      {
        bool                        edge_edge;
        std::array<unsigned int, 4> points;
        Point3                      orientation;
      };

      // Distance and its rate along the flight for the normal of c at x.
      inline std::pair<double, double>
      distance_and_rate(const FirstContact &c, const double *x, const double *v)
      {
        double d = 0., r = 0.;
        for (unsigned int k = 0; k < 4; ++k)
          {
            d += c.weights[k] * dot(c.normal, point_at(x, c.points[k]));
            r += c.weights[k] * dot(c.normal, point_at(v, c.points[k]));
          }
        return {d, r};
      }

      /**
       * A bound of the round-off of the rate of @p c at the velocities
       * @p v, and of the smallest change of it that a change of v can make
       * (the last bits of v's components): a rate within it cannot be told
       * from zero, nor reflected.
       */
      double
      rate_roundoff(const FirstContact &c, const double *v)
      {
        double magnitude = 0.;
        for (unsigned int k = 0; k < 4; ++k)
          {
            const Point3 vk = point_at(v, c.points[k]);
            for (unsigned int i = 0; i < 3; ++i)
              magnitude += std::abs(c.weights[k] * c.normal[i] * vk[i]);
          }
        return 64. * unit * magnitude;
      }

      /**
       * Whether the closest points that define the weights of @p c lie on the
       * primitives themselves, not only on their lines or planes, up to
       * @p slack in distance: only then is a small distance along the normal a
       * small distance between the primitives. (Far-apart edges whose lines
       * nearly meet, or a vertex near the plane of a distant face, are not
       * touching.)
       */
      bool
      closest_points_on_primitives(const FirstContact &c,
                                   const double       *x,
                                   const double        slack)
      {
        const auto length = [x](const unsigned int i, const unsigned int j) {
          const Point3 d = minus(point_at(x, i), point_at(x, j));
          return std::sqrt(dot(d, d));
        };
        const auto within = [slack](const double t, const double size) {
          const double margin = slack / std::max(size, slack);
          return t >= -margin && t <= 1. + margin;
        };
        if (c.edge_edge)
          return within(c.weights[1], length(c.points[0], c.points[1])) &&
                 within(-c.weights[3], length(c.points[2], c.points[3]));
        // Barycentric coordinates (w0, w1, w2) = -(weights 1, 2, 3) of the
        // projection on the face; the face's longest edge sets the scale.
        const double size = std::max({length(c.points[1], c.points[2]),
                                      length(c.points[2], c.points[3]),
                                      length(c.points[3], c.points[1])});
        return within(-c.weights[1], size) && within(-c.weights[2], size) &&
               within(-c.weights[3], size);
      }

      /** Touching: a distance of at most this along the normal. */
      double
      touching_distance(const CcdSettings &settings)
      {
        return 2. * std::sqrt(3.) * settings.tolerance;
      }

      /** The rule of a pair touching at q. */
      struct TouchingRule
      {
        /** Touching: a distance of at most this along the normal. */
        double touching;
        /** A distance below this may have the wrong sign by round-off. */
        double distance_roundoff;

        TouchingRule(const CcdSettings &settings, const double max_q)
          : touching(touching_distance(settings))
          , distance_roundoff(64. * unit * max_q)
        {}

        /**
         * 0 if the pair @p c at @p distance along its normal does not touch
         * at @p x; else the side it lies on along the normal, +1 or -1: the
         * sign of its distance. The orientation of the normal only guesses
         * the side (the outward normals of one face pair, which at an edge of
         * two faces can point the wrong way), and decides only a distance
         * within round-off.
         */
        int
        side(const FirstContact &c,
             const double        distance,
             const double       *x) const
        {
          if (std::abs(distance) > touching ||
              !closest_points_on_primitives(c, x, touching))
            return 0;
          return distance < -distance_roundoff ? -1 : 1;
        }
      };

      /**
       * The primitive queries of the candidate triangle pairs of @p tree
       * whose boxes, swept over the flight q + s v, 0 <= s <= s_max, and
       * enlarged by @p margin, overlap: in the order of their keys,
       * duplicates removed. @p max_q is set to the largest |q_i|.
       */
      std::vector<Query>
      candidate_queries(BoundingVolumeHierarchy &tree,
                        const double            *q,
                        const double            *v,
                        const std::size_t        n,
                        const double             s_max,
                        const double             margin,
                        double                  &max_q)
      {
        const auto &triangles = tree.get_triangles();
        max_q                 = tree.largest_vertex_coordinate(q);
        const double max_v    = tree.largest_vertex_coordinate(v);
        // Boxes enlarged by the margin: pairs that come within it are
        // examined. The tree's topology may be an earlier flight's: it
        // changes the order of the pairs, which the queries are sorted out
        // of, not the pairs.
        tree.refit_swept(
          q, v, n, s_max, margin + 8. * unit * (max_q + s_max * max_v));
        std::vector<std::pair<unsigned int, unsigned int>> pairs;
        tree.find_pairs(pairs);

        std::vector<Query> queries;
        queries.reserve(15 * pairs.size());
        for (const auto &[i, j] : pairs)
          {
            const TriangleIndices &Ti = triangles[i], &Tj = triangles[j];
            const Point3 ni = unit_normal(q, Ti), nj = unit_normal(q, Tj);
            for (unsigned int k = 0; k < 3; ++k)
              {
                queries.push_back({false, {{Ti[k], Tj[0], Tj[1], Tj[2]}}, nj});
                queries.push_back({false, {{Tj[k], Ti[0], Ti[1], Ti[2]}}, ni});
              }
            const Point3 o = minus(nj, ni);
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int b = 0; b < 3; ++b)
                {
                  std::array<unsigned int, 2> ea = {{Ti[a], Ti[(a + 1) % 3]}},
                                              eb = {{Tj[b], Tj[(b + 1) % 3]}};
                  if (ea[0] > ea[1])
                    std::swap(ea[0], ea[1]);
                  if (eb[0] > eb[1])
                    std::swap(eb[0], eb[1]);
                  queries.push_back({true, {{ea[0], ea[1], eb[0], eb[1]}}, o});
                }
          }
        // Each query once, in the order of its key, and among equal keys (an
        // edge pair that several triangle pairs give, each with its own
        // orientation) the one whose orientation's bytes come first (a total
        // order, NaN included), so that the query kept does not depend on the
        // order of the pairs. The keys are sorted packed into two words: a
        // point's index is below 2^31, since its coordinates' indices 3 i + c
        // are unsigned ints.
        struct PackedKey
        {
          std::uint64_t high, low;
          std::uint32_t query;
        };
        std::vector<PackedKey> keys(queries.size());
        for (std::size_t k = 0; k < queries.size(); ++k)
          {
            const Query &x = queries[k];
            keys[k]        = {(std::uint64_t{x.edge_edge} << 62) |
                                (std::uint64_t{x.points[0]} << 31) | x.points[1],
                              (std::uint64_t{x.points[2]} << 31) | x.points[3],
                              static_cast<std::uint32_t>(k)};
          }
        std::sort(keys.begin(),
                  keys.end(),
                  [](const PackedKey &a, const PackedKey &b) {
                    return a.high < b.high ||
                           (a.high == b.high && a.low < b.low);
                  });
        std::vector<Query> distinct;
        for (std::size_t a = 0, b = 0; a < keys.size(); a = b)
          {
            std::uint32_t kept = keys[a].query;
            for (b = a + 1; b < keys.size() && keys[b].high == keys[a].high &&
                            keys[b].low == keys[a].low;
                 ++b)
              if (std::memcmp(queries[keys[b].query].orientation.data(),
                              queries[kept].orientation.data(),
                              sizeof(Point3)) < 0)
                kept = keys[b].query;
            distinct.push_back(queries[kept]);
          }
        return distinct;
      }
    } // namespace



    FirstContact
    contact_normal(const std::array<unsigned int, 4> &points,
                   const bool                         edge_edge,
                   const double                      *x,
                   const Point3                      &orientation)
    {
      FirstContact c;
      c.edge_edge = edge_edge;
      c.points    = points;
      Point3 n;
      if (!edge_edge)
        {
          const Point3 p = point_at(x, points[0]), a = point_at(x, points[1]),
                       b = point_at(x, points[2]), cc = point_at(x, points[3]);
          const Point3 e1 = minus(b, a), e2 = minus(cc, a), r = minus(p, a);
          n              = cross(e1, e2);
          const double A = dot(e1, e1), B = dot(e1, e2), C = dot(e2, e2);
          const double det = A * C - B * B;
          double       u = 1. / 3., w = 1. / 3.;
          if (det > 0.)
            {
              u = (C * dot(e1, r) - B * dot(e2, r)) / det;
              w = (A * dot(e2, r) - B * dot(e1, r)) / det;
            }
          c.weights = {{1., -(1. - u - w), -u, -w}};
        }
      else
        {
          const Point3 a0 = point_at(x, points[0]), a1 = point_at(x, points[1]),
                       b0 = point_at(x, points[2]), b1 = point_at(x, points[3]);
          const Point3 da = minus(a1, a0), db = minus(b1, b0),
                       r = minus(a0, b0);
          const double A = dot(da, da), B = dot(da, db), C = dot(db, db);
          const double D = dot(da, r), E = dot(db, r);
          const double det = A * C - B * B;
          n                = cross(da, db);
          double sa = 0.5, sb = 0.5;
          if (det > 1e-14 * A * C && det > 0.)
            {
              sa = (B * E - C * D) / det;
              sb = (A * E - B * D) / det;
              // Beyond an end of either edge the lines' closest points are
              // not the edges': the edges come closest at an end (a vertex
              // meets the other edge), and the lines' normal, perpendicular
              // to both edges, can be perpendicular to the way they approach
              // (an edge that meets the other end-on: a box's vertical edge
              // resting with its lower end on a floor's edge had the
              // horizontal normal across that edge). The edges' distance is
              // that of their own closest points (the lines' clamped as in
              // Ericson, Real-Time Collision Detection, 5.1.9), its gradient
              // along their difference; weights at those points keep the net
              // force and torque zero. Where the difference is within
              // round-off it has no direction: the lines' normal is kept.
              if (sa < 0. || sa > 1. || sb < 0. || sb > 1.)
                {
                  double ta = std::clamp(sa, 0., 1.);
                  double tb = (E + ta * B) / C;
                  if (tb < 0.)
                    {
                      tb = 0.;
                      ta = std::clamp(-D / A, 0., 1.);
                    }
                  else if (tb > 1.)
                    {
                      tb = 1.;
                      ta = std::clamp((B - D) / A, 0., 1.);
                    }
                  Point3 d;
                  double size = 0.;
                  for (unsigned int k = 0; k < 3; ++k)
                    {
                      d[k] = (a0[k] + ta * da[k]) - (b0[k] + tb * db[k]);
                      size = std::max({size,
                                       std::abs(a0[k]),
                                       std::abs(a1[k]),
                                       std::abs(b0[k]),
                                       std::abs(b1[k])});
                    }
                  const double roundoff = 64. * unit * size;
                  if (dot(d, d) > roundoff * roundoff)
                    {
                      n  = d;
                      sa = ta;
                      sb = tb;
                    }
                }
            }
          else
            {
              // Parallel edges: the midpoint of a and its projection on b;
              // the normal along their difference keeps the torque zero.
              if (C > 0.)
                sb = (dot(db, r) + 0.5 * B) / C;
              Point3 d;
              for (unsigned int k = 0; k < 3; ++k)
                d[k] = (a0[k] + sa * da[k]) - (b0[k] + sb * db[k]);
              n = d;
              if (dot(n, n) == 0.)
                {
                  // Touching: any direction perpendicular to the edges.
                  const unsigned int axis =
                    std::abs(da[0]) <= std::abs(da[1]) ?
                      (std::abs(da[0]) <= std::abs(da[2]) ? 0 : 2) :
                      (std::abs(da[1]) <= std::abs(da[2]) ? 1 : 2);
                  Point3 e = {{0., 0., 0.}};
                  e[axis]  = 1.;
                  n        = cross(da, e);
                }
            }
          c.weights = {{1. - sa, sa, -(1. - sb), -sb}};
        }
      double l = std::sqrt(dot(n, n));
      if (!(l > 0.))
        {
          n = orientation;
          l = std::sqrt(dot(n, n));
        }
      if (l > 0.)
        for (double &k : n)
          k /= l;
      if (dot(n, orientation) < 0.)
        for (double &k : n)
          k = -k;
      c.normal = n;
      return c;
    }



    std::optional<FirstContact>
    find_first_contact(const std::vector<TriangleIndices> &triangles,
                       const std::vector<unsigned int>    &groups,
                       const double                       *q,
                       const double                       *v,
                       const std::size_t                   n,
                       const double                        s_max,
                       const CcdSettings                  &settings)
    {
      BoundingVolumeHierarchy tree(triangles, groups);
      return find_first_contact(tree, q, v, n, s_max, settings);
    }



    std::optional<FirstContact>
    find_first_contact(BoundingVolumeHierarchy &tree,
                       const double            *q,
                       const double            *v,
                       const std::size_t        n,
                       const double             s_max,
                       const CcdSettings       &settings)
    {
      if (!(s_max >= 0.) || !std::isfinite(s_max))
        throw std::invalid_argument(
          "find_first_contact: s_max must be finite and >= 0");
      const auto &triangles = tree.get_triangles();
      if (triangles.empty())
        return std::nullopt;
      double             max_q = 0.;
      std::vector<Query> queries =
        candidate_queries(tree, q, v, n, s_max, settings.tolerance, max_q);

      const TouchingRule rule(settings, max_q);
      double             best  = s_max;
      const Query       *found = nullptr;
      for (const Query &query : queries)
        {
          const FirstContact start =
            contact_normal(query.points, query.edge_edge, q, query.orientation);
          const auto [distance, rate] = distance_and_rate(start, q, v);
          double    s0                = 0.;
          const int side              = rule.side(start, distance, q);
          if (side != 0)
            {
              // The rate at which the pair parts, on its side.
              const double parting = side * rate;
              const double held    = rate_roundoff(start, v);
              if (parting < -held)
                {
                  // Touching and approaching: a contact now.
                  best  = 0.;
                  found = &query;
                  break;
                }
              // Held, up to round-off: it does not move along its normal.
              if (parting <= held)
                continue;
              s0 = 8. * settings.tolerance / parting;
            }
          if (s0 >= best)
            continue;
          std::array<Point3, 4> x0, x1;
          double                largest = 0.;
          for (unsigned int k = 0; k < 4; ++k)
            for (unsigned int c = 0; c < 3; ++c)
              {
                const unsigned int m = 3 * query.points[k] + c;
                x0[k][c]             = q[m] + s0 * v[m];
                x1[k][c]             = q[m] + best * v[m];
                largest =
                  std::max({largest, std::abs(x0[k][c]), std::abs(x1[k][c])});
              }
          if (largest > ccd_coordinate_limit(settings.tolerance))
            {
              std::ostringstream message;
              message << "the contact detection met points at coordinates as "
                         "large as "
                      << largest << ", where its round-off exceeds half the "
                      << "collision tolerance " << settings.tolerance
                      << " and it cannot tell contact from separation (it "
                         "needs coordinates within 2^45 times the tolerance, "
                      << ccd_coordinate_limit(settings.tolerance) << ").";
              throw std::runtime_error(message.str());
            }
          const CcdResult r = query.edge_edge ?
                                edge_edge_ccd(x0, x1, settings) :
                                vertex_face_ccd(x0, x1, settings);
          if (!r.hit)
            continue;
          double s = s0 + r.time * (best - s0);
          s        = std::max(s0, s - 4. * unit * s);
          if (s < best || found == nullptr)
            {
              best  = std::min(best, s);
              found = &query;
            }
        }
      if (found == nullptr)
        return std::nullopt;

      std::vector<double> x(n);
      for (std::size_t i = 0; i < n; ++i)
        x[i] = q[i] + best * v[i];
      FirstContact c = contact_normal(found->points,
                                      found->edge_edge,
                                      x.data(),
                                      found->orientation);
      c.s            = best;
      return c;
    }



    std::vector<FirstContact>
    touching_contacts(BoundingVolumeHierarchy &tree,
                      const double            *q,
                      const std::size_t        n,
                      const CcdSettings       &settings)
    {
      std::vector<FirstContact> touching_pairs;
      if (tree.get_triangles().empty())
        return touching_pairs;
      const std::vector<double> at_rest(n, 0.);
      double                    max_q   = 0.;
      const std::vector<Query>  queries = candidate_queries(
        tree, q, at_rest.data(), n, 0., touching_distance(settings), max_q);
      const TouchingRule rule(settings, max_q);
      for (const Query &query : queries)
        {
          FirstContact c =
            contact_normal(query.points, query.edge_edge, q, query.orientation);
          const int side =
            rule.side(c, distance_and_rate(c, q, at_rest.data()).first, q);
          if (side == 0)
            continue;
          for (double &component : c.normal)
            component *= side;
          touching_pairs.push_back(c);
        }
      return touching_pairs;
    }
  } // namespace contact
} // namespace estep
