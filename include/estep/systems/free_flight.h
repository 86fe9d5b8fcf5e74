#ifndef estep_systems_free_flight_h
#define estep_systems_free_flight_h

#include <estep/base/interval.h>

#include <limits>

namespace estep
{
  /**
   * Value and slope of the potential energy restricted to a free-flight line.
   */
  struct LineValue
  {
    /** f(s) = V(q + s v). */
    double value;
    /** f'(s) = grad V(q + s v) . v. */
    double derivative;

    /** The line value of a sum of energies. */
    LineValue &
    operator+=(const LineValue &other)
    {
      value += other.value;
      derivative += other.derivative;
      return *this;
    }
  };

  /**
   * Enclosures of the potential energy and of its slope over a parameter
   * interval of the line.
   */
  struct LineEnclosure
  {
    /** Holds every f(s) for s in [a, b]. */
    Interval value;
    /** Holds every f'(s) for s in [a, b]. */
    Interval derivative;
    /** Holds every f''(s) for s in [a, b], if f is twice differentiable there
     * and the enclosure knows; unbounded otherwise. */
    Interval curvature = {-std::numeric_limits<double>::infinity(),
                          std::numeric_limits<double>::infinity()};
    /**
     * Optional: a point of [a, b] where the enclosure evaluated f and f' (a
     * Taylor form's centre) and the computed values there, as
     * value_and_derivative() returns them; NaN if there is none. The search
     * starts locating a crossing from it instead of evaluating anew.
     */
    double    sample_point = std::numeric_limits<double>::quiet_NaN();
    LineValue sample       = {std::numeric_limits<double>::quiet_NaN(),
                              std::numeric_limits<double>::quiet_NaN()};
  };

  /**
   * The potential energy of a mechanical system restricted to one free-flight
   * line, f(s) = V(q + s v) for s >= 0, where q and v are the configuration and
   * velocity at the start of the flight (s is therefore time since the last
   * event).
   *
   * A system builds one object of this kind per free flight
   * (MechanicalSystem::free_flight()) and precomputes there whatever makes many
   * evaluations along the same line cheap. The certified first-crossing search
   * of EnergyStepping only uses this interface: point values and slopes, and
   * rigorous enclosures of both over parameter intervals. The search is as
   * correct as the enclosures are valid; they may be loose (the search
   * subdivides) but never too tight.
   */
  class FreeFlight
  {
  public:
    virtual ~FreeFlight() = default;

    /** f(s); +infinity where the configuration q + s v is inadmissible. */
    virtual double
    value(const double s) const = 0;

    /** f(s) and f'(s) together. */
    virtual LineValue
    value_and_derivative(const double s) const = 0;

    /**
     * Enclosures of f and f' over [a, b], 0 <= a < b < admissible_limit().
     * Every value taken on the interval must lie inside the returned intervals,
     * round-off included.
     */
    virtual LineEnclosure
    enclose(const double a, const double b) const = 0;

    /**
     * An absolute bound on the round-off error of value() (e.g. a few units of
     * round-off of the sum of the magnitudes of the terms V adds up). The
     * first-crossing search treats a flight that stays within this distance of
     * the level it departs from as still sitting on it. The default, 0,
     * claims exact values.
     */
    virtual double
    value_tolerance() const
    {
      return 0.;
    }

    /**
     * The end of the admissible part of the line: V is finite on [0,
     * admissible_limit()) (e.g. before the first element inversion of a
     * finite-element body); beyond it value() is +infinity and enclose() may
     * not bound anything, which the search treats as a level reached before.
     * Infinity by default.
     */
    virtual double
    admissible_limit() const
    {
      return std::numeric_limits<double>::infinity();
    }
  };
} // namespace estep

#endif
