#include <estep/base/distributed_blocks.h>
#include <estep/contact/penalty_flight.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace estep
{
  namespace
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    constexpr double unit     = std::numeric_limits<double>::epsilon() / 2.;

    const Interval entire = {-infinity, infinity};

    inline double
    magnitude(const Interval &a)
    {
      return std::max(std::abs(a.lower), std::abs(a.upper));
    }

    inline Interval
    hull(const Interval &a, const Interval &b)
    {
      return {std::min(a.lower, b.lower), std::max(a.upper, b.upper)};
    }
  } // namespace



  namespace contact
  {
    namespace
    {
      /** Bound of the relative rounding of the polynomial coefficients below,
       * relative to the sums of the magnitudes of their terms (about 15 units
       * of round-off along the longest chain of operations, with a safety
       * factor). */
      constexpr double coefficient_rounding = 64. * unit;

      /** Relative rounding of the few operations that turn coefficients into
       * ranges. */
      constexpr double range_rounding = 8. * unit;

      /**
       * A vector linear in t = s - m, y + t z, with the magnitudes of the
       * terms it was computed from (for its rounding).
       */
      struct Linear3
      {
        std::array<double, 3> y, z, my, mz;
      };

      /** A vector quadratic in t, sum_k c[k] t^k, with term magnitudes. */
      struct Quadratic3
      {
        std::array<std::array<double, 3>, 3> c, a;
      };

      /** A cubic in t, sum_k c[k] t^k, with term magnitudes a[k]: the computed
       * c[k] is within coefficient_rounding a[k] of the exact one. */
      struct Cubic
      {
        std::array<double, 4> c = {{0., 0., 0., 0.}};
        std::array<double, 4> a = {{0., 0., 0., 0.}};
      };

      /** Enclosures of a function and its first two derivatives over |t| <= r.
       */
      struct Jet
      {
        Interval v, d, dd;
      };

      using Jet3 = std::array<Jet, 3>;

      /** The vector from vertex j of @p xj to vertex i of @p xi at s = m + t,
       * (xi - xj) + s (wi - wj), formed from differences (so that it is
       * accurate relative to its own size). */
      Linear3
      difference(const double      *xi,
                 const double      *wi,
                 const double      *xj,
                 const double      *wj,
                 const double       m,
                 const unsigned int i,
                 const unsigned int j)
      {
        Linear3 l;
        for (unsigned int c = 0; c < 3; ++c)
          {
            const double dx = xi[3 * i + c] - xj[3 * j + c];
            const double dw = wi[3 * i + c] - wj[3 * j + c];
            l.y[c]          = dx + m * dw;
            l.z[c]          = dw;
            l.my[c]         = std::abs(dx) + std::abs(m * dw);
            l.mz[c]         = std::abs(dw);
          }
        return l;
      }

      Quadratic3
      cross(const Linear3 &p, const Linear3 &q)
      {
        const auto x = [](const std::array<double, 3> &a,
                          const std::array<double, 3> &b,
                          const unsigned int           c,
                          const bool                   absolute) {
          const unsigned int c1 = (c + 1) % 3, c2 = (c + 2) % 3;
          return absolute ? a[c1] * b[c2] + a[c2] * b[c1] :
                            a[c1] * b[c2] - a[c2] * b[c1];
        };
        Quadratic3 n;
        for (unsigned int c = 0; c < 3; ++c)
          {
            n.c[0][c] = x(p.y, q.y, c, false);
            n.c[1][c] = x(p.y, q.z, c, false) + x(p.z, q.y, c, false);
            n.c[2][c] = x(p.z, q.z, c, false);
            n.a[0][c] = x(p.my, q.my, c, true);
            n.a[1][c] = x(p.my, q.mz, c, true) + x(p.mz, q.my, c, true);
            n.a[2][c] = x(p.mz, q.mz, c, true);
          }
        return n;
      }

      Cubic
      dot(const Quadratic3 &n, const Linear3 &p)
      {
        Cubic r;
        for (unsigned int c = 0; c < 3; ++c)
          {
            r.c[0] += n.c[0][c] * p.y[c];
            r.c[1] += n.c[1][c] * p.y[c] + n.c[0][c] * p.z[c];
            r.c[2] += n.c[2][c] * p.y[c] + n.c[1][c] * p.z[c];
            r.c[3] += n.c[2][c] * p.z[c];
            r.a[0] += n.a[0][c] * p.my[c];
            r.a[1] += n.a[1][c] * p.my[c] + n.a[0][c] * p.mz[c];
            r.a[2] += n.a[2][c] * p.my[c] + n.a[1][c] * p.mz[c];
            r.a[3] += n.a[2][c] * p.mz[c];
          }
        return r;
      }

      Cubic
      operator-(const Cubic &p, const Cubic &q)
      {
        Cubic r;
        for (unsigned int k = 0; k < 4; ++k)
          {
            r.c[k] = p.c[k] - q.c[k];
            r.a[k] = p.a[k] + q.a[k];
          }
        return r;
      }

      /** c + [-spread, spread] + [min(bend, 0), max(bend, 0)], widened for
       * the rounding of these operations. */
      Interval
      range(const double c, const double bend, const double spread)
      {
        const double margin =
          range_rounding * (std::abs(c) + std::abs(bend) + spread);
        return {c + std::min(bend, 0.) - spread - margin,
                c + std::max(bend, 0.) + spread + margin};
      }

      /** The jet of the cubic over |t| <= r, from its Taylor coefficients
       * about t = 0 and their rounding bounds. */
      Jet
      jet(const Cubic &p, const double r)
      {
        const double r2 = r * r * (1. + 2. * unit), r3 = r2 * r * (1. + unit);
        std::array<double, 4> e;
        for (unsigned int k = 0; k < 4; ++k)
          e[k] = coefficient_rounding * p.a[k];
        const auto &c = p.c;
        Jet         j;
        // c0 + c1 t + c2 t^2 + c3 t^3, c1 + 2 c2 t + 3 c3 t^2, 2 c2 + 6 c3 t.
        j.v  = range(c[0],
                    c[2] * r2,
                    std::abs(c[1]) * r + std::abs(c[3]) * r3 + e[0] + e[1] * r +
                      e[2] * r2 + e[3] * r3);
        j.d  = range(c[1],
                    3. * c[3] * r2,
                    2. * std::abs(c[2]) * r + e[1] + 2. * e[2] * r +
                      3. * e[3] * r2);
        j.dd = range(2. * c[2],
                     0.,
                     6. * std::abs(c[3]) * r + 2. * e[2] + 6. * e[3] * r);
        return j;
      }

      /** The jets of the components of a linear vector over |t| <= r. */
      Jet3
      jet(const Linear3 &l, const double r)
      {
        Jet3 j;
        for (unsigned int c = 0; c < 3; ++c)
          {
            const double e = 4. * unit * (l.my[c] + l.mz[c] * r);
            j[c].v         = range(l.y[c], 0., std::abs(l.z[c]) * r + e);
            j[c].d         = range(l.z[c], 0., 2. * unit * l.mz[c]);
            j[c].dd        = {0., 0.};
          }
        return j;
      }

      inline bool
      excludes_zero(const Interval &a)
      {
        return a.lower > 0. || a.upper < 0.;
      }

      /** a * b, unbounded instead of NaN (0 * infinity). */
      inline Interval
      times(const Interval &a, const Interval &b)
      {
        const Interval r = a * b;
        return (std::isnan(r.lower) || std::isnan(r.upper)) ? entire : r;
      }

      /** a / b for b not containing 0. */
      inline Interval
      divide(const Interval &a, const Interval &b)
      {
        const Interval inverse =
          Interval{1. / b.upper, 1. / b.lower}.widened(interval_rounding);
        return times(a, inverse);
      }

      inline Jet
      operator+(const Jet &a, const Jet &b)
      {
        return {a.v + b.v, a.d + b.d, a.dd + b.dd};
      }

      inline Jet
      operator-(const Jet &a, const Jet &b)
      {
        return {a.v - b.v, a.d - b.d, a.dd - b.dd};
      }

      inline Jet
      operator*(const Jet &a, const Jet &b)
      {
        return {times(a.v, b.v),
                times(a.d, b.v) + times(a.v, b.d),
                times(a.dd, b.v) + 2. * times(a.d, b.d) + times(a.v, b.dd)};
      }

      /** a / b (b.v must exclude 0): q' = (a' - q b') / b, q'' = (a'' - 2 q'
       * b' - q b'') / b. */
      inline Jet
      operator/(const Jet &a, const Jet &b)
      {
        Jet q;
        q.v  = divide(a.v, b.v);
        q.d  = divide(a.d - times(q.v, b.d), b.v);
        q.dd = divide(a.dd - 2. * times(q.d, b.d) - times(q.v, b.dd), b.v);
        return q;
      }

      /** An edge (i, j) of triangle k (0 or 1) crossing the plane of the
       * other triangle. */
      struct Edge
      {
        unsigned int k, i, j;
      };

      /** Everything about a pair along [m - r, m + r] that the cases below
       * share. */
      struct PairGeometry
      {
        const double *x[2], *w[2];
        double        m, r;
        /** Face normals (quadratics in t). */
        Quadratic3 normal[2];
        /** distance[k][i]: vertex i of triangle k to the plane of the other
         * (scaled by the length of its normal), and its jet. */
        Cubic distance[2][3];
        Jet   distance_jet[2][3];
        /** Its proven sign, 0 if not proven. */
        int sign[2][3];

        /** The vector from vertex j of triangle l to vertex i of triangle k.
         */
        Linear3
        vector(const unsigned int k,
               const unsigned int i,
               const unsigned int l,
               const unsigned int j) const
        {
          return difference(x[k], w[k], x[l], w[l], m, i, j);
        }

        /** The jet of the crossing X = x_i + D_i / (D_i - D_j) (x_j - x_i) of
         * edge e with the other plane, relative to vertex 0 of triangle 0;
         * false if D_i - D_j is not bounded away from 0. Also returns the jet
         * of S = D_i - D_j. */
        bool
        crossing(const Edge &e, Jet3 &X, Jet &S) const
        {
          S = jet(distance[e.k][e.i] - distance[e.k][e.j], r);
          if (!excludes_zero(S.v))
            return false;
          const Jet  t    = distance_jet[e.k][e.i] / S;
          const Jet3 base = jet(vector(e.k, e.i, 0, 0), r);
          const Jet3 edge = jet(vector(e.k, e.j, e.k, e.i), r);
          for (unsigned int c = 0; c < 3; ++c)
            X[c] = base[c] + t * edge[c];
          return true;
        }

        /**
         * The sign of u(X_e0) - u(X_e1) along d = n0 x n1 for an edge e0 of
         * triangle 0 and an edge e1 of triangle 1, both crossing: with X on
         * (a, b) and Y on (c, e), d . (X - Y) has the sign of -orient3d(a, b,
         * c, e) (D_b - D_a) (E_e - E_c) (derivation in
         * source/contact/triangle_intersection.cc). 0 if not proven.
         */
        int
        order(const Edge &e0, const Edge &e1) const
        {
          const Cubic det =
            dot(cross(vector(0, e0.j, 0, e0.i), vector(1, e1.i, 0, e0.i)),
                vector(1, e1.j, 0, e0.i));
          const Interval o = jet(det, r).v;
          if (!excludes_zero(o))
            return 0;
          return (o.lower > 0. ? -1 : 1) * sign[0][e0.j] * sign[1][e1.j];
        }
      };

      /** The largest length of a linear vector over |t| <= r. */
      double
      max_length(const Linear3 &l, const double r)
      {
        double s = 0.;
        for (unsigned int c = 0; c < 3; ++c)
          {
            const double x = std::abs(l.y[c]) + std::abs(l.z[c]) * r;
            s += x * x;
          }
        return std::sqrt(s) * (1. + 4. * unit);
      }

      /** The smallest length of a linear vector over |t| <= r (or 0). */
      double
      min_length(const Linear3 &l, const double r)
      {
        double y = 0., z = 0.;
        for (unsigned int c = 0; c < 3; ++c)
          {
            y += l.y[c] * l.y[c];
            z += l.z[c] * l.z[c];
          }
        return std::max((std::sqrt(y) - std::sqrt(z) * r) * (1. - 4. * unit),
                        0.);
      }

      /** The largest magnitude of a quadratic vector over |t| <= r. */
      double
      max_length(const Quadratic3 &n, const double r)
      {
        double s = 0.;
        for (unsigned int c = 0; c < 3; ++c)
          {
            const double x = std::abs(n.c[0][c]) + std::abs(n.c[1][c]) * r +
                             std::abs(n.c[2][c]) * r * r +
                             coefficient_rounding *
                               (n.a[0][c] + n.a[1][c] * r + n.a[2][c] * r * r);
            s += x * x;
          }
        return std::sqrt(s) * (1. + 4. * unit);
      }

      /**
       * The stated round-off bounds of a computed crossing point of edge @p e
       * (position error) and of its velocity (see the header), from the jet of
       * S = D_i - D_j.
       */
      struct CrossingError
      {
        double position, velocity;
      };

      CrossingError
      crossing_error(const PairGeometry &g,
                     const Edge         &e,
                     const Jet          &S,
                     const double        L,
                     const double        w_max)
      {
        const unsigned int f                  = 1 - e.k;
        double             shortest_face_edge = infinity;
        for (unsigned int i = 0; i < 3; ++i)
          shortest_face_edge =
            std::min(shortest_face_edge,
                     min_length(g.vector(f, (i + 1) % 3, f, i), g.r));
        const double edge  = max_length(g.vector(e.k, e.j, e.k, e.i), g.r);
        const double S_min = std::min(std::abs(S.v.lower), std::abs(S.v.upper));
        // 1 / sin(angle between edge and plane) = |n| |e| / |S|.
        const double inverse_sine = max_length(g.normal[f], g.r) * edge / S_min;
        CrossingError error;
        error.position =
          256. * unit * (L + edge * L / shortest_face_edge) * inverse_sine;
        error.velocity = error.position * (w_max / L + magnitude(S.d) / S_min);
        return error;
      }

      /** Largest |X| over the jet's values (@p part = &Jet::v) or largest
       * |X'| (&Jet::d). */
      double
      max_norm(const Jet3 &X, Interval Jet::*part)
      {
        double s = 0.;
        for (const Jet &c : X)
          s += magnitude(c.*part) * magnitude(c.*part);
        return std::sqrt(s);
      }

      /** value_error and slope_error of g = |Delta|^2 and g' = 2 Delta .
       * Delta' from the errors of the end points, |Delta| <= length and
       * |Delta'| <= rate. */
      void
      set_errors(LineTaylorForm &form,
                 const double    length,
                 const double    rate,
                 const double    position_error,
                 const double    velocity_error)
      {
        const double dp = 2. * position_error, dv = 2. * velocity_error;
        form.value_error =
          2. * length * dp + dp * dp + 4. * unit * length * length;
        form.slope_error =
          2. * (dp * rate + length * dv + dp * dv) + 8. * unit * length * rate;
      }
    } // namespace



    LineTaylorForm
    squared_intersection_length_form(const double *x0,
                                     const double *w0,
                                     const double *x1,
                                     const double *w1,
                                     const double  m,
                                     const double  r)
    {
      LineTaylorForm form;
      form.centre = m;
      form.radius = r;

      // Value and slope at the centre, as the point evaluation computes them.
      PairGeometry g;
      g.x[0] = x0, g.x[1] = x1, g.w[0] = w0, g.w[1] = w1;
      g.m = m, g.r = r;
      Triangle3 T[2];
      double    L = 0., w_max = 0.;
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            {
              const double x = g.x[k][3 * i + c], w = g.w[k][3 * i + c];
              T[k][i][c] = x + m * w;
              L          = std::max(L, std::abs(T[k][i][c]) + std::abs(w) * r);
              w_max      = std::max(w_max, std::abs(w));
            }
      std::array<double, 18> gradient;
      form.value = squared_intersection_length(T[0], T[1], &gradient);
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int n = 0; n < 9; ++n)
          form.slope += gradient[9 * k + n] * g.w[k][n];

      // Normals and vertex-plane distances.
      for (unsigned int k = 0; k < 2; ++k)
        g.normal[k] = cross(g.vector(k, 1, k, 0), g.vector(k, 2, k, 0));
      bool proven = true;
      for (unsigned int k = 0; k < 2; ++k)
        {
          int n_positive = 0, n_negative = 0;
          for (unsigned int i = 0; i < 3; ++i)
            {
              g.distance[k][i] = dot(g.normal[1 - k], g.vector(k, i, 1 - k, 0));
              g.distance_jet[k][i] = jet(g.distance[k][i], r);
              const Interval &D    = g.distance_jet[k][i].v;
              g.sign[k][i]         = D.lower > 0. ? 1 : (D.upper < 0. ? -1 : 0);
              n_positive += g.sign[k][i] > 0;
              n_negative += g.sign[k][i] < 0;
              proven = proven && g.sign[k][i] != 0;
            }
          if (n_positive == 3 || n_negative == 3)
            return form; // one side of the plane: g = 0 on the interval
        }

      if (proven)
        {
          // The chord of each triangle on the common line runs between the
          // crossings of the two edges at its alone vertex; for triangle 0,
          // d . (X_ik - X_ij) has the sign of -D_i (i alone, j = i + 1, k =
          // i + 2), for triangle 1 that of +D_i (d = n0 x n1).
          Edge low[2], high[2];
          for (unsigned int k = 0; k < 2; ++k)
            {
              unsigned int alone = 0;
              for (unsigned int i = 0; i < 3; ++i)
                if (g.sign[k][i] != g.sign[k][(i + 1) % 3] &&
                    g.sign[k][i] != g.sign[k][(i + 2) % 3])
                  alone = i;
              const Edge next        = {k, alone, (alone + 1) % 3};
              const Edge other       = {k, alone, (alone + 2) % 3};
              const bool next_is_low = (k == 0) == (g.sign[k][alone] < 0);
              low[k]                 = next_is_low ? next : other;
              high[k]                = next_is_low ? other : next;
            }
          // A = the later start, B = the earlier end along d.
          const int start_order = g.order(low[0], low[1]);
          const int end_order   = g.order(high[0], high[1]);
          if (start_order != 0 && end_order != 0)
            {
              const Edge &A = start_order > 0 ? low[0] : low[1];
              const Edge &B = end_order < 0 ? high[0] : high[1];
              const int   length_sign =
                A.k == B.k ? 1 : (A.k == 0 ? -g.order(A, B) : g.order(B, A));
              if (length_sign < 0)
                return form; // the chords do not overlap: g = 0
              Jet3 XA, XB;
              Jet  SA, SB;
              if (g.crossing(A, XA, SA) && g.crossing(B, XB, SB))
                {
                  Jet3 delta;
                  for (unsigned int c = 0; c < 3; ++c)
                    delta[c] = XB[c] - XA[c];
                  const Jet squared = delta[0] * delta[0] +
                                      delta[1] * delta[1] + delta[2] * delta[2];
                  form.curvature         = length_sign > 0 ?
                                             squared.dd :
                                             hull(squared.dd, Interval{0., 0.});
                  const CrossingError eA = crossing_error(g, A, SA, L, w_max);
                  const CrossingError eB = crossing_error(g, B, SB, L, w_max);
                  set_errors(form,
                             max_norm(delta, &Jet::v),
                             max_norm(delta, &Jet::d),
                             std::max(eA.position, eB.position),
                             std::max(eA.velocity, eB.velocity));
                  return form;
                }
            }
        }

      // A kink is possible (a vertex may cross a plane, or chord ends may
      // swap): the slope lies in the hull of 0 and of the slopes of |X_e' -
      // X_e|^2 over pairs of edges that may generate the end points.
      std::array<Jet3, 6> X;
      unsigned int        n_edges        = 0;
      double              position_error = 0., velocity_error = 0.;
      for (unsigned int k = 0; k < 2; ++k)
        for (unsigned int i = 0; i < 3; ++i)
          {
            const unsigned int j  = (i + 1) % 3;
            const Interval    &Di = g.distance_jet[k][i].v;
            const Interval    &Dj = g.distance_jet[k][j].v;
            if (!((Di.lower <= 0. && Dj.upper >= 0.) ||
                  (Di.upper >= 0. && Dj.lower <= 0.)))
              continue;
            Jet        S;
            const Edge e = {k, i, j};
            if (!g.crossing(e, X[n_edges], S))
              {
                form.slope_offset = entire;
                form.value_error  = infinity;
                return form;
              }
            const CrossingError error = crossing_error(g, e, S, L, w_max);
            position_error = std::max(position_error, error.position);
            velocity_error = std::max(velocity_error, error.velocity);
            ++n_edges;
          }
      Interval slopes = {0., 0.};
      double   length = 0., rate = 0.;
      for (unsigned int p = 0; p < n_edges; ++p)
        for (unsigned int q = p + 1; q < n_edges; ++q)
          {
            Interval s = {0., 0.};
            Jet3     delta;
            for (unsigned int c = 0; c < 3; ++c)
              {
                delta[c] = X[q][c] - X[p][c];
                s        = s + 2. * times(delta[c].v, delta[c].d);
              }
            slopes = hull(slopes, s);
            length = std::max(length, max_norm(delta, &Jet::v));
            rate   = std::max(rate, max_norm(delta, &Jet::d));
          }
      form.slope_offset = slopes - Interval::point(form.slope);
      set_errors(form, length, rate, position_error, velocity_error);
      return form;
    }



    PenaltyFlight::PenaltyFlight(const PenaltyContact &contact,
                                 const double         *q,
                                 const double         *v,
                                 const std::size_t     n)
      : contact(contact)
      , q(q, q + n)
      , v(v, v + n)
      , max_q(contact.hierarchy().largest_vertex_coordinate(q))
      , max_v(contact.hierarchy().largest_vertex_coordinate(v))
      , bvh(contact.hierarchy())
      , swept_boxes(contact.get_triangles().size())
      , box_query(contact.get_triangles().size(), 0)
    {}



    void
    PenaltyFlight::update_candidates(const double a, const double b) const
    {
      // The computed positions q + s v may differ from the exact ones (and
      // the box corners) by a few units of round-off.
      const double margin =
        8. * unit * (max_q + std::max(std::abs(a), std::abs(b)) * max_v) +
        std::numeric_limits<double>::min();
      if (!(cached && a >= cache_a && b <= cache_b))
        {
          // A broad phase over [a, a + 4 (b - a)], the contact's hierarchy
          // refitted: the search examines [a, b] and its parts, then the
          // next, twice longer window.
          const double      end = a + 4. * (b - a);
          const std::size_t n   = q.size();
          scratch.resize(n);
          for (const unsigned int i : bvh.vertices())
            for (unsigned int d = 0; d < 3; ++d)
              scratch[3 * i + d] = q[3 * i + d] + a * v[3 * i + d];
          bvh.refit_swept(scratch.data(),
                          v.data(),
                          n,
                          end - a,
                          margin + 8. * unit * std::abs(end) * max_v);
          bvh.find_pairs(broad_pairs);
          // In the order of the triangle numbers, not the tree's, which
          // depends on the window above: so the pairs of an interval, and
          // with them the bits of a value, do not depend on the queries
          // made before (an enclosure's sample is what a later evaluation at
          // its point gives).
          std::sort(broad_pairs.begin(), broad_pairs.end());
          cached  = true;
          cache_a = a;
          cache_b = end;
        }
      // The pairs of the broad phase whose boxes swept over [a, b] overlap;
      // the box of a triangle made once, when a pair first needs it (a
      // triangle is in several pairs, and most in none).
      const auto &tris = contact.get_triangles();
      ++n_queries;
      const auto box = [&](const unsigned int t) -> const BoundingBox & {
        BoundingBox &box = swept_boxes[t];
        if (box_query[t] == n_queries)
          return box;
        box_query[t] = n_queries;
        box          = BoundingBox::empty();
        for (const unsigned int i : tris[t])
          for (unsigned int k = 0; k < 3; ++k)
            for (const double s : {a, b})
              {
                const double x = q[3 * i + k] + s * v[3 * i + k];
                box.lower[k]   = std::min(box.lower[k], x - margin);
                box.upper[k]   = std::max(box.upper[k], x + margin);
              }
        return box;
      };
      pairs.clear();
      for (const auto &p : broad_pairs)
        if (box(p.first).overlaps(box(p.second)))
          pairs.push_back(p);
    }



    double
    PenaltyFlight::evaluate(const double  s,
                            double       *derivative,
                            unsigned int *count) const
    {
      update_candidates(s, s);
      return contact.sum_along_line(
        pairs, q.data(), v.data(), s, derivative, count);
    }



    double
    PenaltyFlight::value(const double s) const
    {
      return evaluate(s, nullptr, nullptr);
    }



    std::pair<double, double>
    PenaltyFlight::value_and_derivative(const double s) const
    {
      double       d     = 0.;
      const double value = evaluate(s, &d, nullptr);
      return {value, d};
    }



    unsigned int
    PenaltyFlight::n_intersecting_pairs(const double s) const
    {
      unsigned int count = 0;
      evaluate(s, nullptr, &count);
      return count;
    }



    LineTaylorForm
    PenaltyFlight::taylor_form(const double a, const double b) const
    {
      if (!(a <= b))
        throw std::invalid_argument("PenaltyFlight::taylor_form: a > b");
      update_candidates(a, b);
      const LineTaylorForm about = LineTaylorForm::about_centre_of(a, b);
      const auto          &tris  = contact.get_triangles();
      const unsigned int   size  = PenaltyContact::pairs_per_block;
      const LineTaylorForm sum   = sum_over_shared_blocks<LineTaylorForm>(
        std::max(1u, n_blocks(pairs.size(), size)), [&](const unsigned int b) {
          const BlockRange block = block_range(b, pairs.size(), size);
          LineTaylorForm   form  = about;
          double           x[2][9], w[2][9];
          for (unsigned int k = block.begin; k < block.end; ++k)
            {
              const auto [i, j]           = pairs[k];
              const TriangleIndices *t[2] = {&tris[i], &tris[j]};
              for (unsigned int m = 0; m < 2; ++m)
                for (unsigned int p = 0; p < 3; ++p)
                  for (unsigned int c = 0; c < 3; ++c)
                    {
                      x[m][3 * p + c] = q[3 * (*t[m])[p] + c];
                      w[m][3 * p + c] = v[3 * (*t[m])[p] + c];
                    }
              form += squared_intersection_length_form(
                x[0], w[0], x[1], w[1], form.centre, form.radius);
            }
          return form;
        });
      return sum.scaled(1. / (2. * contact.get_eps()));
    }



    LineEnclosure
    PenaltyFlight::enclose(const double a, const double b) const
    {
      return taylor_form(a, b).enclosure();
    }



    double
    PenaltyFlight::value_tolerance() const
    {
      if (tolerance < 0.)
        tolerance = taylor_form(0., 0.).value_error;
      return tolerance;
    }
  } // namespace contact
} // namespace estep
