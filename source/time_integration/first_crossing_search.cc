#include <estep/base/exception_text.h>
#include <estep/base/interruption.h>
#include <estep/time_integration/first_crossing_search.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace estep
{
  namespace
  {
    constexpr double epsilon = std::numeric_limits<double>::epsilon();

    /** A parameter interval [a, b] waiting to be examined, with f at its ends.
     */
    struct PendingInterval
    {
      double a, b, fa, fb;
    };

    /**
     * The crossing of @p level on [a, b], where f is proven monotone, f(a) has
     * not reached the level and f(b) has. Safeguarded Newton iteration inside a
     * shrinking bracket [lo, hi] (lo on the near side, hi beyond), bisection
     * when Newton leaves the bracket or is slow. It stops when f is within the
     * flight's value tolerance of the level or the Newton step is a few units
     * of round-off of s; the point returned is then on the near side (or
     * exactly on the level): a point found beyond is stepped back by twice its
     * Newton correction, doubled until f is on the near side (Newton aims half
     * the tolerance short of the level, which makes that rare). The first
     * point is the enclosure's sample of [a, b] if it has one (no evaluation:
     * its values narrow the bracket and give the first Newton step), else
     * the secant point of [a, b].
     */
    double
    locate_crossing(const FreeFlight    &flight,
                    const double         level,
                    const double         a,
                    const double         b,
                    const double         fa,
                    const double         fb,
                    const LineEnclosure &enclosure,
                    SearchStatistics    &statistics)
    {
      const double sign =
        (fb >= fa) ? 1. : -1.; // g = sign (f - level) increases
      const auto g_at = [&](const double s) {
        ++statistics.n_value_evaluations;
        ++statistics.n_locate_evaluations;
        const LineValue f = flight.value_and_derivative(s);
        return LineValue{sign * (f.value - level), sign * f.derivative};
      };
      const double noise = flight.value_tolerance();
      // Newton aims half the tolerance short of the level, so that the point
      // it converges to is usually on the near side already.
      const double target = 0.5 * noise;
      // The step from a point with values g, g' (g' > 0) to the model's
      // crossing of -target: the root nearest 0 of g + target + g' t +
      // kappa t^2 / 2 with kappa the centre of the enclosure's curvature
      // (a plain Newton step where that is unknown or the model has no
      // root).
      const double kappa =
        (std::isfinite(enclosure.curvature.lower) &&
         std::isfinite(enclosure.curvature.upper)) ?
          sign * 0.5 * (enclosure.curvature.lower + enclosure.curvature.upper) :
          0.;
      const auto model_step = [&](const double g, const double dg) {
        const double c            = g + target;
        const double discriminant = dg * dg - 2. * kappa * c;
        return discriminant >= 0. ? -2. * c / (dg + std::sqrt(discriminant)) :
                                    -c / dg;
      };
      double       lo = a, hi = b;
      const double g_lo = sign * (fa - level), g_hi = sign * (fb - level);
      double       x             = (std::isfinite(g_hi) && g_hi > g_lo) ?
                                     lo - g_lo * (hi - lo) / (g_hi - g_lo) :
                                     0.5 * (lo + hi);
      double       previous_step = hi - lo;
      const double m             = enclosure.sample_point;
      if (m > lo && m < hi && std::isfinite(enclosure.sample.value) &&
          std::isfinite(enclosure.sample.derivative))
        {
          const double gm = sign * (enclosure.sample.value - level),
                       dg = sign * enclosure.sample.derivative;
          if (gm == 0. || (gm < 0. && -gm <= noise))
            return m; // on the level, or within round-off on the near side
          (gm < 0. ? lo : hi) = m;
          x = (dg > 0.) ? m + model_step(gm, dg) : 0.5 * (lo + hi);
        }
      for (unsigned int iteration = 0; iteration < 200; ++iteration)
        {
          const double resolution =
            4. * epsilon * std::max(std::abs(lo), std::abs(hi));
          if (hi - lo <= resolution)
            break;
          if (!(x > lo && x < hi))
            x = 0.5 * (lo + hi);
          const LineValue gx = g_at(x);
          if (gx.value == 0.)
            return x;
          (gx.value < 0. ? lo : hi) = x;

          const double newton =
            (gx.derivative > 0.) ? -gx.value / gx.derivative : hi - lo;
          if (std::abs(gx.value) <= noise || std::abs(newton) <= resolution)
            {
              // Converged: x is within round-off of the crossing. Return a
              // point on the near side.
              if (gx.value < 0.)
                return x;
              double back = std::max(2. * std::abs(newton), 2. * resolution);
              while (x - back > lo)
                {
                  const double before = x - back;
                  if (g_at(before).value <= 0.)
                    return before;
                  hi = before;
                  back *= 2.;
                }
              return lo;
            }
          double step =
            (gx.derivative > 0.) ? model_step(gx.value, gx.derivative) : newton;
          if (!(x + step > lo && x + step < hi) ||
              std::abs(step) > 0.5 * previous_step)
            step = 0.5 * (lo + hi) - x; // bisect
          previous_step = std::abs(step);
          x += step;
        }
      return lo;
    }
  } // namespace



  SearchStalled::SearchStalled(const std::string &reason)
    : std::runtime_error(reason)
  {}



  namespace
  {
    /** The end of a stall's reason where a larger energy step may help. */
    const std::string step_below_round_off =
      ". The energy step is likely below the round-off of the potential "
      "energy (or V is not finite there); try a larger Energy step";

    /** find_first_crossing() in windows that double from the first one on,
     * the last reaching past the horizon (so that no window depends on the
     * horizon): a crossing it returns may lie beyond it. */
    Crossing
    first_crossing_in_windows(const FreeFlight    &flight,
                              const CrossingQuery &query,
                              SearchStatistics    &statistics)
    {
      const double c0  = query.lower_level;
      const double c1  = query.upper_level;
      const double end = query.horizon;
      // The band around a level that counts as sitting on it: a few times the
      // flight's round-off, so that enclosures (widened by that round-off
      // themselves) can fit inside, and never less than a few units of
      // round-off of the level itself, which no computed value of f can
      // resolve (a flight that claims exact values, value_tolerance() = 0, but
      // widens its enclosures by their rounding would otherwise crawl away from
      // a level it departs from tangentially, one resolution at a time).
      const double tolerance =
        4. * std::max(flight.value_tolerance(),
                      4. * epsilon * std::max(std::abs(c0), std::abs(c1)));
      if (!std::isfinite(tolerance))
        throw SearchStalled(
          "the round-off of V along the flight has no finite bound: V is "
          "not smooth enough there for a certified search (as the penalty "
          "between flush, coplanar faces), whatever the energy step");
      if (!(tolerance < 0.5 * (c1 - c0)))
        throw SearchStalled("the round-off band of V along the flight, " +
                            message_number(tolerance) +
                            ", is not below half the energy step" +
                            step_below_round_off);
      // f = +infinity where the configuration is inadmissible (beyond the
      // flight's admissible limit); such intervals are never enclosed.
      const auto value_at = [&](const double s) {
        ++statistics.n_value_evaluations;
        return flight.value(s);
      };
      const double f_zero = value_at(0.);
      // The level the flight sits on at s = 0, if any: the departure level, or
      // a level that f(0) lies within the band of.
      const double sitting_level =
        query.departure == Departure::from_lower_level ?
          c0 :
        query.departure == Departure::from_upper_level ?
          c1 :
        std::abs(f_zero - c0) <= tolerance ?
          c0 :
        std::abs(f_zero - c1) <= tolerance ?
          c1 :
          std::numeric_limits<double>::quiet_NaN();
      const bool sitting = !std::isnan(sitting_level);
      // The side of the sitting level the terrace lies on: +1 on the lower
      // level, -1 on the upper one, 0 strictly inside. A flight that starts
      // interior but within the band of a level (a run whose initial V lies on
      // a level, to round-off) is treated as departing from it: the flight is
      // on the level, and moving out of the terrace through it is a crossing
      // at once, not a crawl along the band.
      const int departure_sign = !sitting ? 0 : sitting_level == c0 ? +1 : -1;
      // On [0, prefix_end] f is proven not to leave the sitting level and come
      // back: it stays within the tolerance of it, or moves away monotonically.
      double       prefix_end = 0.;
      const double resolution_floor =
        std::max(query.first_window, std::numeric_limits<double>::min());

      std::vector<PendingInterval> pending;
      std::uint64_t                n_examined = 0;
      double window_start = 0., window_length = query.first_window;
      if (!(window_length > 0.))
        window_length = end;
      double f_start = f_zero;

      // Whether enclosures were made, and whether any bounded f'': if none
      // did (no convexity rule could apply), that is the likely cause of a
      // stall.
      bool enclosed = false, curvature_bounded = false;
      while (window_start < end)
        {
          const double window_end = window_start + window_length;
          const double f_end      = value_at(window_end);
          pending.push_back({window_start, window_end, f_start, f_end});

          while (!pending.empty())
            {
              const PendingInterval I = pending.back();
              pending.pop_back();
              if (++n_examined % intervals_between_interruption_polls == 0)
                abandon_step_if_interrupted();
              if (n_examined > max_intervals_examined)
                throw SearchStalled(
                  "the first-crossing search examined " +
                  std::to_string(max_intervals_examined) +
                  " intervals without deciding, the last at flight parameter "
                  "s = " +
                  message_number(I.a) + ", " + message_number(I.b - I.a) +
                  " wide" +
                  (enclosed && !curvature_bounded ?
                     ". The flight's enclosures bound no curvature of V (a "
                     "material without Material::"
                     "volumetric_second_derivative_range(), for one), and "
                     "without it the search cannot settle a turning point of "
                     "V close to a level; give the material that range, or "
                     "try a larger Energy step" :
                     step_below_round_off));
              statistics.max_intervals_in_one_search =
                std::max(statistics.max_intervals_in_one_search, n_examined);
              // The rules for the sitting level apply while f(a) is still
              // within its band; beyond, f(a) is strictly inside the terrace.
              const bool in_prefix =
                sitting && I.a == prefix_end &&
                std::abs(I.fa - sitting_level) <= tolerance;
              const bool at_limit    = !std::isfinite(I.fb);
              bool       up_possible = true, down_possible = true;

              if (!at_limit)
                {
                  const LineEnclosure enclosure = flight.enclose(I.a, I.b);
                  ++statistics.n_enclosures;
                  enclosed = true;
                  curvature_bounded =
                    curvature_bounded ||
                    std::isfinite(enclosure.curvature.lower) ||
                    std::isfinite(enclosure.curvature.upper);
                  const bool increasing = enclosure.derivative.lower > 0.;
                  const bool decreasing = enclosure.derivative.upper < 0.;
                  // The unique crossing in [a, b] of the level in @p direction,
                  // f(a) = fa on the near side of it, f(b) = fb beyond.
                  const auto locate = [&](const int    direction,
                                          const double a,
                                          const double fa,
                                          const double b,
                                          const double fb) -> Crossing {
                    return {direction,
                            locate_crossing(flight,
                                            direction > 0 ? c1 : c0,
                                            a,
                                            b,
                                            fa,
                                            fb,
                                            enclosure,
                                            statistics)};
                  };

                  if (in_prefix &&
                      enclosure.value.lower >= sitting_level - tolerance &&
                      enclosure.value.upper <= sitting_level + tolerance)
                    {
                      // Still sitting on the level, within round-off.
                      prefix_end = I.b;
                      continue;
                    }

                  if (in_prefix && departure_sign != 0 &&
                      (departure_sign > 0 ? increasing : decreasing))
                    {
                      // Moving away from the departure level all the way from s
                      // = 0: only the level ahead can be reached, and only if
                      // f(b) reaches it.
                      prefix_end = I.b;
                      if (departure_sign > 0 && I.fb >= c1)
                        return locate(+1, I.a, I.fa, I.b, I.fb);
                      if (departure_sign < 0 && I.fb <= c0)
                        return locate(-1, I.a, I.fa, I.b, I.fb);
                      continue;
                    }

                  if (in_prefix && departure_sign != 0 &&
                      (departure_sign > 0 ? decreasing : increasing))
                    {
                      // Still within the band of the departure level, and
                      // proven to move back through it: f came back within the
                      // band (a dip or bump shallower than the round-off), so
                      // the departure level is the one reached, at the latest
                      // where f(b) is beyond it; if f(a) is beyond it already,
                      // the flight is on it at a.
                      const int direction = -departure_sign;
                      if (direction * (I.fb - sitting_level) >= 0.)
                        {
                          if (direction * (I.fa - sitting_level) < 0.)
                            return locate(direction, I.a, I.fa, I.b, I.fb);
                          return {direction, I.a};
                        }
                      prefix_end = I.b;
                      continue;
                    }

                  // A NaN bound proves nothing: the level stays possible.
                  up_possible   = !(enclosure.value.upper < c1);
                  down_possible = !(enclosure.value.lower > c0);
                  // Convexity: where f is convex its sublevel sets are
                  // intervals, so on [a, b] it stays below max(f(a), f(b)) and
                  // crosses a level at most once going down and once going up;
                  // where it is concave, the mirror image. This decides
                  // intervals that hold a turning point of f, where the slope
                  // has no sign. It applies where f(a) lies strictly inside the
                  // terrace (outside the prefix: everything before a has been
                  // dismissed) or on the level f departs from, moving away.
                  {
                    const double m  = enclosure.sample_point;
                    const double fm = enclosure.sample.value;
                    const bool   sampled =
                      m > I.a && m < I.b && std::isfinite(fm);
                    const bool inside = !in_prefix;
                    if (enclosure.curvature.lower > 0. &&
                        (inside || (departure_sign < 0 && in_prefix)))
                      {
                        // Convex, from inside or leaving c1 downwards.
                        if (I.fb <= c0)
                          return locate(-1, I.a, I.fa, I.b, I.fb);
                        if (I.fb >= c1)
                          {
                            if (!down_possible && inside)
                              return locate(+1, I.a, I.fa, I.b, I.fb);
                            if (!down_possible && sampled && fm < c1)
                              return locate(+1, m, fm, I.b, I.fb);
                          }
                        else
                          {
                            if (sampled && fm <= c0)
                              return locate(-1, I.a, I.fa, m, fm);
                            up_possible = false;
                          }
                      }
                    else if (enclosure.curvature.upper < 0. &&
                             (inside || (departure_sign > 0 && in_prefix)))
                      {
                        // Concave, from inside or leaving c0 upwards.
                        if (I.fb >= c1)
                          return locate(+1, I.a, I.fa, I.b, I.fb);
                        if (I.fb <= c0)
                          {
                            if (!up_possible && inside)
                              return locate(-1, I.a, I.fa, I.b, I.fb);
                            if (!up_possible && sampled && fm > c0)
                              return locate(-1, m, fm, I.b, I.fb);
                          }
                        else
                          {
                            if (sampled && fm >= c1)
                              return locate(+1, I.a, I.fa, m, fm);
                            down_possible = false;
                          }
                      }
                  }
                  if (!up_possible && !down_possible)
                    continue;

                  if (!in_prefix && (increasing || decreasing))
                    {
                      // f(a) lies strictly inside the terrace (everything
                      // before a has been dismissed), so a monotone f can only
                      // reach the level ahead of it.
                      if (increasing && I.fb >= c1)
                        return locate(+1, I.a, I.fa, I.b, I.fb);
                      if (decreasing && I.fb <= c0)
                        return locate(-1, I.a, I.fa, I.b, I.fb);
                      continue;
                    }
                }

              const double resolution =
                16. * epsilon * std::max(I.b, resolution_floor);
              if (I.b - I.a <= resolution)
                {
                  if (in_prefix)
                    {
                      // Not separable from the departure root at s = 0 (a
                      // tangential departure): accepted as part of the
                      // departure.
                      prefix_end = I.b;
                      if (departure_sign > 0 && I.fb >= c1)
                        return {+1, I.a};
                      if (departure_sign < 0 && I.fb <= c0)
                        return {-1, I.a};
                      continue;
                    }
                  // Undecidable at the resolution: report a crossing here
                  // (early, never late).
                  const bool up =
                    at_limit ||
                    (up_possible && (!down_possible || std::abs(I.fa - c1) <=
                                                         std::abs(I.fa - c0)));
                  return {up ? +1 : -1, I.a};
                }

              const double mid = I.a + 0.5 * (I.b - I.a);
              const double fm  = value_at(mid);
              pending.push_back({mid, I.b, fm, I.fb});
              pending.push_back({I.a, mid, I.fa, fm});
            }

          window_start = window_end;
          f_start      = f_end;
          window_length *= 2.;
        }
      return {0, end};
    }
  } // namespace



  Crossing
  find_first_crossing(const FreeFlight    &flight,
                      const CrossingQuery &query,
                      SearchStatistics    &statistics)
  {
    const Crossing crossing =
      first_crossing_in_windows(flight, query, statistics);
    if (crossing.direction != 0 && crossing.s > query.horizon)
      return {0, query.horizon};
    return crossing;
  }
} // namespace estep
