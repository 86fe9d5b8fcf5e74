#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>

#include <estep/materials/material_registry.h>
#include <estep/materials/quadratic_volume_neo_hookean.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace estep
{
  namespace
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    constexpr double unit     = std::numeric_limits<double>::epsilon();
    /** An absolute margin for products that underflow (far below any
     * relative margin of a nonzero value). */
    constexpr double tiny = 16. * std::numeric_limits<double>::min();

    // The point functions, shared by the scalar and the batch paths so that
    // both compute the same values (which the ranges enclose). With each
    // operation rounded to nearest and std::log within one ulp, their results
    // differ from the exact values by less than 3 u times the magnitudes
    // below (u = unit); the ranges widen by 16 u times them.

    /** f(J) = lambda/2 (J - 1)^2 - mu log J for J > 0. */
    inline double
    energy(const double lambda, const double mu, const double J)
    {
      const double d = J - 1.;
      return 0.5 * lambda * d * d - mu * std::log(J);
    }

    /** lambda/2 (J - 1)^2 + mu |log J| >= |f(J)|, the scale of the round-off
     * of energy(). It decreases on (0, 1] and increases on [1, infinity). */
    inline double
    energy_magnitude(const double lambda, const double mu, const double J)
    {
      const double d = J - 1.;
      return 0.5 * lambda * d * d + mu * std::abs(std::log(J));
    }

    /** f'(J) = lambda (J - 1) - mu / J for J > 0. */
    inline double
    derivative(const double lambda, const double mu, const double J)
    {
      return lambda * (J - 1.) - mu / J;
    }

    /** f''(J) = lambda + mu / J^2 for J > 0. */
    inline double
    second_derivative(const double lambda, const double mu, const double J)
    {
      return lambda + mu / (J * J);
    }
  } // namespace

  QuadraticVolumeNeoHookean::QuadraticVolumeNeoHookean(const double lambda0,
                                                       const double mu0)
    : lambda0(lambda0)
    , mu0(mu0)
  {
    AssertThrow(lambda0 >= 0. && mu0 > 0. && std::isfinite(lambda0) &&
                  std::isfinite(mu0),
                dealii::ExcMessage(
                  "QuadraticVolumeNeoHookean: the Lame constants must satisfy "
                  "lambda0 >= 0 and mu0 > 0 (got lambda0 = " +
                  std::to_string(lambda0) + ", mu0 = " + std::to_string(mu0) +
                  ")."));
    // f'(J) = 0 <=> lambda J^2 - lambda J - mu = 0; the root J* > 1 (for
    // lambda = 0, or 4 mu / lambda overflowing, f decreases everywhere).
    J_star = lambda0 > 0. ? 0.5 * (1. + std::sqrt(1. + 4. * (mu0 / lambda0))) :
                            infinity;
    f_min  = std::isfinite(J_star) ? energy(lambda0, mu0, J_star) : -infinity;
    // Below every computed f(x): for x < 1 energy() returns values >= 0 >=
    // f_min; for x >= 1 it returns at least (1 - 3 u) lambda/2 (x - 1)^2 -
    // (1 + 3 u) mu log x, a function of the form of f with mu larger by a
    // factor 1 + 7 u, whose minimum (near J*) lies at most 7 u mu log(2 J*)
    // below the exact minimum, which f_min exceeds by at most 3 u
    // energy_magnitude(J*) plus the error of J* (see
    // volumetric_energy_range()).
    global_lower =
      std::isfinite(f_min) ?
        f_min -
          16. * unit *
            (energy_magnitude(lambda0, mu0, J_star) +
             mu0 * std::log(2. * J_star)) -
          8. * (lambda0 + mu0) * (unit * J_star) * (unit * J_star) - tiny :
        -infinity;
  }

  std::string
  QuadraticVolumeNeoHookean::name() const
  {
    return "neo-Hookean quadratic volume";
  }

  double
  QuadraticVolumeNeoHookean::quadratic_modulus() const
  {
    return mu0;
  }

  double
  QuadraticVolumeNeoHookean::volumetric_energy(const double J) const
  {
    if (!(J > 0.))
      return infinity;
    return energy(lambda0, mu0, J);
  }

  double
  QuadraticVolumeNeoHookean::volumetric_derivative(const double J) const
  {
    return derivative(lambda0, mu0, J);
  }

  double
  QuadraticVolumeNeoHookean::volumetric_second_derivative(const double J) const
  {
    return second_derivative(lambda0, mu0, J);
  }

  Interval
  QuadraticVolumeNeoHookean::volumetric_energy_range(const Interval &J) const
  {
    if (!(J.upper > 0.))
      return {infinity, infinity};
    // f is convex with its minimum at J*: the range is spanned by the ends,
    // and f(J*) when J* lies inside. As J -> 0, f -> +infinity.
    const double f_hi = energy(lambda0, mu0, J.upper);
    double       lower, upper, magnitude;
    if (J.lower > 0.)
      {
        const double f_lo = energy(lambda0, mu0, J.lower);
        lower             = std::min(f_lo, f_hi);
        upper             = std::max(f_lo, f_hi);
        // The round-off of energy(x) is at most 3 u energy_magnitude(x),
        // which is largest at an end of the interval.
        magnitude = std::max(energy_magnitude(lambda0, mu0, J.lower),
                             energy_magnitude(lambda0, mu0, J.upper));
      }
    else
      {
        lower = f_hi;
        upper = infinity;
        // On (0, min(1, J.upper)) f = energy_magnitude >= 0 and energy()
        // returns values >= 0 that are at most 3 u f below f, f >= the true
        // lower bound; on [1, J.upper] the magnitude is largest at J.upper.
        magnitude = energy_magnitude(lambda0, mu0, J.upper);
      }
    // The interior minimum, taken whenever J* lies inside the interval up to
    // the rounding of J* (f_min is a lower bound of f everywhere). f_min is f
    // at the computed J*, a few ulps away from the exact one: it exceeds the
    // minimum by at most (lambda + mu)/2 (J* - J*_exact)^2.
    double extra = 0.;
    if (std::isfinite(J_star) && J.lower < J_star * (1. + 8. * unit) &&
        J_star * (1. - 8. * unit) < J.upper)
      {
        lower = std::min(lower, f_min);
        extra = 8. * (lambda0 + mu0) * (unit * J_star) * (unit * J_star);
      }
    const double margin = 16. * unit * magnitude + extra + tiny;
    // Overflow ((J - 1)^2 beyond the largest double, J.upper > 1e153): only
    // the bound below every value of f.
    if (!std::isfinite(margin))
      return {global_lower, infinity};
    return {lower - margin, upper + margin};
  }

  Interval
  QuadraticVolumeNeoHookean::volumetric_derivative_range(
    const Interval &J) const
  {
    if (!(J.lower > 0.))
      return {-infinity, infinity};
    // f' increases. The round-off of derivative(x) is at most 2 u (lambda |x
    // - 1| + mu / x), which is largest at the ends.
    const double magnitude =
      lambda0 * std::max(std::abs(J.lower - 1.), std::abs(J.upper - 1.)) +
      mu0 / J.lower;
    const double margin = 8. * unit * magnitude + tiny;
    // Overflow (mu / J beyond the largest double): no finite bounds.
    if (!std::isfinite(margin))
      return {-infinity, infinity};
    return {derivative(lambda0, mu0, J.lower) - margin,
            derivative(lambda0, mu0, J.upper) + margin};
  }

  Interval
  QuadraticVolumeNeoHookean::volumetric_second_derivative_range(
    const Interval &J) const
  {
    if (!(J.lower > 0.))
      return {-infinity, infinity};
    // f'' decreases. All terms of second_derivative() are positive: its
    // relative round-off is at most 2 u as long as x^2 does not underflow
    // (x^2 >= the smallest normal double, with a factor 4 to spare). Below,
    // f'' >= lambda still holds, and the upper bound is infinite.
    const double normal = 4. * std::numeric_limits<double>::min();
    const double lower =
      J.upper * J.upper >= normal ?
        second_derivative(lambda0, mu0, J.upper) * (1. - 8. * unit) :
        lambda0;
    const double upper =
      J.lower * J.lower >= normal ?
        second_derivative(lambda0, mu0, J.lower) * (1. + 8. * unit) :
        infinity;
    return {lower, upper};
  }

  double
  QuadraticVolumeNeoHookean::sum_volumetric_energy(const double     *J,
                                                   const double     *w,
                                                   const std::size_t n) const
  {
    double sum = 0.;
    for (std::size_t i = 0; i < n; ++i)
      {
        if (!(J[i] > 0.))
          return infinity;
        sum += w[i] * energy(lambda0, mu0, J[i]);
      }
    return sum;
  }

  LineValue
  QuadraticVolumeNeoHookean::sum_volumetric_energy_and_slope(
    const double     *J,
    const double     *dJ,
    const double     *w,
    const std::size_t n) const
  {
    LineValue r{0., 0.};
    for (std::size_t i = 0; i < n; ++i)
      {
        if (!(J[i] > 0.))
          return {infinity, 0.};
        r.value += w[i] * energy(lambda0, mu0, J[i]);
        r.derivative += w[i] * derivative(lambda0, mu0, J[i]) * dJ[i];
      }
    return r;
  }

  void
  QuadraticVolumeNeoHookean::volumetric_derivatives(const double     *J,
                                                    double           *df,
                                                    const std::size_t n) const
  {
    for (std::size_t i = 0; i < n; ++i)
      df[i] = derivative(lambda0, mu0, J[i]);
  }



  namespace
  {
    /** The subsection of the material's parameters. */
    const char *const quadratic_volume_section = "Neo-Hookean quadratic volume";

    void
    declare_quadratic_volume_parameters(dealii::ParameterHandler &prm)
    {
      declare_lame_constants(prm, quadratic_volume_section);
    }

    std::shared_ptr<const Material>
    create_quadratic_volume(dealii::ParameterHandler &prm)
    {
      const LameConstants c =
        parse_lame_constants(prm, quadratic_volume_section);
      return std::make_shared<QuadraticVolumeNeoHookean>(c.lambda, c.mu);
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_MATERIAL(
  "neo-Hookean quadratic volume",
  "W(F) = lambda0/2 (J - 1)^2 - mu0 log J + mu0/2 (tr(F^T F) - 3), the "
  "compressible neo-Hookean solid with a quadratic volumetric term and the "
  "same linearisation (parameters in the subsection Neo-Hookean quadratic "
  "volume).",
  estep::declare_quadratic_volume_parameters,
  estep::create_quadratic_volume)
