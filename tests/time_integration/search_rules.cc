// One constructed function per rule of the first-crossing search that lets it
// dismiss or decide an interval without bisecting (enclosure, monotonicity,
// convexity, concavity, departure level, sitting band, prefix, centre
// sample, resolution): each function is built so that the rule, wrong in
// either direction, gives a missed, a wrong or a late crossing, and each test
// asserts the exact first crossing. The mutation suite (tests/mutations/)
// checks that every such mistake is caught here.
#include <estep/time_integration/first_crossing_search.h>

#include <gtest/gtest.h>

#include "test_flights.h"

#include <cmath>
#include <vector>

namespace
{
  using namespace estep;
  using estep::testing::BumpFlight;
  using estep::testing::PolynomialFlight;

  /** The smaller root of c2 s^2 + c1 s + c0 (two real roots), computed
   * without cancellation. */
  double
  first_root(const double c0, const double c1, const double c2)
  {
    const double q =
      -0.5 * (c1 + std::copysign(std::sqrt(c1 * c1 - 4. * c2 * c0), c1));
    const double r1 = q / c2, r2 = c0 / q;
    return std::min(r1 > 0. ? r1 : INFINITY, r2 > 0. ? r2 : INFINITY);
  }

  /** The search on [0, horizon] in one first window, levels 0 and 1. */
  Crossing
  search(const FreeFlight &flight,
         const Departure   departure,
         const double      horizon,
         SearchStatistics *statistics = nullptr)
  {
    SearchStatistics local;
    return find_first_crossing(flight,
                               {0., 1., departure, horizon, horizon},
                               statistics ? *statistics : local);
  }

  /** The returned crossing is the exact first one: its direction, and its
   * parameter on the near side of @p s_exact within @p tolerance. */
  void
  expect_crossing(const Crossing &crossing,
                  const int       direction,
                  const double    s_exact,
                  const double    tolerance = 1e-12)
  {
    EXPECT_EQ(crossing.direction, direction);
    EXPECT_NEAR(crossing.s, s_exact, tolerance);
    EXPECT_LE(crossing.s, s_exact + 1e-14);
  }

  /** A quadratic c0 + c1 s + c2 s^2 and its mirror image 1 - f about the
   * middle of the terrace [0, 1] (each convex rule tested on the first is the
   * concave rule on the second, with the direction of every crossing and
   * departure reversed). */
  struct MirroredQuadratic
  {
    double c0, c1, c2;

    PolynomialFlight
    flight(const bool mirrored) const
    {
      return mirrored ? PolynomialFlight({1. - c0, -c1, -c2}, true) :
                        PolynomialFlight({c0, c1, c2}, true);
    }
  };

  Departure
  mirror(const Departure departure, const bool mirrored)
  {
    if (!mirrored || departure == Departure::interior)
      return departure;
    return departure == Departure::from_lower_level ?
             Departure::from_upper_level :
             Departure::from_lower_level;
  }

  // -- Enclosure: an interval is dismissed only if its value range lies
  // strictly between the levels.

  TEST(SearchRules, EnclosureFindsAThinDipBelowTheLowerLevel)
  {
    // The mirror image of the thin bump: 1e-9 below 0 over about 1e-8 in s.
    const double     s0 = 0.35, w = 1e-4, A = 0.5 + 1e-9;
    const BumpFlight flight(0.5, -A, s0, w);
    expect_crossing(search(flight, Departure::interior, 1.),
                    -1,
                    s0 - w * std::sqrt(std::log(A / 0.5)));
  }

  TEST(SearchRules, AnEnclosureThatProvesNothingIsNeverDismissed)
  {
    // f = 0.5 + s, but its enclosures are NaN over [0.3, 0.31] (as where V is
    // not finite): the search may not pass there, so it reports the upper
    // level at 0.3 at the latest instead of its crossing at 0.5.
    class Blind : public PolynomialFlight
    {
    public:
      Blind()
        : PolynomialFlight({0.5, 1.})
      {}
      LineEnclosure
      enclose(const double a, const double b) const override
      {
        if (b >= 0.3 && a <= 0.31)
          return {{NAN, NAN}, {NAN, NAN}};
        return PolynomialFlight::enclose(a, b);
      }
    };
    const Crossing crossing = search(Blind(), Departure::interior, 1.);
    EXPECT_EQ(crossing.direction, +1);
    EXPECT_LE(crossing.s, 0.3);
  }

  // -- Resolution: an interval still undecided at the resolution of s is a
  // crossing at its left end, never dismissed.

