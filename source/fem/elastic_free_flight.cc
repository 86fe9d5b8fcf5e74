#include <deal.II/base/exceptions.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/elastic_free_flight.h>

#include "p1_kernels.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

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

    /** Relative rounding bound of the centred (Taylor) form of a cubic and
     * its derivatives about a point, together with the Horner evaluation of
     * the cubic (with a safety factor). */
    constexpr double jacobian_rounding = 64. * unit;

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

    /** Sums over cells of |Omega_e| (|F_e|^2 - 3), |Omega_e| F_e : G_e and
     * |Omega_e| |G_e|^2. */
    struct QuadraticSums
    {
      double FF, FG, GG;
      QuadraticSums &
      operator+=(const QuadraticSums &other)
      {
        FF += other.FF;
        FG += other.FG;
        GG += other.GG;
        return *this;
      }
    };

    /**
     * The cubic coefficients of J_e(s) of the cells of @p cells (padding
     * included) and their QuadraticSums, four cells at a time (q and v
     * padded, see load_triples()).
     */
    ESTEP_LANE_KERNEL QuadraticSums
    build_cubics(const P1CellData &d,
                 const double     *q,
                 const double     *v,
                 const BlockRange  cells,
                 double           *c0,
                 double           *c1,
                 double           *c2,
                 double           *c3)
    {
      Lanes FF = lanes(0.), FG = lanes(0.), GG = lanes(0.);
      for (unsigned int e = cells.begin; e < cells.end; e += n_lanes)
        {
          Lanes F[9], G[9], CF[9], CG[9];
          internal::deformation_gradient(q, d, e, F);
          internal::deformation_gradient(v, d, e, G);
          internal::cofactor(F, CF);
          internal::cofactor(G, CG);
          const unsigned int h = d.at(e);
          store_lanes(c0 + h, internal::determinant(F, CF));
          store_lanes(c1 + h, internal::contract(CF, G));
          store_lanes(c2 + h, internal::contract(CG, F));
          store_lanes(c3 + h, internal::determinant(G, CG));
          const Lanes w = load_lanes(d.volume.data() + h);
          FF += w * (internal::contract(F, F) - 3.);
          FG += w * internal::contract(F, G);
          GG += w * internal::contract(G, G);
        }
      return {sum(FF), sum(FG), sum(GG)};
    }

    /**
     * J[i] = c0[i] + c1[i] s + c2[i] s^2 + c3[i] s^3 (Horner) and, if @p dJ
     * is not null, dJ[i] = J'(s), for i < n rounded up to a multiple of 4 (the
     * arrays are padded).
     */
    ESTEP_LANE_KERNEL void
    evaluate_cubics(const double       s,
                    const double      *c0,
                    const double      *c1,
                    const double      *c2,
                    const double      *c3,
                    const unsigned int n,
                    double            *J,
                    double            *dJ)
    {
      for (unsigned int i = 0; i < n; i += n_lanes)
        {
          const Lanes k1 = load_lanes(c1 + i), k2 = load_lanes(c2 + i),
                      k3 = load_lanes(c3 + i);
          store_lanes(J + i, load_lanes(c0 + i) + s * (k1 + s * (k2 + s * k3)));
          if (dJ != nullptr)
            store_lanes(dJ + i, k1 + s * (2. * k2 + 3. * s * k3));
        }
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
    // Per cell this rank holds (at(e)); not value-initialised: every entry is
    // written before it is read.
    const unsigned int n_padded = body.cell_data().n_padded_cells();
    n_held                      = body.cell_data().volume.size();
    storage.reset(new double[6 * std::size_t(n_held)]);
    c0      = storage.get();
    c1      = c0 + n_held;
    c2      = c1 + n_held;
    c3      = c2 + n_held;
    scratch = c3 + n_held;
    // Not value-initialised either (copy_padded() writes every entry that
    // the cells this rank computes read).
    const std::unique_ptr<double[]> padded(new double[2 * (q.size() + 1)]);
    double *const padded_q = padded.get(), *const padded_v =
                                             padded_q + q.size() + 1;
    const std::vector<BlockRange> *const kept = body.kept_coordinates();
    internal::copy_padded(q.data(), q.size(), padded_q, kept);
    internal::copy_padded(v.data(), v.size(), padded_v, kept);
    const QuadraticSums sums = sum_over_distributed_blocks<QuadraticSums>(
      n_blocks(n_padded), [&](const unsigned int b) {
        return build_cubics(body.cell_data(),
                            padded_q,
                            padded_v,
                            block_range(b, n_padded),
                            c0,
                            c1,
                            c2,
                            c3);
      });
    const double    FF = sums.FF, FG = sums.FG, GG = sums.GG;
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

  LineValue
  ElasticFreeFlight::volumetric_part(const double s, const bool slope) const
  {
    return sum_over_distributed_blocks<LineValue>(
      n_blocks(n_cells), [&](const unsigned int b) {
        const BlockRange   cells  = block_range(b, n_cells);
        const unsigned int count  = cells.end - cells.begin;
        const unsigned int h      = at(cells.begin);
        const double      *volume = body.cell_data().volume.data() + h;
        // At s = 0 the cubics are their constant terms: Horner's c0 + 0 (...)
        // would give the same bits, one pass over the cells later.
        if (s == 0. && !slope)
          return LineValue{
            body.material().sum_volumetric_energy(c0 + h, volume, count), 0.};
        double *J  = scratch + h;
        double *dJ = slope ? J + n_held : nullptr;
        evaluate_cubics(s, c0 + h, c1 + h, c2 + h, c3 + h, count, J, dJ);
        if (slope)
          return body.material().sum_volumetric_energy_and_slope(J,
                                                                 dJ,
                                                                 volume,
                                                                 count);
        return LineValue{
          body.material().sum_volumetric_energy(J, volume, count), 0.};
      });
  }

  double
  ElasticFreeFlight::value(const double s) const
  {
    return with_quadratic_part(s, volumetric_part(s, false)).value;
  }

  LineValue
  ElasticFreeFlight::value_and_derivative(const double s) const
  {
    return with_quadratic_part(s, volumetric_part(s, true));
  }

  LineValue
  ElasticFreeFlight::with_quadratic_part(const double s,
                                         LineValue    volumetric) const
  {
    if (!std::isfinite(volumetric.value))
      return {infinity, 0.};
    volumetric.value += quadratic[0] + s * (quadratic[1] + s * quadratic[2]);
    volumetric.derivative += quadratic[1] + 2. * s * quadratic[2];
    return volumetric;
  }

  LineEnclosure
  ElasticFreeFlight::enclose(const double a, const double b) const
  {
    Assert(a <= b, dealii::ExcMessage("enclose(a, b) needs a <= b."));
    // The centre m and a half-width r with [a, b] in [m - r, m + r] despite
    // the rounding of m.
    const LineTaylorForm about = LineTaylorForm::about_centre_of(a, b);
    const double         m = about.centre, r = about.radius;
    // f and f' at the centre, computed with the form.
    LineValue     fm;
    LineEnclosure enclosure;
    if (const auto taylor = taylor_form(about, fm))
      enclosure = taylor->enclosure();
    else
      enclosure = natural_form(a, b, m, r);
    if (m >= a && m <= b)
      {
        enclosure.sample_point = m;
        enclosure.sample       = fm;
      }
    return enclosure;
  }

  namespace
  {
    /** Enclosures of J_e, J_e' and J_e'' over a parameter interval about a
     * centre m for a chunk of cells (lower and upper bounds), and J_e(m),
     * J_e'(m) (the bits of evaluate_cubics() at m); small enough to stay in
     * the L1 cache.
     */
    struct JacobianRanges
    {
      static constexpr unsigned int size = 256; // a multiple of n_lanes
      double J_lo[size], J_hi[size], dJ_lo[size], dJ_hi[size], d2J_lo[size],
        d2J_hi[size], J[size], dJ[size];
    };

    /**
     * Enclosures of J, J' and J'' over [m - r, m + r] of the cubics c0[i] +
     * c1[i] s + c2[i] s^2 + c3[i] s^3, and J, J' at m, i < count rounded up
     * to a multiple of 4 (the arrays are padded), four cells at a time.
     */
    ESTEP_LANE_KERNEL void
    enclose_cubics(const double       m,
                   const double       r,
                   const double      *c0,
                   const double      *c1,
                   const double      *c2,
                   const double      *c3,
                   const unsigned int count,
                   JacobianRanges    &ranges)
    {
      // J(m + t) = Jm + D1 t + D2 t^2 + c3 t^3 exactly, |t| <= r, so
      //   J   in Jm + D2 [0, r^2] + [-1, 1] (|D1| r + |c3| r^3),
      //   J'  in D1 + 3 c3 [0, r^2] + [-1, 1] 2 |D2| r,
      //   J'' in 2 D2 + [-1, 1] 6 |c3| r,
      // widened by a bound on the rounding of these formulas and of the
      // Horner evaluation of J in value() (both a few units of round-off of
      // the magnitudes of the terms at S = |m| + r).
      const double S = std::abs(m) + r, r2 = r * r;
      for (unsigned int i = 0; i < count; i += n_lanes)
        {
          const Lanes k0 = load_lanes(c0 + i), k1 = load_lanes(c1 + i),
                      k2 = load_lanes(c2 + i), k3 = load_lanes(c3 + i);
          const Lanes Jm = k0 + m * (k1 + m * (k2 + m * k3));
          const Lanes D1 = k1 + m * (2. * k2 + 3. * m * k3);
          const Lanes D2 = k2 + 3. * m * k3;
          store_lanes(ranges.J + i, Jm);
          store_lanes(ranges.dJ + i, D1);
          const Lanes a1 = abs(k1), a2 = abs(k2), a3 = abs(k3);
          const Lanes scale0 = abs(k0) + S * (a1 + S * (a2 + S * a3));
          const Lanes scale1 = a1 + S * (2. * a2 + 3. * S * a3);
          const Lanes scale2 = 2. * a2 + 6. * S * a3;

          const Lanes curve = D2 * r2;
          const Lanes spread0 =
            abs(D1) * r + a3 * (r2 * r) + jacobian_rounding * scale0;
          store_lanes(ranges.J_lo + i, Jm + min(curve, lanes(0.)) - spread0);
          store_lanes(ranges.J_hi + i, Jm + max(curve, lanes(0.)) + spread0);

          const Lanes bend    = 3. * r2 * k3;
          const Lanes spread1 = 2. * r * abs(D2) + jacobian_rounding * scale1;
          store_lanes(ranges.dJ_lo + i, D1 + min(bend, lanes(0.)) - spread1);
          store_lanes(ranges.dJ_hi + i, D1 + max(bend, lanes(0.)) + spread1);

          const Lanes spread2 = 6. * r * a3 + jacobian_rounding * scale2;
          store_lanes(ranges.d2J_lo + i, 2. * D2 - spread2);
          store_lanes(ranges.d2J_hi + i, 2. * D2 + spread2);
        }
    }
  } // namespace

  std::optional<LineTaylorForm>
  ElasticFreeFlight::taylor_form(const LineTaylorForm &about,
                                 LineValue            &fm) const
  {
    // f(m + t) = f(m) + f'(m) t + f''(xi) t^2 / 2 and
    // f'(m + t) = f'(m) + f''(xi) t, |t| <= r, with f'' enclosed per cell from
    // f_e'' = w (phi''(J) J'^2 + phi'(J) J''). Unlike a sum of per-cell
    // ranges, this form keeps its relative accuracy when the terms of V
    // cancel (a rigid rotation leaves V = O(s^4) from terms of size O(s^2)).
    const double m = about.centre, r = about.radius;
    // One pass over the cells, block by block and in each chunk by chunk:
    // the volumetric part of f and f' at m, and the enclosure of its
    // curvature (the interval sum rounds outward), unbounded if it is in
    // some chunk.
    struct CentreTerms
    {
      LineValue centre;
      Interval  curvature;
      double    slope_magnitude;
      bool      bounded;
      CentreTerms &
      operator+=(const CentreTerms &other)
      {
        centre.value += other.centre.value;
        centre.derivative += other.centre.derivative;
        curvature += other.curvature;
        slope_magnitude += other.slope_magnitude;
        bounded = bounded && other.bounded;
        return *this;
      }
    };
    CentreTerms terms = sum_over_distributed_blocks<CentreTerms>(
      n_blocks(n_cells), [&](const unsigned int b) {
        const BlockRange cells = block_range(b, n_cells);
        JacobianRanges   ranges;
        CentreTerms      block_terms{{0., 0.}, {0., 0.}, 0., true};
        for (unsigned int begin = cells.begin; begin < cells.end;
             begin += JacobianRanges::size)
          {
            const unsigned int count =
              std::min(JacobianRanges::size, cells.end - begin);
            const unsigned int h      = at(begin);
            const double      *volume = body.cell_data().volume.data() + h;
            enclose_cubics(m, r, c0 + h, c1 + h, c2 + h, c3 + h, count, ranges);
            const LineValue centre =
              body.material().sum_volumetric_energy_and_slope(ranges.J,
                                                              ranges.dJ,
                                                              volume,
                                                              count);
            block_terms.centre.value += centre.value;
            block_terms.centre.derivative += centre.derivative;
            if (!block_terms.bounded)
              continue;
            double         chunk_slope = 0.;
            const Interval chunk =
              body.material().enclose_volumetric_curvature_sum(ranges.J_lo,
                                                               ranges.J_hi,
                                                               ranges.dJ_lo,
                                                               ranges.dJ_hi,
                                                               ranges.d2J_lo,
                                                               ranges.d2J_hi,
                                                               volume,
                                                               count,
                                                               chunk_slope);
            if (!std::isfinite(chunk.lower) || !std::isfinite(chunk.upper))
              block_terms.bounded = false;
            block_terms.curvature += chunk;
            block_terms.slope_magnitude += chunk_slope;
          }
        return block_terms;
      });
    fm = with_quadratic_part(m, terms.centre);
    if (!std::isfinite(fm.value) || !std::isfinite(fm.derivative) ||
        !terms.bounded)
      return std::nullopt;
    Interval &curvature       = terms.curvature;
    double   &slope_magnitude = terms.slope_magnitude;
    curvature += Interval::point(2. * quadratic[2]);
    slope_magnitude +=
      std::abs(quadratic[1]) + 2. * std::abs(quadratic[2]) * (std::abs(m) + r);
    // f is smooth where the form applies (W = 0). The round-off bounds: 32
    // units of round-off of the magnitudes of the terms of f and of f' (the
    // enclosure widens the values by twice the first, plus the slope's error
    // over the half-width, and the slopes by twice the second).
    LineTaylorForm form = about;
    form.value          = fm.value;
    form.slope          = fm.derivative;
    form.curvature      = curvature;
    form.value_error    = 32. * unit * (gross_magnitude + std::abs(fm.value));
    form.slope_error    = 32. * unit * slope_magnitude;
    return form;
  }

  LineEnclosure
  ElasticFreeFlight::natural_form(const double a,
                                  const double b,
                                  const double m,
                                  const double half_width) const
  {
    // The per-cell ranges of the volumetric part, block by block and in each
    // chunk by chunk (the interval sum rounds outward).
    struct Ranges
    {
      Interval value, derivative;
      Ranges &
      operator+=(const Ranges &other)
      {
        value += other.value;
        derivative += other.derivative;
        return *this;
      }
    };
    const Ranges volumetric = sum_over_distributed_blocks<Ranges>(
      n_blocks(n_cells), [&](const unsigned int b) {
        const BlockRange cells = block_range(b, n_cells);
        JacobianRanges   ranges;
        Ranges           block_sum{{0., 0.}, {0., 0.}};
        for (unsigned int begin = cells.begin; begin < cells.end;
             begin += JacobianRanges::size)
          {
            const unsigned int count =
              std::min(JacobianRanges::size, cells.end - begin);
            const unsigned int h = at(begin);
            enclose_cubics(
              m, half_width, c0 + h, c1 + h, c2 + h, c3 + h, count, ranges);
            const LineEnclosure chunk = body.material().enclose_volumetric_sum(
              ranges.J_lo,
              ranges.J_hi,
              ranges.dJ_lo,
              ranges.dJ_hi,
              body.cell_data().volume.data() + h,
              count);
            block_sum.value += chunk.value;
            block_sum.derivative += chunk.derivative;
          }
        return block_sum;
      });
    LineEnclosure  r{volumetric.value, volumetric.derivative};
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
    return r;
  }

  double
  ElasticFreeFlight::admissible_limit() const
  {
    if (limit_ready)
      return limit;
    // Per block, the first inversion of its cells (each bounded by the
    // block's earliest so far), then the earliest of the blocks.
    const std::vector<double> first = distributed_block_terms<double>(
      n_blocks(n_cells), [&](const unsigned int b) {
        const BlockRange   cells = block_range(b, n_cells);
        double             best  = infinity;
        const unsigned int begin = at(cells.begin);
        for (unsigned int h = begin; h < begin + (cells.end - cells.begin); ++h)
          {
            if (!(c0[h] >
                  cubic_rounding * cubic_scale(c0[h], c1[h], c2[h], c3[h], 0.)))
              {
                best = 0.;
                break;
              }
            best =
              std::min(best, first_inversion(c0[h], c1[h], c2[h], c3[h], best));
          }
        return best;
      });
    const double best = *std::min_element(first.begin(), first.end());
    limit             = best;
    limit_ready       = true;
    return limit;
  }

  unsigned int
  ElasticFreeFlight::at(const unsigned int e) const
  {
    return body.cell_data().at(e);
  }

  std::array<double, 4>
  ElasticFreeFlight::jacobian_cubic(const unsigned int e) const
  {
    AssertIndexRange(e, n_cells);
    const unsigned int h = at(e);
    return {{c0[h], c1[h], c2[h], c3[h]}};
  }

  std::array<double, 3>
  ElasticFreeFlight::quadratic_part() const
  {
    return {{quadratic[0], quadratic[1], quadratic[2]}};
  }
} // namespace estep
