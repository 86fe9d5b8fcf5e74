#ifndef estep_systems_line_taylor_form_h
#define estep_systems_line_taylor_form_h

#include <estep/base/interval.h>
#include <estep/systems/free_flight.h>

namespace estep
{
  /**
   * A second-order (Taylor) form of a function f along a free flight over the
   * parameter interval [m - r, m + r]: the computed value and slope at the
   * centre m, f(m) and f'(m), and intervals C and W such that for |t| <= r
   *
   *   f'(m + t) lies in f'(m) + C t + W (+- slope_error),
   *   f(m + t)  lies in f(m) + f'(m) t + C t^2 / 2 + W t
   *                     (+- value_error + slope_error |t|)
   *
   * for the exact f (the second line is the integral of the first). C holds
   * f'' wherever f is twice differentiable; W (an interval containing 0)
   * holds the jumps of f' at kinks, where f is continuous with one-sided
   * slopes, or replaces C where no curvature bound is known (W = f'([a, b])
   * - f'(m)). value_error and slope_error also bound the difference between
   * the computed and the exact f and f' anywhere on the interval, so that
   * enclosure() holds both.
   *
   * Forms of several terms about the same centre add up term by term: the
   * slopes at the centre are summed before any interval is formed, so terms
   * whose slopes cancel (near a grazing crossing of their sum) do not widen
   * the enclosure of the sum.
   *
   * The elastic body's flight (ElasticFreeFlight), the penalty contact's
   * (contact::PenaltyFlight) and the contact system's, which adds the two,
   * build their enclosures from such forms.
   */
  struct LineTaylorForm
  {
    double centre = 0.;
    double radius = 0.;
    /** f(m) and f'(m), as computed. */
    double value = 0.;
    double slope = 0.;
    /** C: f'' where it exists. */
    Interval curvature = {0., 0.};
    /** W: the part of f'(m + t) - f'(m) not accounted for by C t. */
    Interval slope_offset = {0., 0.};
    /** Round-off bounds (see above). */
    double value_error = 0.;
    double slope_error = 0.;

    /** A form of f = 0 about the centre of [a, b], with a radius that covers
     * [a, b] despite the rounding of the centre. */
    static LineTaylorForm
    about_centre_of(const double a, const double b);

    /** The sum of two forms about the same centre (throws std::logic_error
     * for different centres or radii). */
    LineTaylorForm &
    operator+=(const LineTaylorForm &other);

    /** The form of c f. */
    LineTaylorForm
    scaled(const double c) const;

    /**
     * Whether the form bounds f'' over the whole interval: W = 0 exactly (no
     * kink, f is continuously differentiable) and C bounded. Then C holds
     * f'' wherever it exists, and f is convex on the interval if C > 0,
     * concave if C < 0.
     */
    bool
    bounds_curvature() const;

    /**
     * Enclosures of f and f' over [m - r, m + r]: the exact ranges of the two
     * quadratics f(m) + (f'(m) + W_lo/hi) t + C_lo/hi t^2 / 2 on either side of
     * the centre, and f'(m) + C [-r, r] + W, widened by the round-off bounds.
     * Unbounded if C or W is. The curvature of the enclosure is C where
     * bounds_curvature(), unbounded otherwise; it has no sample (a form's
     * value and slope at the centre need not be exactly what a flight's
     * value_and_derivative() computes there: the flight adds the sample).
     */
    LineEnclosure
    enclosure() const;

    /**
     * The first-order form of a term that only offers point values and
     * enclosures over [m - r, m + r]: C = 0, W = @p enclosure.derivative -
     * f'(m) (unbounded if that is), value_error = @p value_error (a bound of
     * the round-off of the term's values), slope_error = 0 (the slope
     * enclosure holds the computed slopes already).
     */
    static LineTaylorForm
    from_enclosure(const double         centre,
                   const double         radius,
                   const LineValue     &at_centre,
                   const LineEnclosure &enclosure,
                   const double         value_error);
  };
} // namespace estep

#endif