  TEST(SearchRules, ANearMissWithinTheRoundOffIsReportedAsATouch)
  {
    // f = 1 - 1e-15 - (s - 0.25)^2 peaks 1e-15 below the level, inside the
    // round-off the flight claims (1e-14, by which its enclosures widen): no
    // enclosure decides the intervals around the peak, and the search reports
    // a touch there (early, never late), not the crossing of 0 at 1.24.
    for (const bool mirrored : {false, true})
      {
        const double           top = 1. - 1e-15;
        const PolynomialFlight flight =
          mirrored ?
            PolynomialFlight({1. - (top - 0.0625), -0.5, 1.}, false, 1e-14) :
            PolynomialFlight({top - 0.0625, 0.5, -1.}, false, 1e-14);
        const Crossing crossing = search(flight, Departure::interior, 2.);
        EXPECT_EQ(crossing.direction, mirrored ? -1 : +1);
        EXPECT_LE(crossing.s, 0.25);
        EXPECT_GT(crossing.s, 0.25 - 1e-6);
      }
  }

  // -- Monotonicity: where f' has one sign only the level ahead can be
  // reached, and only if f(b) reaches it.

  TEST(SearchRules, MonotoneFlightsReachTheLevelAheadAtTheEnd)
  {
    // f(b) exactly on the level (dyadic data): reached, not missed.
    expect_crossing(
      search(PolynomialFlight({0.5, 2.}), Departure::interior, 0.25), +1, 0.25);
    expect_crossing(search(PolynomialFlight({0.5, -2.}),
                           Departure::interior,
                           0.25),
                    -1,
                    0.25);
    // And inside: the crossing of the level ahead, the other one never.
    expect_crossing(search(PolynomialFlight({0.5, 3.}),
                           Departure::interior,
                           1.),
                    +1,
                    1. / 6.);
    expect_crossing(search(PolynomialFlight({0.5, -3.}),
                           Departure::interior,
                           1.),
                    -1,
                    1. / 6.);
    // Short of the level ahead: no crossing.
    const Crossing none =
      search(PolynomialFlight({0.5, 1.}), Departure::interior, 0.25);
    EXPECT_EQ(none.direction, 0);
    EXPECT_EQ(none.s, 0.25);
  }

  // -- Convexity and concavity, from inside the terrace. Each case in both
  // mirror images: convex as written, concave mirrored.

