#ifndef estep_tests_test_flights_h
#define estep_tests_test_flights_h

// Free flights built to test the first-crossing search: a polynomial (enclosed
// by interval Horner evaluation) and a thin Gaussian bump (enclosed exactly
// through its monotone pieces).

#include <estep/systems/free_flight.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace estep::testing
{
  /**
   * f(s) = sum_k c[k] s^k. With @p with_curvature its enclosures also hold
   * f'' and the sample of f, f' at the centre, as the elastic body's do. It
   * claims the round-off @p value_tolerance, and its enclosures are widened by
   * as much (the second-order form by 1e-13 (1 + |f(m)| + |f'(m)|) more, of
   * which it claims 1e-13: a flight's enclosures near a level must fit in the
   * search's band of four value tolerances, as the elastic body's do).
   */
  class PolynomialFlight : public FreeFlight
  {
  public:
    explicit PolynomialFlight(std::vector<double> coefficients,
                              const bool          with_curvature  = false,
                              const double        value_tolerance = 0.)
      : c(std::move(coefficients))
      , with_curvature(with_curvature)
      , tolerance(value_tolerance)
    {
      for (unsigned int k = 1; k < c.size(); ++k)
        dc.push_back(k * c[k]);
      if (dc.empty())
        dc.push_back(0.);
      for (unsigned int k = 1; k < dc.size(); ++k)
        ddc.push_back(k * dc[k]);
      if (ddc.empty())
        ddc.push_back(0.);
    }

    double
    value(const double s) const override
    {
      return horner(c, s);
    }

    LineValue
    value_and_derivative(const double s) const override
    {
      return {horner(c, s), horner(dc, s)};
    }

    double
    value_tolerance() const override
    {
      return tolerance + (with_curvature ? 1e-13 : 0.);
    }

    LineEnclosure
    enclose(const double a, const double b) const override
    {
      LineEnclosure e{interval_horner(c, a, b).widened(0., tolerance),
                      interval_horner(dc, a, b)};
      if (with_curvature)
        {
          // The second-order form about the centre m (as the elastic body
          // forms it): f between the quadratics with the extreme curvatures,
          // widened for round-off.
          const double m = 0.5 * (a + b), r = 0.5 * (b - a);
          e.curvature    = interval_horner(ddc, a, b);
          e.sample_point = m;
          e.sample       = value_and_derivative(m);
          const double margin =
            tolerance + 1e-13 * (1. + std::abs(e.sample.value) +
                                 std::abs(e.sample.derivative));
          e.value = Interval{quadratic_range(e.sample.value,
                                             e.sample.derivative,
                                             0.5 * e.curvature.lower,
                                             -r,
                                             r)
                               .lower,
                             quadratic_range(e.sample.value,
                                             e.sample.derivative,
                                             0.5 * e.curvature.upper,
                                             -r,
                                             r)
                               .upper}
                      .widened(0., margin);
          e.derivative = (Interval::point(e.sample.derivative) +
                          e.curvature * Interval{-r, r})
                           .widened(0., margin);
        }
      return e;
    }

  private:
    static double
    horner(const std::vector<double> &p, const double s)
    {
      double r = 0.;
      for (auto k = p.rbegin(); k != p.rend(); ++k)
        r = r * s + *k;
      return r;
    }

    static Interval
    interval_horner(const std::vector<double> &p,
                    const double               a,
                    const double               b)
    {
      const Interval x{a, b};
      Interval       r = Interval::point(0.);
      for (auto k = p.rbegin(); k != p.rend(); ++k)
        r = r * x + Interval::point(*k);
      return r;
    }

    std::vector<double> c, dc, ddc;
    bool                with_curvature;
    double              tolerance;
  };

  /** f(s) = base + A exp(-((s - s0) / w)^2). */
  class BumpFlight : public FreeFlight
  {
  public:
    BumpFlight(const double base,
               const double A,
               const double s0,
               const double w)
      : base(base)
      , A(A)
      , s0(s0)
      , w(w)
    {}

    double
    value(const double s) const override
    {
      const double x = (s - s0) / w;
      return base + A * std::exp(-x * x);
    }

    LineValue
    value_and_derivative(const double s) const override
    {
      const double x = (s - s0) / w;
      return {base + A * std::exp(-x * x), -2. * x / w * A * std::exp(-x * x)};
    }

    LineEnclosure
    enclose(const double a, const double b) const override
    {
      // f is monotone on either side of s0 (up then down for A > 0, the mirror
      // image for A < 0); f' has its extremes at s0 -+ w / sqrt(2).
      Interval value = Interval::hull(value_at(a), value_at(b));
      if (a < s0 && s0 < b)
        value = {std::min(value.lower, value_at(s0)),
                 std::max(value.upper, value_at(s0))};
      Interval slope = Interval::hull(slope_at(a), slope_at(b));
      for (const double extreme :
           {s0 - w / std::sqrt(2.), s0 + w / std::sqrt(2.)})
        if (a < extreme && extreme < b)
          slope = {std::min(slope.lower, slope_at(extreme)),
                   std::max(slope.upper, slope_at(extreme))};
      return {value.widened(1e-15, 1e-300), slope.widened(1e-15, 1e-300)};
    }

  private:
    double
    value_at(const double s) const
    {
      return value(s);
    }

    double
    slope_at(const double s) const
    {
      return value_and_derivative(s).derivative;
    }

    const double base, A, s0, w;
  };
  /** f = c, on its departure level, with enclosures that prove nothing
   * (they are wider than any band and give f' no sign) and claim no
   * round-off: every interval near s = 0 is bisected to the resolution, and a
   * search crawls. @p on_enclosure, if given, is told the number of each
   * enclosure made. */
  class UselessEnclosureFlight : public FreeFlight
  {
  public:
    explicit UselessEnclosureFlight(
      const double                             c,
      std::function<void(const std::uint64_t)> on_enclosure = {},
      const Interval curvature = LineEnclosure().curvature)
      : c(c)
      , on_enclosure(std::move(on_enclosure))
      , curvature(curvature)
    {}

    double
    value(const double) const override
    {
      return c;
    }

    LineValue
    value_and_derivative(const double) const override
    {
      return {c, 0.};
    }

    LineEnclosure
    enclose(const double, const double) const override
    {
      if (on_enclosure)
        on_enclosure(++n_enclosures);
      return {{c - 1e-3, c + 1e-3}, {-1., 1.}, curvature};
    }

    double
    value_tolerance() const override
    {
      return 0.;
    }

  private:
    const double                                   c;
    const std::function<void(const std::uint64_t)> on_enclosure;
    const Interval                                 curvature;
    mutable std::uint64_t                          n_enclosures = 0;
  };
} // namespace estep::testing

#endif
