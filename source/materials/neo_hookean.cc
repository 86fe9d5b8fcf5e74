#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <estep/base/lanes.h>
#include <estep/materials/batch_log.h>
#include <estep/materials/material_registry.h>
#include <estep/materials/neo_hookean.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

namespace estep
{
  namespace
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    constexpr double unit     = std::numeric_limits<double>::epsilon();

    /** Chunk length of the batch kernels (buffers on the stack). */
    constexpr std::size_t chunk = 256;

    /**
     * Range of f = L (a L - mu) (a = lambda/2) over [L_lo, L_hi] (L_lo may be
     * -infinity), before widening; @p magnitude receives a L_m^2 + mu L_m with
     * L_m the larger finite end magnitude, the scale of the round-off of f
     * there.
     */
    inline void
    range_in_log(const double a,
                 const double mu,
                 const double L_star,
                 const double f_min,
                 const double L_lo,
                 const double L_hi,
                 double      &lower,
                 double      &upper,
                 double      &magnitude)
    {
      const double f_lo =
        (L_lo == -infinity) ? infinity : L_lo * (a * L_lo - mu);
      const double f_hi = L_hi * (a * L_hi - mu);
      lower             = std::min(f_lo, f_hi);
      upper             = std::max(f_lo, f_hi);
      if (L_lo < L_star && L_star < L_hi)
        lower = f_min;
      const double L_m = (L_lo == -infinity) ?
                           std::abs(L_hi) :
                           std::max(std::abs(L_lo), std::abs(L_hi));
      magnitude        = L_m * (a * L_m + mu);
    }

    /** Interval quotient N / [J_lo, J_hi] with 0 < J_lo <= J_hi (before
     * widening). */
    inline void
    divide_positive(const double N_lo,
                    const double N_hi,
                    const double J_lo,
                    const double J_hi,
                    double      &lower,
                    double      &upper)
    {
      lower = N_lo >= 0. ? N_lo / J_hi : N_lo / J_lo;
      upper = N_hi >= 0. ? N_hi / J_lo : N_hi / J_hi;
    }

    /** Interval product [a_lo, a_hi] * [b_lo, b_hi] (before widening). */
    inline void
    multiply(const double a_lo,
             const double a_hi,
             const double b_lo,
             const double b_hi,
             double      &lower,
             double      &upper)
    {
      const double p1 = a_lo * b_lo, p2 = a_lo * b_hi, p3 = a_hi * b_lo,
                   p4 = a_hi * b_hi;
      lower           = std::min(std::min(p1, p2), std::min(p3, p4));
      upper           = std::max(std::max(p1, p2), std::max(p3, p4));
    }

    // The batch kernels, four cells at a time. Arrays of length n are read in
    // batches (load_batch); the lanes past the end of the last batch get
    // neutral values (J = 1, L = 0, rates 0, weight 0) that add nothing.

    /** Sum of w[i] L[i] (a L[i] - mu) for i < n. */
    ESTEP_LANE_KERNEL double
    energy_sum(const double      a,
               const double      mu,
               const double     *L,
               const double     *w,
               const std::size_t n)
    {
      Lanes sum_lanes = lanes(0.);
      for (std::size_t i = 0; i < n; i += n_lanes)
        {
          const Lanes Li = load_batch(L, i, n, 0.);
          sum_lanes += load_batch(w, i, n, 0.) * Li * (a * Li - mu);
        }
      return sum(sum_lanes);
    }

    /** The sums of w[i] L[i] (a L[i] - mu) and of w[i] (2 a L[i] - mu) dJ[i]
     * / J[i] for i < n. */
    ESTEP_LANE_KERNEL LineValue
    energy_and_slope_sum(const double      a,
                         const double      mu,
                         const double     *J,
                         const double     *dJ,
                         const double     *L,
                         const double     *w,
                         const std::size_t n)
    {
      Lanes value = lanes(0.), slope = lanes(0.);
      for (std::size_t i = 0; i < n; i += n_lanes)
        {
          const Lanes Li = load_batch(L, i, n, 0.),
                      wi = load_batch(w, i, n, 0.);
          value += wi * Li * (a * Li - mu);
          slope += wi * (2. * a * Li - mu) * load_batch(dJ, i, n, 0.) /
                   load_batch(J, i, n, 1.);
        }
      return {sum(value), sum(slope)};
    }