  TEST(SearchRules, ConvexDipThroughTheLowerLevelBetweenItsSamples)
  {
    // f = 0.09 - 2 s + 10 s^2 on [0, 0.3]: ends inside (0.39), its centre
    // sample (0.015) is inside, yet it dips below 0 on (0.068, 0.132). Convex
    // and ending inside, only the lower level can be reached: the rule
    // clearing the wrong direction misses it (concave: the 0.91 + 2 s
    // - 10 s^2 with the level 1).
    const MirroredQuadratic f{0.09, -2., 10.};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored), Departure::interior, 0.3),
                      mirrored ? +1 : -1,
                      first_root(0.09, -2., 10.));
  }

  TEST(SearchRules, ConvexEndingBelowTheLowerLevel)
  {
    // f(b) below 0: the crossing of 0, located on all of [a, b].
    const MirroredQuadratic f{0.5, -5., 1.};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored), Departure::interior, 0.3),
                      mirrored ? +1 : -1,
                      first_root(0.5, -5., 1.));
  }

  TEST(SearchRules, ConvexDipsBelowTheLowerLevelBeforeClimbingPastTheUpper)
  {
    // f = 0.02 - 2 s + 30 s^2 ends at 2.12 above 1 but first dips below 0:
    // the upper crossing may be located on [a, b] only where the lower level
    // is proven out of reach.
    const MirroredQuadratic f{0.02, -2., 30.};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored), Departure::interior, 0.3),
                      mirrored ? +1 : -1,
                      first_root(0.02, -2., 30.));
  }

  TEST(SearchRules, ConvexClimbingPastTheUpperLevel)
  {
    // f = 0.5 + 0.1 s + 10 s^2: the lower level out of reach, the upper one
    // crossed once.
    const MirroredQuadratic f{0.5, 0.1, 10.};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored), Departure::interior, 0.3),
                      mirrored ? -1 : +1,
                      first_root(-0.5, 0.1, 10.));
  }

  TEST(SearchRules, ConvexWithTheCentreSampleBelowTheLowerLevel)
  {
    // f = 0.1 - 4 s + 13.5 s^2: the centre sample (-0.196) is below 0, f(b)
    // inside: the crossing lies in [a, m], located there.
    const MirroredQuadratic f{0.1, -4., 13.5};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored), Departure::interior, 0.3),
                      mirrored ? +1 : -1,
                      first_root(0.1, -4., 13.5));
  }

  TEST(SearchRules, ConvexEndingAboveWithTheCentreSampleBelowTheUpperLevel)
  {
    // f = 0.4 + 0.5 s + 9 s^2 on [0, 0.3]: the centre sample (0.6775) below
    // 1, f(b) = 1.36 above it, the lower level out of reach: the crossing lies
    // in [m, b].
    const MirroredQuadratic f{0.4, 0.5, 9.};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored), Departure::interior, 0.3),
                      mirrored ? -1 : +1,
                      first_root(-0.6, 0.5, 9.));
  }

  // -- Departure from a level.

  TEST(SearchRules, LeavingALevelMonotonicallyReachesTheOtherOne)
  {
    // From 0 up, f = 2 s: the departure root s = 0 is not a crossing; 1 is
    // reached at 0.5. Mirrored: from 1 down.
    const MirroredQuadratic f{0., 2., 0.};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored),
                             mirror(Departure::from_lower_level, mirrored),
                             1.),
                      mirrored ? -1 : +1,
                      0.5);
  }

  TEST(SearchRules, LeavingALevelAndComingBackToIt)
  {
    // From 1 down, f = 1 - 3 s + 5 s^2 (convex) comes back to 1 at s = 0.6
    // without reaching 0; mirrored: from 0 up, concave, back to 0.
    const MirroredQuadratic f{1., -3., 5.};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored),
                             mirror(Departure::from_upper_level, mirrored),
                             1.),
                      mirrored ? -1 : +1,
                      0.6);
  }

  TEST(SearchRules, LeavingALevelAndCrossingTheOtherBeforeComingBack)
  {
    // From 1 down, f = 1 - 8 s + 10 s^2 reaches 0 at 0.155 before it could
    // come back to 1.
    const MirroredQuadratic f{1., -8., 10.};
    for (const bool mirrored : {false, true})
      expect_crossing(search(f.flight(mirrored),
                             mirror(Departure::from_upper_level, mirrored),
                             1.),
                      mirrored ? +1 : -1,
                      first_root(1., -8., 10.));
  }

  // -- The sitting band: a flight within the round-off of its departure
  // level is still on it; a return beyond the band is a crossing.

  TEST(SearchRules, AReturnDeeperThanTheBandIsACrossing)
  {
    // From 1 down with f = 1 - 1e-3 s + s^2 and the round-off 1e-12 (band
    // 4e-12): the dip is 2.5e-7 deep, the return to 1 at s = 1e-3 is the
    // first crossing, inside the first window (located to the round-off over
    // the slope, 1e-12 / 1e-3).
    for (const bool mirrored : {false, true})
      {
        const PolynomialFlight flight =
          mirrored ? PolynomialFlight({0., 1e-3, -1.}, true, 1e-12) :
                     PolynomialFlight({1., -1e-3, 1.}, true, 1e-12);
        expect_crossing(search(flight,
                               mirror(Departure::from_upper_level, mirrored),
                               0.01),
                        mirrored ? -1 : +1,
                        1e-3,
                        2e-9);
      }
  }

  TEST(SearchRules, AReturnWithinTheBandIsReportedWithoutCrawling)
  {
    // From 1 down with f = 1 - 1e-7 s + s^2 and the round-off 1e-14 (band
    // 4e-14): the dip, 2.5e-15 deep, cannot be told from the level; f then
    // climbs through it. The search reports the level reached at or before
    // the exact return s = 1e-7 after a few tens of intervals, instead of
    // bisecting the band's edge at round-off (before the rule it crawled
    // there, 1e-17 per interval, and stalled). The enclosures bound no f'',
    // so that no convexity rule can decide in its place.
    for (const bool mirrored : {false, true})
      {
        const PolynomialFlight flight =
          mirrored ? PolynomialFlight({0., 1e-7, -1.}, false, 1e-14) :
                     PolynomialFlight({1., -1e-7, 1.}, false, 1e-14);
        SearchStatistics statistics;
        const Crossing   crossing =
          search(flight,
                 mirror(Departure::from_upper_level, mirrored),
                 1e-3,
                 &statistics);
        // Reached where f is on the level to within the band, never beyond
        // it (f leaves the band at s = 1.4e-7, where the crawl was).
        const double beyond = (mirrored ? -1. : 1.) *
                              (flight.value(crossing.s) - (mirrored ? 0. : 1.));
        EXPECT_EQ(crossing.direction, mirrored ? -1 : +1);
        EXPECT_GT(crossing.s, 0.);
        EXPECT_LE(beyond, 4e-14);
        EXPECT_LT(statistics.n_enclosures, 1000u);
      }
  }

  TEST(SearchRules, AFlightHeadingBackThroughItsDepartureLevelCrossesItAtOnce)
  {
    // Said to leave 1 downwards, the flight f = 1 + 1e-3 s moves up through
    // it from s = 0 (the jump's slope and the flight's disagree in sign at
    // round-off): the level is reached at s = 0, not where f leaves the band
    // (4e-9 later).
    for (const bool mirrored : {false, true})
      {
        const PolynomialFlight flight =
          mirrored ? PolynomialFlight({0., -1e-3}, false, 1e-12) :
                     PolynomialFlight({1., 1e-3}, false, 1e-12);
        const Crossing crossing =
          search(flight, mirror(Departure::from_upper_level, mirrored), 1.);
        EXPECT_EQ(crossing.direction, mirrored ? -1 : +1);
        EXPECT_EQ(crossing.s, 0.);
      }
  }

  TEST(SearchRules, ATangentialDepartureIsNotACrossing)
  {
    // Leaving 0 with zero slope, f = s^2: the departure root at s = 0 is not
    // returned however the intervals near it are decided; 1 is reached at 1.
    for (const bool mirrored : {false, true})
      {
        const PolynomialFlight flight =
          mirrored ? PolynomialFlight({1., 0., -1.}, true) :
                     PolynomialFlight({0., 0., 1.}, true);
        expect_crossing(search(flight,
                               mirror(Departure::from_lower_level, mirrored),
                               2.),
                        mirrored ? -1 : +1,
                        1.);
      }
  }

  TEST(SearchRules, SittingOnTheLevelWithinTheBandIsNoCrossing)
  {
    // From 1 down so slowly that f stays within the band (round-off 1e-12)
    // for s < 4e-3, then down to 0 at 1: the lower level at s = 1, nothing
    // before.
    for (const bool mirrored : {false, true})
      {
        const PolynomialFlight flight =
          mirrored ? PolynomialFlight({0., 1e-9, 1. - 1e-9}, true, 1e-12) :
                     PolynomialFlight({1., -1e-9, -(1. - 1e-9)}, true, 1e-12);
        expect_crossing(search(flight,
                               mirror(Departure::from_upper_level, mirrored),
                               2.),
                        mirrored ? +1 : -1,
                        1.,
                        1e-9);
      }
  }

  TEST(SearchRules, ARunStartingOnALevelAndLeavingTheTerraceCrossesItAtOnce)
  {
    // A run whose initial V lies on a level to round-off (a body resting at a
    // height that makes m g z a multiple of h) starts interior, on the level:
    // f = 1e-13 - s leaves the terrace [0, 1] downwards through 0 at once.
    // The crossing is at s = 0 or at its root 1e-13, found in a few
    // intervals, not by crawling along the band one resolution at a time
    // (which reported it late, at 4e-12).
    for (const bool mirrored : {false, true})
      {
        const PolynomialFlight flight =
          mirrored ? PolynomialFlight({1. - 1e-13, 1.}, false, 1e-12) :
                     PolynomialFlight({1e-13, -1.}, false, 1e-12);
        SearchStatistics statistics;
        const Crossing   crossing =
          search(flight, Departure::interior, 1., &statistics);
        expect_crossing(crossing, mirrored ? +1 : -1, 1e-13, 1e-13);
        EXPECT_LT(statistics.n_enclosures, 100u);
      }
  }

  TEST(SearchRules, ARunStartingOnALevelAndEnteringTheTerraceReachesTheOther)
  {
    // The same start moving into the terrace, f = 1e-13 + s: no crossing at
    // the start; the upper level at s = 1 - 1e-13.
    for (const bool mirrored : {false, true})
      {
        const PolynomialFlight flight =
          mirrored ? PolynomialFlight({1. - 1e-13, -1.}, false, 1e-12) :
                     PolynomialFlight({1e-13, 1.}, false, 1e-12);
        expect_crossing(search(flight, Departure::interior, 2.),
                        mirrored ? -1 : +1,
                        1. - 1e-13,
                        1e-9);
      }
  }

  // -- The prefix: the rules for the departure level hold only from s = 0 on,
  // while f has not left the level's band.

  TEST(SearchRules, ATouchOfTheDepartureLevelLaterInTheFlightIsACrossing)
  {
    // From 0 up, f = 8 s (s - 0.3)^2 peaks at 0.032, touches 0 again at s =
    // 0.3 (tangentially) and then climbs through 1: the touch is the first
    // crossing (reported early by at most the resolution of a tangential
    // touch).
    const double     k = 8.;
    PolynomialFlight flight({0., k * 0.09, -k * 0.6, k}, true);
    const Crossing   crossing = search(flight, Departure::from_lower_level, 1.);
    EXPECT_EQ(crossing.direction, -1);
    EXPECT_LE(crossing.s, 0.3);
    EXPECT_GT(crossing.s, 0.3 - 1e-6);
  }
} // namespace
