#ifndef estep_tests_test_flights_h
#define estep_tests_test_flights_h

// Free flights built to test the first-crossing search: a polynomial (enclosed
// by interval Horner evaluation) and a thin Gaussian bump (enclosed exactly
// through its monotone pieces).

#include <estep/systems/free_flight.h>

#include <cmath>
#include <vector>

namespace estep::testing
{
  /** f(s) = sum_k c[k] s^k. */
  class PolynomialFlight : public FreeFlight
  {
  public:
    explicit PolynomialFlight(std::vector<double> coefficients)
      : c(std::move(coefficients))
    {
      for (unsigned int k = 1; k < c.size(); ++k)
        dc.push_back(k * c[k]);
      if (dc.empty())
        dc.push_back(0.);
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

    LineEnclosure
    enclose(const double a, const double b) const override
    {
      return {interval_horner(c, a, b), interval_horner(dc, a, b)};
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

    std::vector<double> c, dc;
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
      // f increases up to s0 and decreases after; f' has its extremes at s0 -+
      // w / sqrt(2).
      Interval value = Interval::hull(value_at(a), value_at(b));
      if (a < s0 && s0 < b)
        value.upper = value_at(s0);
      Interval     slope  = Interval::hull(slope_at(a), slope_at(b));
      const double peak   = s0 - w / std::sqrt(2.),
                   trough = s0 + w / std::sqrt(2.);
      if (a < peak && peak < b)
        slope.upper = std::max(slope.upper, slope_at(peak));
      if (a < trough && trough < b)
        slope.lower = std::min(slope.lower, slope_at(trough));
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
} // namespace estep::testing

#endif
