#ifndef estep_time_integration_first_crossing_search_h
#define estep_time_integration_first_crossing_search_h

#include <estep/systems/free_flight.h>

#include <cstdint>
#include <stdexcept>

namespace estep
{
  /**
   * Where a free flight starts relative to the two levels of its terrace.
   */
  enum class Departure
  {
    /** Strictly inside the terrace (start of a run). */
    interior,
    /** On the lower level L h, moving up into the terrace (after a climb). */
    from_lower_level,
    /** On the upper level (L+1) h, moving down into the terrace (after a
     * descent or a reflection). */
    from_upper_level
  };

  /**
   * The question the first-crossing search answers: along f(s) = V(q + s v), 0
   * < s <= horizon, when does f first reach @p lower_level or @p upper_level?
   */
  struct CrossingQuery
  {
    double    lower_level;
    double    upper_level;
    Departure departure;
    /** The crossings the search reports lie in (0, horizon]; its last window
     * may look past it (see first_window). */
    double horizon;
    /** Length of the first search window (e.g. the previous step); windows then
     * double, the last reaching past the horizon, so that which crossing is
     * found before the horizon, to the last bit, does not depend on it (a
     * run to a later end time passes through the same states). At most 0:
     * the horizon. */
    double first_window;
  };

  /**
   * The answer of the first-crossing search.
   */
  struct Crossing
  {
    /** +1: the upper level is reached, -1: the lower level, 0: neither before
     * the horizon. */
    int direction = 0;
    /** Flight parameter of the crossing (the horizon when direction == 0). */
    double s = 0.;
  };

  /** Work counters of the search. */
  struct SearchStatistics
  {
    std::uint64_t n_value_evaluations = 0;
    std::uint64_t n_enclosures        = 0;
    /** The part of n_value_evaluations spent locating crossings. */
    std::uint64_t n_locate_evaluations = 0;
    /** The most intervals one search examined (see max_intervals_examined). */
    std::uint64_t max_intervals_in_one_search = 0;
  };

  /**
   * The most parameter intervals one search examines. A search needs a few
   * tens per crossing; one that examines this many is crawling at the
   * round-off of f (the energy step below the round-off of V, or V not
   * finite) and gives up with SearchStalled.
   */
  constexpr std::uint64_t max_intervals_examined = std::uint64_t(1) << 20;

  /**
   * A search that examines this many intervals, and every multiple, asks
   * whether the run was interrupted (abandon_step_if_interrupted(), a
   * collective call on several MPI ranks), so that a signal ends a crawling
   * search long before max_intervals_examined. A search of a few tens of
   * intervals never asks.
   */
  constexpr std::uint64_t intervals_between_interruption_polls = 1024;

  /** Thrown by find_first_crossing() when it cannot decide: it examined
   * max_intervals_examined intervals, or the round-off of f blurs the
   * levels together. */
  class SearchStalled : public std::runtime_error
  {
  public:
    /** The search stalled for the @p reason given. */
    explicit SearchStalled(const std::string &reason);
  };

  /**
   * The certified first-crossing search of energy-stepping.
   *
   * Guarantee: no level is reached on (0, s) where s is the returned crossing
   * (or the horizon). It rests on the enclosures of FreeFlight::enclose(),
   * never on samples:
   * - the parameter range is covered from left to right by intervals [a, b]; an
   * interval is dismissed only when the enclosure of f over it proves that
   * neither level is reached there (the value range lies strictly between the
   * levels), or when the enclosure of f' proves f monotone on it and the end
   * values show that the level ahead is not reached;
   * - an interval that cannot be decided is halved and its left half examined
   * first, so the first crossing found is the first one;
   * - where f' has one sign the crossing is unique and is located by
   * safeguarded Newton iteration inside a shrinking bracket; the point returned
   * lies on the near side of the bracket (never after the crossing, before it
   * by at most a few units of round-off of s or the flight's value tolerance
   * of f);
   * - the departure level, on which the flight starts, is excluded near s = 0
   * only by a proven sign of f' over [0, b] (f moves into the terrace), never
   * by comparing f(s) with the level, so the departure root at s = 0 is never
   * returned and a return to the same level (a crossing right after a
   * reflection) is found like any other;
   * - where f(b) = +infinity (an inadmissible configuration, e.g. beyond the
   *   first element inversion) the interval is not enclosed but halved: V
   *   grows without bound towards it, so a level is reached before;
   * - an undecided interval shorter than the resolution (16 units of round-off
   * of the flight parameter) is reported as a crossing at its left end: the
   * search errs early, never late;
   * - while f stays within the band of the departure level (four times the
   *   flight's value tolerance, at least 16 units of round-off of the level),
   *   a proven slope back through that level (a
   *   return shallower than the round-off of f) reports the departure level
   *   as reached: where f(b) lies beyond it, at the latest;
   * - the search always ends: after max_intervals_examined intervals it
   *   throws SearchStalled instead of crawling on at round-off; so it does at
   *   once where that band is half the terrace or more (the round-off of f
   *   cannot tell the two levels apart); a requested interruption ends it
   *   with StepInterrupted (see intervals_between_interruption_polls).
   */
  Crossing
  find_first_crossing(const FreeFlight    &flight,
                      const CrossingQuery &query,
                      SearchStatistics    &statistics);
} // namespace estep

#endif
