#ifndef estep_time_integration_sampled_crossing_search_h
#define estep_time_integration_sampled_crossing_search_h

#include <estep/time_integration/first_crossing_search.h>

namespace estep
{
  /** Settings of the sampled search. */
  struct SamplingSettings
  {
    /** Samples of f per search window (equally spaced, the window's end
     * last). */
    unsigned int samples_per_window = 8;
    /** Bisection steps locating a bracketed crossing (fewer when the bracket
     * reaches the round-off of s). */
    unsigned int bisection_steps = 60;
  };

  /**
   * The first-crossing search as the reference text made it: sample f at
   * equally spaced points of windows that double from query.first_window on,
   * and bisect the first bracket where a sample lies on or beyond a level.
   * It answers the same question as find_first_crossing() but without its
   * guarantee: a crossing between two samples that comes back before the
   * next one (a grazing crossing, a thin bump of f) is stepped over. Kept as
   * a comparison (Crossing search = sampled), never the default.
   *
   * The departure level, on which f starts, counts as reached only once a
   * sample has been inside the terrace by more than its band (four times the
   * flight's value tolerance, at least 16 units of round-off of the level),
   * or beyond it by more than the band. The point returned is the near end
   * of the final bracket; its direction is that of the far end.
   */
  Crossing
  find_first_crossing_by_sampling(const FreeFlight       &flight,
                                  const CrossingQuery    &query,
                                  const SamplingSettings &settings,
                                  SearchStatistics       &statistics);
} // namespace estep

#endif