    /** df[i] = (lambda L[i] - mu) / J[i] for i < n (L and df may be the same
     * array). */
    ESTEP_LANE_KERNEL void
    derivatives(const double      lambda,
                const double      mu,
                const double     *J,
                const double     *L,
                double           *df,
                const std::size_t n)
    {
      std::size_t i = 0;
      for (; i + n_lanes <= n; i += n_lanes)
        store_lanes(df + i,
                    (lambda * load_lanes(L + i) - mu) / load_lanes(J + i));
      for (; i < n; ++i)
        df[i] = (lambda * L[i] - mu) / J[i];
    }

    /**
     * Bounds of log J over [J_lo[i], J_hi[i]] without logarithms, for i < n:
     * L_lo[i] <= 1 - 1/J_lo[i] <= log J_lo[i] and L_hi[i] >= J_hi[i] - 1 >=
     * log J_hi[i] (each widened by its rounding), which overestimate the
     * range by at most about (J - 1)^2. Returns false, leaving the bounds
     * unfinished, if some J lies farther than 1/16 from 1.
     */
    ESTEP_LANE_KERNEL bool
    log_bounds_near_one(const double     *J_lo,
                        const double     *J_hi,
                        double           *L_lo,
                        double           *L_hi,
                        const std::size_t n)
    {
      Lanes distance = lanes(0.);
      for (std::size_t i = 0; i < n; i += n_lanes)
        {
          const Lanes Jl = load_batch(J_lo, i, n, 1.),
                      Jh = load_batch(J_hi, i, n, 1.);
          distance       = max(distance, max(abs(Jl - 1.), abs(Jh - 1.)));
          const Lanes r  = 1. / Jl;
          // Rounding: 1 / J_lo and the subtraction, J_hi - 1 (exact for J_hi
          // in [1/2, 2]); 4 units of the operands' magnitudes each.
          const Lanes lower = (1. - r) - 4. * unit * (1. + r),
                      upper = (Jh - 1.) + 4. * unit * (1. + Jh);
          if (i + n_lanes <= n)
            {
              store_lanes(L_lo + i, lower);
              store_lanes(L_hi + i, upper);
            }
          else
            for (std::size_t k = 0; i + k < n; ++k)
              {
                L_lo[i + k] = lower[k];
                L_hi[i + k] = upper[k];
              }
        }
      return distance[0] <= 1. / 16. && distance[1] <= 1. / 16. &&
             distance[2] <= 1. / 16. && distance[3] <= 1. / 16.;
    }

