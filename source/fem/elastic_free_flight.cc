#include <deal.II/base/exceptions.h>

#include <estep/fem/elastic_body.h>
#include <estep/fem/elastic_free_flight.h>

#include "p1_kernels.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace estep
{
  namespace
  {
    constexpr double infinity    = std::numeric_limits<double>::infinity();
    constexpr double unit        = std::numeric_limits<double>::epsilon();
    const double     not_a_point = std::numeric_limits<double>::quiet_NaN();

    /** Relative rounding bound of a cubic evaluated by Horner's rule (with a
     * safety factor). */
    constexpr double cubic_rounding = 16. * unit;

    inline double
    cubic(const double c0,
          const double c1,
          const double c2,
          const double c3,
          const double s)
    {
      return c0 + s * (c1 + s * (c2 + s * c3));
    }

    inline double
    cubic_scale(const double c0,
                const double c1,
                const double c2,
                const double c3,
                const double s)
    {
      const double t = std::abs(s);
      return std::abs(c0) +
             t * (std::abs(c1) + t * (std::abs(c2) + t * std::abs(c3)));
    }

    /** Real roots of A t^2 + B t + C = 0 (NaN where there is none), computed
     * stably. */
    inline void
    quadratic_roots(const double A,
                    const double B,
                    const double C,
                    double      &t1,
                    double      &t2)
    {
      t1 = t2 = not_a_point;
      if (A == 0.)
        {
          if (B != 0.)
            t1 = -C / B;
          return;
        }
      const double discriminant = B * B - 4. * A * C;
      if (discriminant < 0.)
        return;
      const double q = -0.5 * (B + std::copysign(std::sqrt(discriminant), B));
      if (q == 0.)
        {
          t1 = 0.;
          return;
        }
      t1 = q / A;
      t2 = C / q;
    }

    /**
     * A point s_lo <= the first root in (u, w] of the cubic, which is monotone
     * on [u, w] with J(u) above its rounding bound and J(w) not: bisection
     * keeping J(lo) > bound(lo).
     */
    double
    first_root_from_below(const double c0,
                          const double c1,
                          const double c2,
                          const double c3,
                          double       lo,
                          double       hi)
    {
      for (unsigned int it = 0; it < 200 && hi - lo > 4. * unit * hi; ++it)
        {
          const double mid = 0.5 * (lo + hi);
          if (cubic(c0, c1, c2, c3, mid) >
              cubic_rounding * cubic_scale(c0, c1, c2, c3, mid))
            lo = mid;
          else
            hi = mid;
        }
      return lo;
    }

    /**
     * The first s in (0, limit) with J(s) at or below its rounding bound, from
     * below; returns
     * @p limit if there is none. J(0) = c0 must be clearly positive.
     */
    double
    first_inversion(const double c0,
                    const double c1,
                    const double c2,
                    const double c3,
                    const double limit)
    {
      const auto positive = [&](const double s) {
        return cubic(c0, c1, c2, c3, s) >
               cubic_rounding * cubic_scale(c0, c1, c2, c3, s);
      };
      // Cheap exclusion: J(s) >= c0 - a1 s - a2 s^2 - a3 s^3 (negative parts
      // only), which is decreasing in s; if it is positive at the limit, there
      // is no root before it.
      if (std::isfinite(limit))
        {
          const double a1 = std::max(-c1, 0.), a2 = std::max(-c2, 0.),
                       a3 = std::max(-c3, 0.);
          if (c0 - limit * (a1 + limit * (a2 + limit * a3)) >
              cubic_rounding * cubic_scale(c0, c1, c2, c3, limit))
            return limit;
        }
      // Pieces of monotonicity: [0, t1], [t1, t2], [t2, infinity) for the
      // positive critical points t1 < t2 (roots of J' = c1 + 2 c2 s + 3 c3
      // s^2).
      double t[2];
      quadratic_roots(3. * c3, 2. * c2, c1, t[0], t[1]);
      if (t[1] < t[0])
        std::swap(t[0], t[1]);
      double u = 0.;
      for (unsigned int k = 0; k < 2; ++k)
        {
          if (!(t[k] > u))
            continue;
          const double w = std::min(t[k], limit);
          if (!positive(w))
            return first_root_from_below(c0, c1, c2, c3, u, w);
          if (w >= limit)
            return limit;
          u = w;
        }
      // Last piece [u, infinity): J is monotone; it has a root iff J decreases
      // to -infinity.
      const bool decreasing =
        c3 < 0. || (c3 == 0. && (c2 < 0. || (c2 == 0. && c1 < 0.)));
      if (!decreasing)
        return limit;
      double w = std::max(2. * u, 1e-300);
      // Find w with J(w) below its bound: start from a root bound of the cubic.
      const double scale = std::max({std::abs(c1 / c0),
                                     std::sqrt(std::abs(c2 / c0)),
                                     std::cbrt(std::abs(c3 / c0))});
      w                  = std::max(w, 0.5 / scale);
      for (unsigned int it = 0; it < 2100 && positive(w); ++it)
        {
          if (w >= limit)
            return limit;
          u = w;
          w *= 2.;
        }
      return std::min(first_root_from_below(c0, c1, c2, c3, u, w), limit);
    }
  } // namespace

  ElasticFreeFlight::ElasticFreeFlight(const ElasticBody &body,
                                       const Vector      &q,
                                       const Vector      &v)
    : body(body)
    , n_cells(body.n_cells())
  {
    AssertDimension(q.size(), body.n_dofs());
    AssertDimension(v.size(), body.n_dofs());
    const P1CellData &d = body.cell_data();
    c0.resize(n_cells);
    c1.resize(n_cells);
    c2.resize(n_cells);
    c3.resize(n_cells);
    scratch_1.resize(n_cells);
    scratch_2.resize(n_cells);
    double FF = 0., FG = 0., GG = 0.;
    for (unsigned int e = 0; e < n_cells; ++e)
      {
        double F[9], G[9], CF[9], CG[9];
        internal::deformation_gradient(q.data(), d, e, F);
        internal::deformation_gradient(v.data(), d, e, G);
        internal::cofactor(F, CF);
        internal::cofactor(G, CG);
        c0[e]          = internal::determinant(F, CF);
        c1[e]          = internal::contract(CF, G);
        c2[e]          = internal::contract(CG, F);
        c3[e]          = internal::determinant(G, CG);
        const double w = d.volume[e];
        FF += w * (internal::contract(F, F) - 3.);
        FG += w * internal::contract(F, G);
        GG += w * internal::contract(G, G);
      }
    const Material &material = body.material();
    const double    c        = material.quadratic_modulus();
    quadratic[0] =
      0.5 * c * FF - material.volumetric_energy(1.) * body.volume();
    quadratic[1] = c * FG;
    quadratic[2] = 0.5 * c * GG;

    // The magnitude of the terms V adds up, for its round-off: the quadratic
    // part (c/2 tr F^T F ~ 3c/2 per unit volume) dominates the volumetric
    // terms near J = 1.
    gross_magnitude = 0.5 * c * (std::abs(FF) + 3. * body.volume()) +
                      std::abs(material.volumetric_energy(1.)) * body.volume();
  }

  double
  ElasticFreeFlight::value_tolerance() const
  {
    return 64. * unit * gross_magnitude;
  }

  double
  ElasticFreeFlight::value(const double s) const
  {
    double *J = scratch_1.data();
    for (unsigned int e = 0; e < n_cells; ++e)
      J[e] = cubic(c0[e], c1[e], c2[e], c3[e], s);
    const double volumetric =
      body.material().sum_volumetric_energy(J,
                                            body.cell_data().volume.data(),
                                            n_cells);
    if (!std::isfinite(volumetric))
      return infinity;
    return volumetric + (quadratic[0] + s * (quadratic[1] + s * quadratic[2]));
  }

  LineValue
  ElasticFreeFlight::value_and_derivative(const double s) const
  {
    double *J = scratch_1.data(), *dJ = scratch_2.data();
    for (unsigned int e = 0; e < n_cells; ++e)
      {
        J[e]  = cubic(c0[e], c1[e], c2[e], c3[e], s);
        dJ[e] = c1[e] + s * (2. * c2[e] + 3. * s * c3[e]);
      }
    LineValue r = body.material().sum_volumetric_energy_and_slope(
      J, dJ, body.cell_data().volume.data(), n_cells);
    if (!std::isfinite(r.value))
      return {infinity, 0.};
    r.value += quadratic[0] + s * (quadratic[1] + s * quadratic[2]);
    r.derivative += quadratic[1] + 2. * s * quadratic[2];
    return r;
  }

  void
  ElasticFreeFlight::compute_critical_points() const
  {
    critical_1.resize(n_cells);
    critical_2.resize(n_cells);
    slope_vertex.resize(n_cells);
    scratch_3.resize(n_cells);
    scratch_4.resize(n_cells);
    scratch_5.resize(n_cells);
    scratch_6.resize(n_cells);
    for (unsigned int e = 0; e < n_cells; ++e)
      {
        quadratic_roots(
          3. * c3[e], 2. * c2[e], c1[e], critical_1[e], critical_2[e]);
        slope_vertex[e] = c3[e] != 0. ? -c2[e] / (3. * c3[e]) : not_a_point;
      }
    critical_points_ready = true;
  }

  LineEnclosure
  ElasticFreeFlight::enclose(const double a, const double b) const
  {
    Assert(a <= b, dealii::ExcMessage("enclose(a, b) needs a <= b."));
    if (!critical_points_ready)
      compute_critical_points();
    // f and f' at the midpoint, for the second-order form below (computed
    // first: value_and_derivative() uses the scratch arrays filled next).
    const LineValue fm   = value_and_derivative(0.5 * (a + b));
    double         *J_lo = scratch_1.data(), *J_hi = scratch_2.data();
    double         *dJ_lo = scratch_3.data(), *dJ_hi = scratch_4.data();
    const double    S = std::max(std::abs(a), std::abs(b));
    for (unsigned int e = 0; e < n_cells; ++e)
      {
        const double k0 = c0[e], k1 = c1[e], k2 = c2[e], k3 = c3[e];
        const double Ja = cubic(k0, k1, k2, k3, a),
                     Jb = cubic(k0, k1, k2, k3, b);
        double       lo = std::min(Ja, Jb), hi = std::max(Ja, Jb);
        const double t1 = critical_1[e], t2 = critical_2[e];
        if (t1 > a && t1 < b)
          {
            const double Jt = cubic(k0, k1, k2, k3, t1);
            lo              = std::min(lo, Jt);
            hi              = std::max(hi, Jt);
          }
        if (t2 > a && t2 < b)
          {
            const double Jt = cubic(k0, k1, k2, k3, t2);
            lo              = std::min(lo, Jt);
            hi              = std::max(hi, Jt);
          }
        const double margin = cubic_rounding * cubic_scale(k0, k1, k2, k3, S);
        J_lo[e]             = lo - margin;
        J_hi[e]             = hi + margin;

        const double da  = k1 + a * (2. * k2 + 3. * a * k3),
                     db  = k1 + b * (2. * k2 + 3. * b * k3);
        double       dlo = std::min(da, db), dhi = std::max(da, db);
        const double tv = slope_vertex[e];
        if (tv > a && tv < b)
          {
            const double dv = k1 + tv * (2. * k2 + 3. * tv * k3);
            dlo             = std::min(dlo, dv);
            dhi             = std::max(dhi, dv);
          }
        const double slope_margin =
          cubic_rounding *
          (std::abs(k1) + S * (2. * std::abs(k2) + 3. * S * std::abs(k3)));
        dJ_lo[e] = dlo - slope_margin;
        dJ_hi[e] = dhi + slope_margin;
      }
    LineEnclosure r = body.material().enclose_volumetric_sum(
      J_lo, J_hi, dJ_lo, dJ_hi, body.cell_data().volume.data(), n_cells);
    const Interval Q =
      quadratic_range(quadratic[0], quadratic[1], quadratic[2], a, b);
    const Interval dQ =
      quadratic_range(quadratic[1], 2. * quadratic[2], 0., a, b);
    r.value.lower += Q.lower;
    r.value.upper += Q.upper;
    r.derivative.lower += dQ.lower;
    r.derivative.upper += dQ.upper;
    // The final additions (and their rounding in value()).
    const double value_margin =
      4. * unit *
      (std::abs(Q.lower) + std::abs(Q.upper) + std::abs(r.value.lower) +
       std::abs(r.value.upper));
    const double slope_margin =
      4. * unit *
      (std::abs(dQ.lower) + std::abs(dQ.upper) + std::abs(r.derivative.lower) +
       std::abs(r.derivative.upper));
    if (std::isfinite(value_margin))
      {
        r.value.lower -= value_margin;
        r.value.upper += value_margin;
      }
    if (std::isfinite(slope_margin))
      {
        r.derivative.lower -= slope_margin;
        r.derivative.upper += slope_margin;
      }
    tighten_by_taylor_form(a, b, fm, r);
    return r;
  }

  void
  ElasticFreeFlight::tighten_by_taylor_form(const double     a,
                                            const double     b,
                                            const LineValue &fm,
                                            LineEnclosure   &enclosure) const
  {
    // f(x) = f(m) + f'(m) (x - m) + f''(xi) (x - m)^2 / 2 and
    // f'(x) = f'(m) + f''(xi) (x - m), with f'' enclosed per cell from
    // f_e'' = w (phi''(J) J'^2 + phi'(J) J''). The first-order enclosures
    // lose all relative accuracy when terms of V cancel (a rigid rotation
    // leaves V = O(s^4) from terms of size O(s^2)); this form does not.
    if (!std::isfinite(fm.value) || !std::isfinite(fm.derivative))
      return;
    const double *J_lo = scratch_1.data(), *J_hi = scratch_2.data();
    const double *dJ_lo = scratch_3.data(), *dJ_hi = scratch_4.data();
    double       *d2J_lo = scratch_5.data(), *d2J_hi = scratch_6.data();
    for (unsigned int e = 0; e < n_cells; ++e)
      {
        const double u      = 2. * c2[e] + 6. * c3[e] * a,
                     v      = 2. * c2[e] + 6. * c3[e] * b;
        const double margin = 4. * unit * (std::abs(u) + std::abs(v));
        d2J_lo[e]           = std::min(u, v) - margin;
        d2J_hi[e]           = std::max(u, v) + margin;
      }
    double   slope_magnitude = 0.;
    Interval curvature       = body.material().enclose_volumetric_curvature_sum(
      J_lo,
      J_hi,
      dJ_lo,
      dJ_hi,
      d2J_lo,
      d2J_hi,
      body.cell_data().volume.data(),
      n_cells,
      slope_magnitude);
    if (!std::isfinite(curvature.lower) || !std::isfinite(curvature.upper))
      return;
    curvature += Interval::point(2. * quadratic[2]);
    slope_magnitude +=
      std::abs(quadratic[1]) +
      2. * std::abs(quadratic[2]) * std::max(std::abs(a), std::abs(b));
    const double r = 0.5 * (b - a);
    const double value_margin =
      64. * unit * (gross_magnitude + std::abs(fm.value));
    const double   slope_margin = 64. * unit * slope_magnitude;
    const Interval value =
      (Interval::point(fm.value) +
       Interval{-std::abs(fm.derivative) * r, std::abs(fm.derivative) * r} +
       0.5 * curvature * Interval{0., r * r})
        .widened(0., value_margin);
    const Interval slope =
      (Interval::point(fm.derivative) + curvature * Interval{-r, r})
        .widened(0., slope_margin);
    const auto intersect = [](Interval &x, const Interval &y) {
      const Interval z{std::max(x.lower, y.lower), std::min(x.upper, y.upper)};
      if (z.lower <= z.upper)
        x = z;
    };
    intersect(enclosure.value, value);
    intersect(enclosure.derivative, slope);
  }

  double
  ElasticFreeFlight::admissible_limit() const
  {
    if (limit_ready)
      return limit;
    double best = infinity;
    for (unsigned int e = 0; e < n_cells; ++e)
      {
        if (!(c0[e] >
              cubic_rounding * cubic_scale(c0[e], c1[e], c2[e], c3[e], 0.)))
          {
            best = 0.;
            break;
          }
        best =
          std::min(best, first_inversion(c0[e], c1[e], c2[e], c3[e], best));
      }
    limit       = best;
    limit_ready = true;
    return limit;
  }

  std::array<double, 4>
  ElasticFreeFlight::jacobian_cubic(const unsigned int e) const
  {
    AssertIndexRange(e, n_cells);
    return {{c0[e], c1[e], c2[e], c3[e]}};
  }

  std::array<double, 3>
  ElasticFreeFlight::quadratic_part() const
  {
    return {{quadratic[0], quadratic[1], quadratic[2]}};
  }
} // namespace estep
