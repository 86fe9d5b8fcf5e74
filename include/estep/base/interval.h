#ifndef estep_base_interval_h
#define estep_base_interval_h

#include <algorithm>
#include <cmath>
#include <limits>

namespace estep
{
  /**
   * A closed interval [lower, upper] of real numbers. It is the enclosure type
   * of the certified first-crossing search: a function's range over a parameter
   * interval is reported as an Interval that contains every value the function
   * takes there.
   *
   * The arithmetic below widens every result by a few units in the last place
   * (outward rounding by a relative margin), so that enclosures computed in
   * floating point stay valid.
   */
  struct Interval
  {
    double lower = 0.;
    double upper = 0.;

    /** The interval [x, x]. */
    static Interval
    point(const double x)
    {
      return {x, x};
    }

    /** The smallest interval holding both a and b. */
    static Interval
    hull(const double a, const double b)
    {
      return {std::min(a, b), std::max(a, b)};
    }

    bool
    contains(const double x) const
    {
      return lower <= x && x <= upper;
    }

    double
    width() const
    {
      return upper - lower;
    }

    /** Widen by @p relative times the larger magnitude of the bounds plus @p
     * absolute. */
    Interval
    widened(const double relative, const double absolute = 0.) const
    {
      const double margin =
        relative * std::max(std::abs(lower), std::abs(upper)) + absolute;
      return {lower - margin, upper + margin};
    }
  };

  /** Relative outward-rounding margin used by the interval arithmetic: 4 units
   * of round-off. */
  constexpr double interval_rounding =
    4. * std::numeric_limits<double>::epsilon();

  inline Interval
  operator+(const Interval &a, const Interval &b)
  {
    return Interval{a.lower + b.lower, a.upper + b.upper}.widened(
      interval_rounding);
  }

  inline Interval
  operator-(const Interval &a, const Interval &b)
  {
    return Interval{a.lower - b.upper, a.upper - b.lower}.widened(
      interval_rounding);
  }

  inline Interval
  operator*(const Interval &a, const Interval &b)
  {
    const double p1 = a.lower * b.lower, p2 = a.lower * b.upper,
                 p3 = a.upper * b.lower, p4 = a.upper * b.upper;
    return Interval{std::min({p1, p2, p3, p4}), std::max({p1, p2, p3, p4})}
      .widened(interval_rounding);
  }

  inline Interval
  operator*(const double c, const Interval &a)
  {
    return (c >= 0. ? Interval{c * a.lower, c * a.upper} :
                      Interval{c * a.upper, c * a.lower})
      .widened(interval_rounding);
  }

  inline Interval &
  operator+=(Interval &a, const Interval &b)
  {
    a = a + b;
    return a;
  }

  /**
   * Range of the quadratic c0 + c1 s + c2 s^2 over [a, b], exact up to rounding
   * (the vertex is taken into account when it lies inside).
   */
  inline Interval
  quadratic_range(const double c0,
                  const double c1,
                  const double c2,
                  const double a,
                  const double b)
  {
    const auto f = [&](const double s) { return c0 + s * (c1 + s * c2); };
    Interval   r = Interval::hull(f(a), f(b));
    if (c2 != 0.)
      {
        const double vertex = -c1 / (2. * c2);
        if (vertex > a && vertex < b)
          {
            const double fv = f(vertex);
            r.lower         = std::min(r.lower, fv);
            r.upper         = std::max(r.upper, fv);
          }
      }
    const double scale = std::abs(c0) +
                         std::abs(c1) * std::max(std::abs(a), std::abs(b)) +
                         std::abs(c2) * std::max(a * a, b * b);
    return r.widened(0., interval_rounding * scale);
  }
} // namespace estep

#endif
