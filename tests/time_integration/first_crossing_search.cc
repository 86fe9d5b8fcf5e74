// The certified first-crossing search on functions built to defeat sampling.
#include <estep/base/interruption.h>
#include <estep/time_integration/first_crossing_search.h>

#include <gtest/gtest.h>

#include "test_flights.h"

#include <iostream>
#include <random>

namespace
{
  using namespace estep;
  using estep::testing::BumpFlight;
  using estep::testing::PolynomialFlight;
  using estep::testing::UselessEnclosureFlight;

  CrossingQuery
  query(const double    lower,
        const double    upper,
        const Departure departure,
        const double    horizon,
        const double    first_window)
  {
    return {lower, upper, departure, horizon, first_window};
  }

  TEST(FirstCrossingSearch, FindsAThinBumpBetweenWouldBeSamples)
  {
    // The bump rises above the upper level 1 by 1e-9 over about 1e-8 in s,
    // around s0 = 0.35: samples at 0.3 and 0.4 (or any grid coarser than 1e-8)
    // see nothing.
    const double     s0 = 0.35, w = 1e-4, A = 0.5 + 1e-9;
    const BumpFlight flight(0.5, A, s0, w);
    SearchStatistics statistics;
    const Crossing   crossing =
      find_first_crossing(flight,
                          query(0., 1., Departure::interior, 1., 0.1),
                          statistics);
    const double exact = s0 - w * std::sqrt(std::log(A / 0.5));
    EXPECT_EQ(crossing.direction, +1);
    EXPECT_LE(crossing.s, exact);
    EXPECT_NEAR(crossing.s, exact, 1e-12);
    EXPECT_GT(statistics.n_enclosures, 0u);
  }

  TEST(FirstCrossingSearch, ReportsATangentialTouch)
  {
    // The bump reaches the level exactly at its peak and no further.
    const double     s0 = 0.35, w = 1e-4;
    const BumpFlight flight(0.5, 0.5, s0, w);
    SearchStatistics statistics;
    const Crossing   crossing =
      find_first_crossing(flight,
                          query(0., 1., Departure::interior, 1., 0.1),
                          statistics);
    EXPECT_EQ(crossing.direction, +1);
    EXPECT_LE(crossing.s, s0);
    EXPECT_GE(crossing.s, s0 - 1e-9);
  }

  TEST(FirstCrossingSearch, IgnoresANearMiss)
  {
    // The bump stops 1e-9 below the level: no crossing before the horizon.
    const BumpFlight flight(0.5, 0.5 - 1e-9, 0.35, 1e-4);
    SearchStatistics statistics;
    const Crossing   crossing =
      find_first_crossing(flight,
                          query(0., 1., Departure::interior, 1., 0.1),
                          statistics);
    EXPECT_EQ(crossing.direction, 0);
    EXPECT_EQ(crossing.s, 1.);
  }

  TEST(FirstCrossingSearch, FindsTheCrossingRightAfterAReflection)
  {
    // After a reflection on the upper level 1 the flight leaves it with the
    // small slope -1e-6 and curves back: f(s) = 1 - 1e-6 s + s^2 returns to 1
    // at s = 1e-6.
    const PolynomialFlight flight({1., -1e-6, 1.});
    SearchStatistics       statistics;
    const Crossing         crossing =
      find_first_crossing(flight,
                          query(0., 1., Departure::from_upper_level, 10., 1.),
                          statistics);
    // Near the root f - 1 = s (s - 1e-6) is computed with an absolute error of
    // about 1e-16 and has the slope 1e-6: the root is determined to about
    // 1e-10.
    EXPECT_EQ(crossing.direction, +1);
    EXPECT_NEAR(crossing.s, 1e-6, 1e-10);
  }

  TEST(FirstCrossingSearch, NeverReturnsTheDepartureRoot)
  {
    // Leaving the lower level 1 upwards, f(s) = 1 + s - s^2 peaks at 1.25 < 2
    // and comes back to 1 at s = 1: the first crossing is that return, not s =
    // 0.
    const PolynomialFlight flight({1., 1., -1.});
    SearchStatistics       statistics;
    const Crossing         crossing =
      find_first_crossing(flight,
                          query(1., 2., Departure::from_lower_level, 10., 1e-3),
                          statistics);
    EXPECT_EQ(crossing.direction, -1);
    EXPECT_NEAR(crossing.s, 1., 1e-14);
    EXPECT_LE(crossing.s, 1.);
  }