    /**
     * The sums over i < n of the curvature enclosure of
     * NeoHookean::enclose_volumetric_curvature_sum() (all J_lo > 0, L_lo and
     * L_hi their logarithms): lower, upper and magnitude in @p result, the
     * slope magnitude in result[3].
     */
    ESTEP_LANE_KERNEL void
    curvature_sums(const double      lambda,
                   const double      mu,
                   const double     *J_lo,
                   const double     *J_hi,
                   const double     *L_lo,
                   const double     *L_hi,
                   const double     *dJ_lo,
                   const double     *dJ_hi,
                   const double     *d2J_lo,
                   const double     *d2J_hi,
                   const double     *w,
                   const std::size_t n,
                   double           *result)
    {
      const double log_factor = 2. * batch_log_ulp() * unit;
      const Lanes  zero       = lanes(0.);
      Lanes        lower = zero, upper = zero, magnitude = zero, slope = zero;
      for (std::size_t i = 0; i < n; i += n_lanes)
        {
          const Lanes Jl = load_batch(J_lo, i, n, 1.),
                      Jh = load_batch(J_hi, i, n, 1.),
                      Ll = load_batch(L_lo, i, n, 0.),
                      Lh = load_batch(L_hi, i, n, 0.);
          const Lanes e  = log_factor * (lambda * max(abs(Ll), abs(Lh)) + mu);
          // f' = (lambda L - mu) / J and f'' = (lambda + mu - lambda L) / J^2
          // over the box, each end divided by the J end that makes it
          // extreme (0 < J_lo <= J_hi).
          const Lanes N1_lo = lambda * Ll - mu - e,
                      N1_hi = lambda * Lh - mu + e;
          const Lanes f1_lo = N1_lo / (N1_lo >= 0. ? Jh : Jl),
                      f1_hi = N1_hi / (N1_hi >= 0. ? Jl : Jh);
          const Lanes N2_lo = lambda + mu - lambda * Lh - e,
                      N2_hi = lambda + mu - lambda * Ll + e;
          const Lanes f2_lo = N2_lo / (N2_lo >= 0. ? Jh * Jh : Jl * Jl),
                      f2_hi = N2_hi / (N2_hi >= 0. ? Jl * Jl : Jh * Jh);
          // J'^2 over [a, b].
          const Lanes a    = load_batch(dJ_lo, i, n, 0.),
                      b    = load_batch(dJ_hi, i, n, 0.);
          const Lanes s_hi = max(a * a, b * b);
          const Lanes s_lo = (a <= 0. && b >= 0.) ? zero : min(a * a, b * b);
          // The products f'' J'^2 and f' J''.
          const Lanes c  = load_batch(d2J_lo, i, n, 0.),
                      d  = load_batch(d2J_hi, i, n, 0.);
          const Lanes p1 = f2_lo * s_lo, p2 = f2_lo * s_hi, p3 = f2_hi * s_lo,
                      p4 = f2_hi * s_hi;
          const Lanes q1 = f1_lo * c, q2 = f1_lo * d, q3 = f1_hi * c,
                      q4   = f1_hi * d;
          const Lanes p_lo = min(min(p1, p2), min(p3, p4)),
                      p_hi = max(max(p1, p2), max(p3, p4));
          const Lanes q_lo = min(min(q1, q2), min(q3, q4)),
                      q_hi = max(max(q1, q2), max(q3, q4));
          const Lanes wi   = load_batch(w, i, n, 0.);
          lower += wi * (p_lo + q_lo);
          upper += wi * (p_hi + q_hi);
          magnitude +=
            wi * (max(abs(p_lo), abs(p_hi)) + max(abs(q_lo), abs(q_hi)));
          slope += wi * max(abs(f1_lo), abs(f1_hi)) * max(abs(a), abs(b));
        }
      result[0] = sum(lower);
      result[1] = sum(upper);
      result[2] = sum(magnitude);
      result[3] = sum(slope);
    }
  } // namespace

  NeoHookean::NeoHookean(const double lambda0, const double mu0)
    : lambda0(lambda0)
    , mu0(mu0)
  {
    AssertThrow(lambda0 >= 0. && mu0 > 0. && std::isfinite(lambda0) &&
                  std::isfinite(mu0),
                dealii::ExcMessage(
                  "NeoHookean: the Lame constants must satisfy lambda0 >= 0 "
                  "and mu0 > 0 (got lambda0 = " +
                  std::to_string(lambda0) + ", mu0 = " + std::to_string(mu0) +
                  ")."));
  }

  std::string
  NeoHookean::name() const
  {
    return "neo-Hookean";
  }

  double
  NeoHookean::quadratic_modulus() const
  {
    return mu0;
  }

  double
  NeoHookean::volumetric_energy(const double J) const
  {
    if (!(J > 0.))
      return infinity;
    const double L = std::log(J);
    return L * (0.5 * lambda0 * L - mu0);
  }

  double
  NeoHookean::volumetric_derivative(const double J) const
  {
    return (lambda0 * std::log(J) - mu0) / J;
  }

  double
  NeoHookean::volumetric_second_derivative(const double J) const
  {
    return (lambda0 + mu0 - lambda0 * std::log(J)) / (J * J);
  }

  Interval
  NeoHookean::volumetric_second_derivative_range(const Interval &J) const
  {
    if (!(J.lower > 0.))
      return {-infinity, infinity};
    const auto f2 = [this](const double x) {
      return (lambda0 + mu0 - lambda0 * std::log(x)) / (x * x);
    };
    Interval     range = Interval::hull(f2(J.lower), f2(J.upper));
    const double J_min = std::exp(1.5 + mu0 / lambda0);
    if (J.lower < J_min && J_min < J.upper)
      range.lower = f2(J_min);
    // Rounding of the log, the sum and the division.
    const double e =
      16. * unit * (lambda0 + mu0) *
      (1. + std::abs(std::log(J.lower)) + std::abs(std::log(J.upper))) /
      (J.lower * J.lower);
    return {range.lower - e, range.upper + e};
  }

  Interval
  NeoHookean::volumetric_energy_range(const Interval &J) const
  {
    if (!(J.upper > 0.))
      return {infinity, infinity};
    const double L_lo   = J.lower > 0. ? std::log(J.lower) : -infinity;
    const double L_hi   = std::log(J.upper);
    const double L_star = lambda0 > 0. ? mu0 / lambda0 : infinity;
    const double f_min  = lambda0 > 0. ? -0.5 * mu0 * mu0 / lambda0 : -infinity;
    double       lower, upper, magnitude;
    range_in_log(
      0.5 * lambda0, mu0, L_star, f_min, L_lo, L_hi, lower, upper, magnitude);
    // log error (batch_log_ulp() ulps) and the evaluation of the quadratic in
    // L.
    const double margin = (2. * batch_log_ulp() + 8.) * unit * magnitude;
    return {lower - margin, upper + margin};
  }

  Interval
  NeoHookean::volumetric_derivative_range(const Interval &J) const
  {
    if (!(J.lower > 0.))
      return {-infinity, infinity};
    const double L_lo = std::log(J.lower), L_hi = std::log(J.upper);
    const double e = (batch_log_ulp() + 4.) * unit *
                     (lambda0 * std::max(std::abs(L_lo), std::abs(L_hi)) + mu0);
    double lower, upper;
    divide_positive(lambda0 * L_lo - mu0 - e,
                    lambda0 * L_hi - mu0 + e,
                    J.lower,
                    J.upper,
                    lower,
                    upper);
    return Interval{lower, upper}.widened(4. * unit);
  }

  double
  NeoHookean::sum_volumetric_energy(const double     *J,
                                    const double     *w,
                                    const std::size_t n) const
  {
    const double a   = 0.5 * lambda0;
    double       sum = 0.;
    double       L[chunk];
    for (std::size_t begin = 0; begin < n; begin += chunk)
      {
        const std::size_t m  = std::min(chunk, n - begin);
        const double     *Jc = J + begin, *wc = w + begin;
        bool              inadmissible = false;
        for (std::size_t i = 0; i < m; ++i)
          inadmissible |= !(Jc[i] > 0.);
        if (inadmissible)
          return infinity;
        batch_log(Jc, L, m);
        sum += energy_sum(a, mu0, L, wc, m);
      }
    return sum;
  }

  LineValue
  NeoHookean::sum_volumetric_energy_and_slope(const double     *J,
                                              const double     *dJ,
                                              const double     *w,
                                              const std::size_t n) const
  {
    const double a = 0.5 * lambda0;
    LineValue    r{0., 0.};
    double       L[chunk];
    for (std::size_t begin = 0; begin < n; begin += chunk)
      {
        const std::size_t m  = std::min(chunk, n - begin);
        const double     *Jc = J + begin, *dJc = dJ + begin, *wc = w + begin;
        bool              inadmissible = false;
        for (std::size_t i = 0; i < m; ++i)
          inadmissible |= !(Jc[i] > 0.);
        if (inadmissible)
          return {infinity, 0.};
        batch_log(Jc, L, m);
        const LineValue chunk_sums =
          energy_and_slope_sum(a, mu0, Jc, dJc, L, wc, m);
        r.value += chunk_sums.value;
        r.derivative += chunk_sums.derivative;
      }
    return r;
  }

  void
  NeoHookean::volumetric_derivatives(const double     *J,
                                     double           *df,
                                     const std::size_t n) const
  {
    batch_log(J, df, n);
    derivatives(lambda0, mu0, J, df, df, n);
  }

  LineEnclosure
  NeoHookean::enclose_volumetric_sum(const double     *J_lo,
                                     const double     *J_hi,
                                     const double     *dJ_lo,
                                     const double     *dJ_hi,
                                     const double     *w,
                                     const std::size_t n) const
  {
    const double a      = 0.5 * lambda0;
    const double L_star = lambda0 > 0. ? mu0 / lambda0 : infinity;
    const double f_min  = lambda0 > 0. ? -0.5 * mu0 * mu0 / lambda0 : -infinity;
    // The log error enters f as at most |f'(L)| dL <= 2 ulp_log u (a L^2 + mu
    // |L|).
    const double log_factor = 2. * batch_log_ulp() * unit;

    double value_lower = 0., value_upper = 0., value_magnitude = 0.;
    double slope_lower = 0., slope_upper = 0., slope_magnitude = 0.;
    bool   slope_unbounded = false;

    double L_lo[chunk], L_hi[chunk];
    for (std::size_t begin = 0; begin < n; begin += chunk)
      {
        const std::size_t m = std::min(chunk, n - begin);
        for (std::size_t i = 0; i < m; ++i)
          L_lo[i] = std::max(J_lo[begin + i], 0.);
        batch_log(L_lo, L_lo, m);
        batch_log(J_hi + begin, L_hi, m);
        for (std::size_t i = 0; i < m; ++i)
          {
            const std::size_t k = begin + i;
            if (!(J_hi[k] > 0.))
              return {{infinity, infinity}, {-infinity, infinity}};
            double lower, upper, magnitude;
            range_in_log(
              a, mu0, L_star, f_min, L_lo[i], L_hi[i], lower, upper, magnitude);
            value_lower += w[k] * lower;
            value_upper += w[k] * upper;
            value_magnitude += w[k] * magnitude;

            if (!(J_lo[k] > 0.))
              {
                slope_unbounded = true;
                continue;
              }
            const double e =
              log_factor *
              (lambda0 * std::max(std::abs(L_lo[i]), std::abs(L_hi[i])) + mu0);
            double q_lo, q_hi, d_lo, d_hi;
            divide_positive(lambda0 * L_lo[i] - mu0 - e,
                            lambda0 * L_hi[i] - mu0 + e,
                            J_lo[k],
                            J_hi[k],
                            q_lo,
                            q_hi);
            multiply(q_lo, q_hi, dJ_lo[k], dJ_hi[k], d_lo, d_hi);
            slope_lower += w[k] * d_lo;
            slope_upper += w[k] * d_hi;
            slope_magnitude += w[k] * std::max(std::abs(d_lo), std::abs(d_hi));
          }
      }

    // Per-term round-off (log error, quadratic in L, products) and summation in
    // any order: (n + const) u sum of magnitudes, with a safety factor 2.
    const double  factor = 2. * (static_cast<double>(n) + 32.) * unit;
    LineEnclosure r;
    const double  value_margin = (factor + log_factor) * value_magnitude;
    r.value = Interval{value_lower - value_margin, value_upper + value_margin};
    if (slope_unbounded)
      r.derivative = {-infinity, infinity};
    else
      r.derivative = Interval{slope_lower - factor * slope_magnitude,
                              slope_upper + factor * slope_magnitude};
    return r;
  }

  Interval
  NeoHookean::enclose_volumetric_curvature_sum(const double     *J_lo,
                                               const double     *J_hi,
                                               const double     *dJ_lo,
                                               const double     *dJ_hi,
                                               const double     *d2J_lo,
                                               const double     *d2J_hi,
                                               const double     *w,
                                               const std::size_t n,
                                               double &slope_magnitude) const
  {
    double lower = 0., upper = 0., magnitude = 0.;
    slope_magnitude = 0.;
    double L_lo[chunk], L_hi[chunk];
    for (std::size_t begin = 0; begin < n; begin += chunk)
      {
        const std::size_t m = std::min(chunk, n - begin);
        for (std::size_t i = 0; i < m; ++i)
          if (!(J_lo[begin + i] > 0.))
            return {-infinity, infinity};
        // log J enters f' and f'' next to mu and lambda + mu: near J = 1 its
        // bounds without logarithms are as good.
        if (!log_bounds_near_one(J_lo + begin, J_hi + begin, L_lo, L_hi, m))
          {
            batch_log(J_lo + begin, L_lo, m);
            batch_log(J_hi + begin, L_hi, m);
          }
        double sums[4];
        curvature_sums(lambda0,
                       mu0,
                       J_lo + begin,
                       J_hi + begin,
                       L_lo,
                       L_hi,
                       dJ_lo + begin,
                       dJ_hi + begin,
                       d2J_lo + begin,
                       d2J_hi + begin,
                       w + begin,
                       m,
                       sums);
        lower += sums[0];
        upper += sums[1];
        magnitude += sums[2];
        slope_magnitude += sums[3];
      }
    // Products, sums and the summation over the cells.
    const double margin = 8. * unit * magnitude;
    return {lower - margin, upper + margin};
  }



  namespace
  {
    void
    declare_neo_hookean_parameters(dealii::ParameterHandler &prm)
    {
      declare_lame_constants(prm, "Neo-Hookean");
    }

    std::shared_ptr<const Material>
    create_neo_hookean(dealii::ParameterHandler &prm)
    {
      const LameConstants c = parse_lame_constants(prm, "Neo-Hookean");
      return std::make_shared<NeoHookean>(c.lambda, c.mu);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_MATERIAL(
  "neo-Hookean",
  "W(F) = lambda0/2 (log J)^2 - mu0 log J + mu0/2 (tr(F^T F) - 3), the "
  "compressible neo-Hookean solid (parameters in the subsection "
  "Neo-Hookean).",
  estep::declare_neo_hookean_parameters,
  estep::create_neo_hookean)
