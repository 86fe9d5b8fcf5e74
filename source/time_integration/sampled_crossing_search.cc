#include <estep/time_integration/sampled_crossing_search.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace estep
{
  Crossing
  find_first_crossing_by_sampling(const FreeFlight       &flight,
                                  const CrossingQuery    &query,
                                  const SamplingSettings &settings,
                                  SearchStatistics       &statistics)
  {
    const double epsilon = std::numeric_limits<double>::epsilon();
    const auto   band    = [&](const double level) {
      return std::max(4. * flight.value_tolerance(),
                      16. * epsilon * std::abs(level));
    };
    // A departure level counts once f has left its band into the terrace.
    bool         lower_armed = query.departure != Departure::from_lower_level;
    bool         upper_armed = query.departure != Departure::from_upper_level;
    const double lower_band  = band(query.lower_level);
    const double upper_band  = band(query.upper_level);

    // +1 / -1 where f lies on or beyond the upper / lower level, else 0.
    const auto side = [&](const double f) {
      if (f >= query.upper_level + (upper_armed ? 0. : upper_band))
        return +1;
      if (f < query.lower_level - (lower_armed ? 0. : lower_band))
        return -1;
      return 0;
    };
    const auto arm = [&](const double f) {
      lower_armed = lower_armed || f > query.lower_level + lower_band;
      upper_armed = upper_armed || f < query.upper_level - upper_band;
    };

    const unsigned int n = std::max(1u, settings.samples_per_window);
    double             a = 0.;
    double window = std::min(std::max(query.first_window, 0.), query.horizon);
    if (!(window > 0.))
      window = query.horizon;
    while (a < query.horizon)
      {
        const double b        = std::min(a + window, query.horizon);
        double       s_inside = a;
        for (unsigned int k = 1; k <= n; ++k)
          {
            const double s = (k == n) ? b : a + (b - a) * k / n;
            const double f = flight.value(s);
            ++statistics.n_value_evaluations;
            int direction = side(f);
            if (direction == 0)
              {
                arm(f);
                s_inside = s;
                continue;
              }
            // Bisect [s_inside, s] down to the round-off of s.
            double lo = s_inside, hi = s;
            for (unsigned int i = 0; i < settings.bisection_steps &&
                                     hi - lo > 4. * epsilon * std::abs(hi);
                 ++i)
              {
                const double m   = 0.5 * (lo + hi);
                const double f_m = flight.value(m);
                ++statistics.n_value_evaluations;
                ++statistics.n_locate_evaluations;
                if (const int d = side(f_m); d != 0)
                  {
                    hi        = m;
                    direction = d;
                  }
                else
                  lo = m;
              }
            return {direction, lo};
          }
        a = b;
        window *= 2.;
      }
    return {0, query.horizon};
  }
} // namespace estep