  TEST(FirstCrossingSearch, ReturnsTheFirstOfSeveralCrossings)
  {
    // f(s) = 0.5 + 10 s - 10 s^2 crosses 1 at s = 0.0528 and again at 0.947,
    // then 0 at 1.05; a first window much longer than all of that must still
    // give the first crossing.
    const PolynomialFlight flight({0.5, 10., -10.});
    SearchStatistics       statistics;
    const Crossing         crossing =
      find_first_crossing(flight,
                          query(0., 1., Departure::interior, 100., 100.),
                          statistics);
    EXPECT_EQ(crossing.direction, +1);
    EXPECT_NEAR(crossing.s, (1. - std::sqrt(0.8)) / 2., 1e-14);
  }

  TEST(FirstCrossingSearch, NeverReportsALaterCrossingThanDenseSamplingFinds)
  {
    // Random quartics starting inside the terrace [0, 1]: dense sampling may
    // only ever find the first level reached at or after the returned crossing.
    std::mt19937                           random(2026);
    std::uniform_real_distribution<double> coefficient(-30., 30.),
      start(0.05, 0.95);
    unsigned int n_crossings = 0;
    for (unsigned int trial = 0; trial < 300; ++trial)
      {
        const PolynomialFlight flight({start(random),
                                       coefficient(random),
                                       coefficient(random),
                                       coefficient(random),
                                       coefficient(random)});
        SearchStatistics       statistics;
        const Crossing         crossing =
          find_first_crossing(flight,
                              query(0., 1., Departure::interior, 1., 0.01),
                              statistics);
        const unsigned int n_samples = 100000;
        for (unsigned int i = 1; i <= n_samples; ++i)
          {
            const double s = crossing.s * i / n_samples;
            const double f = flight.value(s);
            if (i < n_samples)
              {
                ASSERT_TRUE(f > 0. && f < 1.)
                  << "a level is reached at s = " << s
                  << " before the returned crossing " << crossing.s
                  << " (trial " << trial << ")";
              }
          }
        if (crossing.direction != 0)
          {
            ++n_crossings;
            const double f = flight.value(crossing.s);
            EXPECT_NEAR(f, crossing.direction > 0 ? 1. : 0., 1e-12);
          }
      }
    EXPECT_GT(n_crossings, 100u);
  }

  TEST(FirstCrossingSearch, ConvexityRulesNeverReportALaterCrossing)
  {
    // Random quartics with a dominant quadratic term whose enclosures also
    // bound f'' (so that the search decides intervals around turning points
    // by convexity), starting
    // inside the terrace [0, 1] or on one of its levels, moving away: dense
    // sampling may only find a level reached at or after the returned
    // crossing, and the crossing is on its level.
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> coefficient(-30., 30.),
      start(0.05, 0.95), slope(1., 30.), curvature(10., 60.), small(-3., 3.);
    std::bernoulli_distribution upwards(0.5);
    unsigned int                n_crossings = 0, n_enclosures = 0;
    for (const Departure departure : {Departure::interior,
                                      Departure::from_lower_level,
                                      Departure::from_upper_level})
      for (unsigned int trial = 0; trial < 300; ++trial)
        {
          const double f0 = departure == Departure::interior ? start(random) :
                            departure == Departure::from_lower_level ? 0. :
                                                                       1.;
          const double f1 =
            departure == Departure::interior         ? coefficient(random) :
            departure == Departure::from_lower_level ? slope(random) :
                                                       -slope(random);
          // Mostly convex or mostly concave: a dominant s^2 term.
          const double f2 = (upwards(random) ? 1. : -1.) * curvature(random);
          const PolynomialFlight flight(
            {f0, f1, f2, small(random), small(random)}, true);
          SearchStatistics statistics;
          const Crossing   crossing =
            find_first_crossing(flight,
                                query(0., 1., departure, 1., 0.01),
                                statistics);
          n_enclosures += statistics.n_enclosures;
          const unsigned int n_samples = 100000;
          for (unsigned int i = 1; i < n_samples; ++i)
            {
              const double s = crossing.s * i / n_samples;
              const double f = flight.value(s);
              ASSERT_TRUE(f > 0. && f < 1.)
                << "a level is reached at s = " << s
                << " before the returned crossing " << crossing.s << " (trial "
                << trial << ", departure " << static_cast<int>(departure)
                << ")";
            }
          if (crossing.direction != 0)
            {
              ++n_crossings;
              EXPECT_NEAR(flight.value(crossing.s),
                          crossing.direction > 0 ? 1. : 0.,
                          1e-12);
            }
        }
    EXPECT_GT(n_crossings, 500u);
    std::cout << n_crossings << " crossings, " << n_enclosures
              << " enclosures\n";
  }

