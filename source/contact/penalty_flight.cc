#include <estep/contact/penalty_flight.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace estep
{
  namespace contact
  {
    namespace
    {
      constexpr double infinity = std::numeric_limits<double>::infinity();
      constexpr double unit     = std::numeric_limits<double>::epsilon() / 2.;

      const Interval entire = {-infinity, infinity};

      inline Interval
      hull(const Interval &a, const Interval &b)
      {
        return {std::min(a.lower, b.lower), std::max(a.upper, b.upper)};
      }

      inline Interval
      negate(const Interval &a)
      {
        return {-a.upper, -a.lower};
      }

      inline bool
      excludes_zero(const Interval &a)
      {
        return a.lower > 0. || a.upper < 0.;
      }

      // a / b for b not containing 0 (entire otherwise).
      inline Interval
      divide(const Interval &a, const Interval &b)
      {
        if (!excludes_zero(b))
          return entire;
        const Interval inverse =
          Interval{1. / b.upper, 1. / b.lower}.widened(interval_rounding);
        return a * inverse;
      }

      inline Interval
      product(const Interval &a, const Interval &b)
      {
        // Guard against 0 * inf = NaN in unbounded intervals.
        const Interval r = a * b;
        if (std::isnan(r.lower) || std::isnan(r.upper))
          return entire;
        return r;
      }

      /** An interval value with an interval derivative in s. */
      struct Dual
      {
        Interval v, d;
      };

      inline Dual
      operator+(const Dual &a, const Dual &b)
      {
        return {a.v + b.v, a.d + b.d};
      }

      inline Dual
      operator-(const Dual &a, const Dual &b)
      {
        return {a.v - b.v, a.d - b.d};
      }

      inline Dual
      operator*(const Dual &a, const Dual &b)
      {
        return {product(a.v, b.v), product(a.d, b.v) + product(a.v, b.d)};
      }

      inline Dual
      operator/(const Dual &a, const Dual &b)
      {
        if (!excludes_zero(b.v))
          return {entire, entire};
        const Interval value = divide(a.v, b.v);
        const Interval slope =
          divide(product(a.d, b.v) - product(a.v, b.d), product(b.v, b.v));
        return {value, slope};
      }

      using Dual3 = std::array<Dual, 3>;

      inline Dual3
      operator-(const Dual3 &a, const Dual3 &b)
      {
        return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}};
      }

      inline Dual3
      cross(const Dual3 &a, const Dual3 &b)
      {
        return {{a[1] * b[2] - a[2] * b[1],
                 a[2] * b[0] - a[0] * b[2],
                 a[0] * b[1] - a[1] * b[0]}};
      }

      inline Dual
      dot(const Dual3 &a, const Dual3 &b)
      {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
      }

      inline double
      magnitude(const Interval &a)
      {
        return std::max(std::abs(a.lower), std::abs(a.upper));
      }

      /**
       * A chord end of one triangle on the common line: the candidates that
       * may produce it, as an interval min (lo) or max (hi) over a set of
       * possibly active candidates, some of them certainly active.
       */
      struct ChordEnd
      {
        Interval value;
        Interval slope;
      };

      struct Candidate
      {
        Dual u;
        bool certain;
      };

      // lo = min over the active candidates (is_min) or hi = max.
      ChordEnd
      extremum(const std::array<Candidate, 3> &c,
               const unsigned int              n,
               const bool                      is_min)
      {
        // For the minimum: lower bound = min of all lowers, upper bound = min
        // of the uppers of certain members. Mirror for the maximum.
        double outer = is_min ? infinity : -infinity;
        double inner = is_min ? infinity : -infinity;
        for (unsigned int i = 0; i < n; ++i)
          if (is_min)
            {
              outer = std::min(outer, c[i].u.v.lower);
              if (c[i].certain)
                inner = std::min(inner, c[i].u.v.upper);
            }
          else
            {
              outer = std::max(outer, c[i].u.v.upper);
              if (c[i].certain)
                inner = std::max(inner, c[i].u.v.lower);
            }
        ChordEnd e;
        e.value    = is_min ? Interval{outer, inner} : Interval{inner, outer};
        bool first = true;
        for (unsigned int i = 0; i < n; ++i)
          {
            const bool can_be_extremum =
              is_min ? c[i].u.v.lower <= inner : c[i].u.v.upper >= inner;
            if (!can_be_extremum)
              continue;
            e.slope = first ? c[i].u.d : hull(e.slope, c[i].u.d);
            first   = false;
          }
        if (first)
          e.slope = entire;
        return e;
      }

      // min (is_min) or max of two chord ends.
      ChordEnd
      extremum(const ChordEnd &x, const ChordEnd &y, const bool is_min)
      {
        ChordEnd e;
        if (is_min)
          e.value = {std::min(x.value.lower, y.value.lower),
                     std::min(x.value.upper, y.value.upper)};
        else
          e.value = {std::max(x.value.lower, y.value.lower),
                     std::max(x.value.upper, y.value.upper)};
        const bool x_can = is_min ? x.value.lower <= e.value.upper :
                                    x.value.upper >= e.value.lower;
        const bool y_can = is_min ? y.value.lower <= e.value.upper :
                                    y.value.upper >= e.value.lower;
        if (x_can && y_can)
          e.slope = hull(x.slope, y.slope);
        else
          e.slope = x_can ? x.slope : y.slope;
        return e;
      }

      /**
       * The chord ends (lo, hi) of triangle X (vertex distances D to the
       * other plane) along the direction d. Returns false if the triangle
       * cannot meet the plane.
       */
      bool
      chord(const std::array<Dual3, 3> &X,
            const std::array<Dual, 3>  &D,
            const Dual3                &d,
            ChordEnd                   &lo,
            ChordEnd                   &hi)
      {
        bool all_positive = true, all_negative = true;
        for (unsigned int i = 0; i < 3; ++i)
          {
            all_positive = all_positive && D[i].v.lower > 0.;
            all_negative = all_negative && D[i].v.upper < 0.;
          }
        if (all_positive || all_negative)
          return false;

        std::array<Dual, 3> u_vertex;
        for (unsigned int i = 0; i < 3; ++i)
          u_vertex[i] = dot(d, X[i]);

        std::array<Candidate, 3> candidates;
        unsigned int             n = 0;
        for (unsigned int e = 0; e < 3; ++e)
          {
            const unsigned int i = e, j = (e + 1) % 3;
            const Interval    &di = D[i].v, &dj = D[j].v;
            const bool         possible = (di.lower <= 0. && dj.upper >= 0.) ||
                                  (di.upper >= 0. && dj.lower <= 0.);
            if (!possible)
              continue;
            const bool certain = (di.lower > 0. && dj.upper < 0.) ||
                                 (di.upper < 0. && dj.lower > 0.);
            Candidate c;
            c.certain            = certain;
            const Dual     denom = D[i] - D[j];
            const Interval edge_hull =
              hull(u_vertex[i].v, u_vertex[j].v).widened(interval_rounding);
            if (excludes_zero(denom.v))
              {
                const Dual  t = D[i] / denom;
                const Dual3 P = {{X[i][0] + t * (X[j][0] - X[i][0]),
                                  X[i][1] + t * (X[j][1] - X[i][1]),
                                  X[i][2] + t * (X[j][2] - X[i][2])}};
                c.u           = dot(d, P);
                // An active crossing lies on the edge.
                c.u.v.lower = std::max(c.u.v.lower, edge_hull.lower);
                c.u.v.upper = std::min(c.u.v.upper, edge_hull.upper);
                if (c.u.v.lower > c.u.v.upper)
                  c.u.v = edge_hull;
              }
            else
              c.u = {edge_hull, entire};
            candidates[n++] = c;
          }
        if (n == 0)
          return false;
        lo = extremum(candidates, n, true);
        hi = extremum(candidates, n, false);
        return true;
      }
    } // namespace



    PenaltyEnclosure
    enclose_squared_intersection_length(const double *x0,
                                        const double *w0,
                                        const double *x1,
                                        const double *w1,
                                        const double  a,
                                        const double  b)
    {
      const Interval          S = {a, b};
      std::array<Dual3, 3>    P, Q;
      double                  L = 0.;
      std::array<Interval, 3> box0, box1;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int k = 0; k < 3; ++k)
          {
            const unsigned int m = 3 * i + k;
            P[i][k]              = {Interval::point(x0[m]) + w0[m] * S,
                                    Interval::point(w0[m])};
            Q[i][k]              = {Interval::point(x1[m]) + w1[m] * S,
                                    Interval::point(w1[m])};
            L       = std::max({L, magnitude(P[i][k].v), magnitude(Q[i][k].v)});
            box0[k] = (i == 0) ? P[i][k].v : hull(box0[k], P[i][k].v);
            box1[k] = (i == 0) ? Q[i][k].v : hull(box1[k], Q[i][k].v);
          }
      const PenaltyEnclosure zero = {{0., 0.}, {0., 0.}};

      const Dual3         n0 = cross(P[1] - P[0], P[2] - P[0]);
      const Dual3         n1 = cross(Q[1] - Q[0], Q[2] - Q[0]);
      std::array<Dual, 3> D0, D1;
      for (unsigned int i = 0; i < 3; ++i)
        {
          D0[i] = dot(n1, P[i] - Q[0]);
          D1[i] = dot(n0, Q[i] - P[0]);
        }
      const Dual3 d  = cross(n0, n1);
      const Dual  dd = dot(d, d);

      ChordEnd lo0, hi0, lo1, hi1;
      if (!chord(P, D0, d, lo0, hi0) || !chord(Q, D1, d, lo1, hi1))
        return zero;

      // Nearly parallel planes: a crude but valid bound.
      if (!(dd.v.lower > 0.))
        {
          double diameter2 = 0.;
          for (unsigned int k = 0; k < 3; ++k)
            {
              const double extent = std::min(box0[k].upper, box1[k].upper) -
                                    std::max(box0[k].lower, box1[k].lower);
              if (extent < 0.)
                return zero;
              diameter2 += extent * extent;
            }
          return {Interval{0., diameter2}.widened(1e-12, 0.), entire};
        }

      const ChordEnd B   = extremum(hi0, hi1, true);
      const ChordEnd A   = extremum(lo0, lo1, false);
      const Dual     len = {B.value - A.value, B.slope - A.slope};
      if (len.v.upper <= 0.)
        return zero;
      Dual positive_len = len;
      if (len.v.lower <= 0.)
        {
          positive_len.v.lower = 0.;
          positive_len.d       = hull(len.d, Interval{0., 0.});
        }
      const Dual g = (positive_len * positive_len) / dd;

      // Round-off of the floating-point end points in
      // squared_intersection_length(): 256 u L / sin(angle) per coordinate,
      // sin(angle) = |d| / (|n0| |n1|).
      double n0_max = 0., n1_max = 0.;
      for (unsigned int k = 0; k < 3; ++k)
        {
          n0_max += magnitude(n0[k].v) * magnitude(n0[k].v);
          n1_max += magnitude(n1[k].v) * magnitude(n1[k].v);
        }
      const double inverse_sine = std::sqrt(n0_max * n1_max / dd.v.lower) + 1.;
      const double point_error = 256. * unit * L * inverse_sine * std::sqrt(3.);
      const double length_max  = std::sqrt(std::max(g.v.upper, 0.));
      const double value_margin =
        4. * point_error * length_max + 4. * point_error * point_error;

      PenaltyEnclosure r;
      r.value       = g.v.widened(interval_rounding, value_margin);
      r.value.lower = std::max(r.value.lower, 0.);
      if (len.v.lower <= 0.)
        r.value.lower = 0.;
      double w_max = 0.;
      for (unsigned int k = 0; k < 9; ++k)
        w_max = std::max({w_max, std::abs(w0[k]), std::abs(w1[k])});
      r.derivative =
        g.d.widened(1e-12, 8. * point_error * w_max * inverse_sine);
      if (std::isnan(r.derivative.lower) || std::isnan(r.derivative.upper))
        r.derivative = entire;
      if (std::isnan(r.value.lower) || std::isnan(r.value.upper))
        r.value = entire;
      return r;
    }



    PenaltyFlight::PenaltyFlight(const PenaltyContact &contact,
                                 const double         *q,
                                 const double         *v,
                                 const std::size_t     n)
      : contact(contact)
      , q(q, q + n)
      , v(v, v + n)
      , bvh(contact.get_triangles())
    {
      for (std::size_t i = 0; i < n; ++i)
        {
          max_q = std::max(max_q, std::abs(q[i]));
          max_v = std::max(max_v, std::abs(v[i]));
        }
    }



    void
    PenaltyFlight::update_candidates(const double a, const double b) const
    {
      // Reuse the candidates of a containing interval unless it is much
      // longer (loose swept boxes give many needless candidates).
      if (cached && a >= cache_a && b <= cache_b &&
          (a == b || cache_b - cache_a <= 4. * (b - a)))
        return;
      const std::size_t n = q.size();
      scratch.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        scratch[i] = q[i] + a * v[i];
      // The computed positions q + s v may differ from the box corners by a
      // few units of round-off.
      const double margin = 8. * unit * (max_q + std::abs(b) * max_v) +
                            std::numeric_limits<double>::min();
      bvh.build_swept(scratch.data(), v.data(), n, b - a, margin);
      bvh.find_pairs(pairs);
      pairs.erase(std::remove_if(pairs.begin(),
                                 pairs.end(),
                                 [this](const auto &p) {
                                   return contact.excluded_by_group(p.first,
                                                                    p.second);
                                 }),
                  pairs.end());
      cached  = true;
      cache_a = a;
      cache_b = b;
    }



    double
    PenaltyFlight::evaluate(const double  s,
                            double       *derivative,
                            unsigned int *count) const
    {
      update_candidates(s, s);
      const auto &tris  = contact.get_triangles();
      double      total = 0., slope = 0.;
      Triangle3   T[2];
      for (const auto &[i, j] : pairs)
        {
          const TriangleIndices *t[2] = {&tris[i], &tris[j]};
          for (unsigned int m = 0; m < 2; ++m)
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int k = 0; k < 3; ++k)
                {
                  const unsigned int index = 3 * (*t[m])[a] + k;
                  T[m][a][k]               = q[index] + s * v[index];
                }
          std::array<double, 18> grad;
          const double           gap = squared_intersection_length(
            T[0], T[1], derivative != nullptr ? &grad : nullptr);
          if (gap == 0.)
            continue;
          total += gap;
          if (count != nullptr)
            ++*count;
          if (derivative != nullptr)
            for (unsigned int m = 0; m < 2; ++m)
              for (unsigned int a = 0; a < 3; ++a)
                for (unsigned int k = 0; k < 3; ++k)
                  slope += grad[9 * m + 3 * a + k] * v[3 * (*t[m])[a] + k];
        }
      const double scale = 1. / (2. * contact.get_eps());
      if (derivative != nullptr)
        *derivative = slope * scale;
      return total * scale;
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



    PenaltyEnclosure
    PenaltyFlight::enclose(const double a, const double b) const
    {
      if (!(a <= b))
        throw std::invalid_argument("PenaltyFlight::enclose: a > b");
      update_candidates(a, b);
      const auto &tris  = contact.get_triangles();
      Interval    value = {0., 0.}, slope = {0., 0.};
      double      x[2][9], w[2][9];
      for (const auto &[i, j] : pairs)
        {
          const TriangleIndices *t[2] = {&tris[i], &tris[j]};
          for (unsigned int m = 0; m < 2; ++m)
            for (unsigned int p = 0; p < 3; ++p)
              for (unsigned int k = 0; k < 3; ++k)
                {
                  x[m][3 * p + k] = q[3 * (*t[m])[p] + k];
                  w[m][3 * p + k] = v[3 * (*t[m])[p] + k];
                }
          const PenaltyEnclosure e =
            enclose_squared_intersection_length(x[0], w[0], x[1], w[1], a, b);
          if (e.value.upper == 0. && e.derivative.lower == 0. &&
              e.derivative.upper == 0.)
            continue;
          value += e.value;
          slope += e.derivative;
        }
      const double     scale = 1. / (2. * contact.get_eps());
      PenaltyEnclosure r     = {scale * value, scale * slope};
      // Mean-value form: I(s) in I(m) + I'([a, b]) (s - m). Its excess is
      // quadratic in b - a, so it decides near-tangential approaches to a
      // level that the direct enclosure (linear excess) cannot. The point
      // value is widened for its round-off.
      if (b > a && std::isfinite(r.derivative.lower) &&
          std::isfinite(r.derivative.upper))
        {
          const double   m       = 0.5 * (a + b);
          const double   I_m     = this->value(m);
          const Interval centre  = Interval::point(I_m).widened(1e-12, 0.);
          const Interval offsets = {a - m, b - m};
          const Interval mv      = centre + r.derivative * offsets;
          r.value.lower          = std::max(r.value.lower, mv.lower);
          r.value.upper          = std::min(r.value.upper, mv.upper);
          if (r.value.lower > r.value.upper)
            r.value = Interval::hull(mv.lower, mv.upper);
          r.value.lower = std::max(r.value.lower, 0.);
        }
      return r;
    }
  } // namespace contact
} // namespace estep
