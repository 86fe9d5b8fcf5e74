// The sampled crossing search (the reference text's way, kept as a comparison):
// it locates ordinary crossings like the certified search, steps over a thin
// bump between two samples (which the certified search finds), does not take
// its departure level for a crossing, and its audit in EnergyStepping counts
// what it stepped over on a real system.
#include <estep/time_integration/energy_stepping.h>
#include <estep/time_integration/sampled_crossing_search.h>

#include <gtest/gtest.h>

#include "argon.h"
#include "test_flights.h"

#include <cmath>

namespace
{
  using namespace estep;
  using estep::testing::BumpFlight;
  using estep::testing::PolynomialFlight;

  const SamplingSettings eight_samples{8, 60};

  TEST(SampledCrossingSearch, LocatesAnOrdinaryCrossingOnItsNearSide)
  {
    // f(s) = 0.5 + s reaches the upper level 1 at s = 0.5.
    const PolynomialFlight flight({0.5, 1.});
    SearchStatistics       statistics;
    const Crossing         crossing =
      find_first_crossing_by_sampling(flight,
                                      {0., 1., Departure::interior, 2., 0.1},
                                      eight_samples,
                                      statistics);
    EXPECT_EQ(crossing.direction, +1);
    EXPECT_LE(crossing.s, 0.5);
    EXPECT_NEAR(crossing.s, 0.5, 1e-15);
    EXPECT_GT(statistics.n_locate_evaluations, 40u);
  }

  TEST(SampledCrossingSearch, StepsOverAThinBumpThatTheCertifiedSearchFinds)
  {
    // Above the upper level 1 by 1e-9 over about 1e-8 around s = 0.3412: the
    // samples of the windows (0, 0.1], (0.1, 0.3], (0.3, 0.7] (0.325, 0.35,
    // ...) miss it and the sampled search sees no crossing before the horizon.
    const BumpFlight    flight(0.5, 0.5 + 1e-9, 0.3412, 1e-4);
    const CrossingQuery query{0., 1., Departure::interior, 1., 0.1};
    SearchStatistics    statistics;
    const Crossing      sampled =
      find_first_crossing_by_sampling(flight, query, eight_samples, statistics);
    const Crossing certified = find_first_crossing(flight, query, statistics);
    EXPECT_EQ(sampled.direction, 0);
    EXPECT_EQ(sampled.s, 1.);
    EXPECT_EQ(certified.direction, +1);
    EXPECT_NEAR(certified.s, 0.3412, 1e-4);

    // A wide bump is found by both, at the same place.
    const BumpFlight wide(0.5, 0.6, 0.35, 0.1);
    const Crossing   sampled_wide =
      find_first_crossing_by_sampling(wide, query, eight_samples, statistics);
    const Crossing certified_wide =
      find_first_crossing(wide, query, statistics);
    EXPECT_EQ(sampled_wide.direction, +1);
    EXPECT_NEAR(sampled_wide.s, certified_wide.s, 1e-13);
  }

  TEST(SampledCrossingSearch, DoesNotTakeItsDepartureLevelForACrossing)
  {
    // Departing from the upper level 1 with f at 1 + 2 eps (round-off above
    // it) and falling: the answer is the lower level 0 at s = 1 + 2 eps, not
    // the upper level at s = 0.
    const double above = 1. + 2. * std::numeric_limits<double>::epsilon();
    const PolynomialFlight flight({above, -1.});
    SearchStatistics       statistics;
    const Crossing         down = find_first_crossing_by_sampling(
      flight,
      {0., 1., Departure::from_upper_level, 2., 0.1},
      eight_samples,
      statistics);
    EXPECT_EQ(down.direction, -1);
    EXPECT_NEAR(down.s, 1., 1e-14);

    // After a reflection f comes back up through the departure level at s =
    // 1/3 (f = 1 - s + 3 s^2): that return is a crossing like any other.
    const PolynomialFlight back({1., -1., 3.});
    const Crossing         up = find_first_crossing_by_sampling(
      back,
      {0., 1., Departure::from_upper_level, 2., 0.1},
      eight_samples,
      statistics);
    EXPECT_EQ(up.direction, +1);
    EXPECT_NEAR(up.s, 1. / 3., 1e-14);
  }

  TEST(SampledCrossingSearch, TheAuditCountsWhatSamplingSteppedOverOnArgon)
  {
    // The argon cluster with one sample per window: the certified search finds
    // crossings the samples stepped over; the run still conserves E_h.
    const Problem  argon = estep::testing::argon_cluster();
    EnergyStepping stepping(*argon.system, 1e-3);
    stepping.use_sampled_search({1, 60}, true);
    stepping.initialize(0., argon.q0, argon.v0);
    while (stepping.time() < 200.)
      stepping.step(200.);
    std::uint64_t stepped_over = 0;
    for (const auto &[name, count] : stepping.counters())
      if (name == "crossings stepped over (audit)")
        stepped_over = count;
    EXPECT_GT(stepped_over, 0u);
    EXPECT_NEAR(stepping.terraced_energy(),
                stepping.initial_terraced_energy(),
                1e-12 * std::abs(stepping.initial_terraced_energy()));
    EXPECT_EQ(stepping.name(), "energy stepping (sampled crossings)");
  }
} // namespace