  TEST(FirstCrossingSearch, StopsAtOnceWhereTheRoundOffBlursTheLevels)
  {
    // A round-off band (four value tolerances) of half the terrace or more
    // cannot tell the levels 0 and 1 apart: the search says so at once.
    SearchStatistics statistics;
    EXPECT_THROW(find_first_crossing(PolynomialFlight({0.5, 1.}, false, 0.2),
                                     query(0., 1., Departure::interior, 1., 1.),
                                     statistics),
                 SearchStalled);
    EXPECT_EQ(statistics.n_enclosures, 0u);
    // Below that the same flight's crossing is found.
    const Crossing crossing =
      find_first_crossing(PolynomialFlight({0.5, 1.}, false, 0.1),
                          query(0., 1., Departure::interior, 1., 1.),
                          statistics);
    EXPECT_EQ(crossing.direction, +1);
    EXPECT_NEAR(crossing.s, 0.5, 0.1);
  }

  TEST(FirstCrossingSearch, GivesUpAfterItsCapOnIntervals)
  {
    // The search crawls from s = 0 one resolution at a time; after
    // max_intervals_examined intervals it stops with SearchStalled instead.
    // Its message blames what it met: enclosures without any bound on f''
    // (no convexity rule could apply), or else the energy step.
    for (const bool curvature_known : {false, true})
      {
        SearchStatistics             statistics;
        const UselessEnclosureFlight flight =
          curvature_known ? UselessEnclosureFlight(0., {}, {-1., 1.}) :
                            UselessEnclosureFlight(0.);
        try
          {
            find_first_crossing(
              flight,
              query(0., 1., Departure::from_lower_level, 1., 1.),
              statistics);
            ADD_FAILURE() << "the search did not give up";
          }
        catch (const SearchStalled &stalled)
          {
            const std::string message = stalled.what();
            EXPECT_EQ(message.find("bound no curvature") == std::string::npos,
                      curvature_known)
              << message;
            EXPECT_NE(message.find("try a larger Energy step"),
                      std::string::npos)
              << message;
          }
        EXPECT_EQ(statistics.max_intervals_in_one_search,
                  max_intervals_examined);
      }
  }

  TEST(FirstCrossingSearch, EndsACrawlWhenTheRunIsInterrupted)
  {
    // A signal arrives while the search crawls: it polls for it every
    // intervals_between_interruption_polls intervals and abandons the step,
    // long before its cap on intervals.
    const std::uint64_t    signal_at = 3000;
    UselessEnclosureFlight flight(0., [&](const std::uint64_t n) {
      if (n == signal_at)
        request_interruption(15);
    });
    SearchStatistics       statistics;
    try
      {
        find_first_crossing(flight,
                            query(0., 1., Departure::from_lower_level, 1., 1.),
                            statistics);
        ADD_FAILURE() << "the search ignored the interruption";
      }
    catch (const StepInterrupted &abandoned)
      {
        EXPECT_EQ(abandoned.signal, 15);
      }
    catch (const SearchStalled &)
      {
        ADD_FAILURE() << "the search crawled on to its cap";
      }
    request_interruption(0);
    EXPECT_GT(statistics.max_intervals_in_one_search, signal_at);
    EXPECT_LE(statistics.max_intervals_in_one_search,
              signal_at + intervals_between_interruption_polls);
  }
} // namespace
