#include <estep/systems/line_taylor_form.h>

#include <algorithm>
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

    inline bool
    bounded(const Interval &a)
    {
      return std::isfinite(a.lower) && std::isfinite(a.upper);
    }
  } // namespace



  LineTaylorForm
  LineTaylorForm::about_centre_of(const double a, const double b)
  {
    LineTaylorForm form;
    form.centre = a + 0.5 * (b - a);
    // [a, b] lies in [m - r, m + r] despite the rounding of m.
    form.radius = std::max(b - form.centre, form.centre - a) * (1. + 4. * unit);
    return form;
  }



  LineTaylorForm &
  LineTaylorForm::operator+=(const LineTaylorForm &other)
  {
    if (other.centre != centre || other.radius != radius)
      throw std::logic_error("LineTaylorForm: adding forms about different "
                             "intervals");
    // The sums at the centre are rounded (once here, once in the point
    // evaluation of the sum).
    value_error +=
      other.value_error + 2. * unit * (std::abs(value) + std::abs(other.value));
    slope_error +=
      other.slope_error + 2. * unit * (std::abs(slope) + std::abs(other.slope));
    value += other.value;
    slope += other.slope;
    curvature    = curvature + other.curvature;
    slope_offset = slope_offset + other.slope_offset;
    return *this;
  }



  LineTaylorForm
  LineTaylorForm::scaled(const double c) const
  {
    LineTaylorForm form = *this;
    form.value          = c * value;
    form.slope          = c * slope;
    form.curvature      = c * curvature;
    form.slope_offset   = c * slope_offset;
    form.value_error =
      std::abs(c) * value_error + 2. * unit * std::abs(form.value);
    form.slope_error =
      std::abs(c) * slope_error + 2. * unit * std::abs(form.slope);
    return form;
  }



  bool
  LineTaylorForm::bounds_curvature() const
  {
    return slope_offset.lower == 0. && slope_offset.upper == 0. &&
           bounded(curvature);
  }



  LineEnclosure
  LineTaylorForm::enclosure() const
  {
    if (!bounded(curvature) || !bounded(slope_offset) ||
        !std::isfinite(value) || !std::isfinite(slope) ||
        !std::isfinite(value_error) || !std::isfinite(slope_error))
      return {entire, entire};
    const double r = radius;
    // The slopes of the two quadratics on either side of the centre, and the
    // rounding of these sums over the half-width.
    const double slope_low  = slope + slope_offset.lower;
    const double slope_high = slope + slope_offset.upper;
    const double rounding =
      unit * (std::abs(slope_low) + std::abs(slope_high)) * r;
    const double value_margin = 2. * value_error + slope_error * r + rounding;
    // f(m + t) - f(m) - f'(m) t lies in C t^2 / 2 + W t: for t >= 0 the
    // extreme slopes are f'(m) + W_lo/hi, for t <= 0 the other way round.
    const double low = std::min(
      quadratic_range(value, slope_low, 0.5 * curvature.lower, 0., r).lower,
      quadratic_range(value, slope_high, 0.5 * curvature.lower, -r, 0.).lower);
    const double high = std::max(
      quadratic_range(value, slope_high, 0.5 * curvature.upper, 0., r).upper,
      quadratic_range(value, slope_low, 0.5 * curvature.upper, -r, 0.).upper);
    LineEnclosure e;
    e.value = Interval{low, high}.widened(0., value_margin);
    e.derivative =
      (Interval::point(slope) + curvature * Interval{-r, r} + slope_offset)
        .widened(0., 2. * slope_error);
    if (bounds_curvature())
      e.curvature = curvature;
    return e;
  }



  LineTaylorForm
  LineTaylorForm::from_enclosure(const double         centre,
                                 const double         radius,
                                 const LineValue     &at_centre,
                                 const LineEnclosure &enclosure,
                                 const double         value_error)
  {
    LineTaylorForm form;
    form.centre = centre;
    form.radius = radius;
    form.value  = at_centre.value;
    form.slope  = at_centre.derivative;
    form.slope_offset =
      bounded(enclosure.derivative) ?
        enclosure.derivative - Interval::point(at_centre.derivative) :
        entire;
    form.value_error = value_error;
    return form;
  }
} // namespace estep
