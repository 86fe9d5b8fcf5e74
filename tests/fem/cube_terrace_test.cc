// Energy-stepping on the seed's spinning cube never leaves its terrace: V
// sampled inside every flight stays between the flight's two levels (up to
// the flight's round-off), for the seed's three energy steps.
#include <estep/time_integration/energy_stepping.h>

#include <gtest/gtest.h>

#include "test_bodies.h"

namespace
{
  TEST(SpinningCube, FlightsStayOnTheirTerrace)
  {
    const estep::ElasticBody &body = estep_test::seed_cube();
    const estep::Vector       q0   = body.reference_configuration();
    const estep::Vector       v0 =
      body.rigid_velocity(q0, {{0., 0., 0.}}, {{0., 0., 1.}}, {{.5, .5, .5}});
    constexpr unsigned int samples = 16;
    for (const double h : {1e-5, 3e-5, 6e-5})
      {
        estep::EnergyStepping stepping(body, h);
        stepping.initialize(0., q0, v0);
        const double end_time = 3.;
        double       worst    = 0.; // largest excursion beyond a level, / h
        while (stepping.time() < end_time)
          {
            const double t0 = stepping.time();
            stepping.step(end_time);
            const double t1 = stepping.time();
            for (unsigned int k = 1; k < samples; ++k)
              {
                const auto x =
                  stepping.dense_output(t0 + k * (t1 - t0) / samples);
                const double below =
                  x.terraced_potential_energy - x.potential_energy;
                const double above =
                  x.potential_energy - (x.terraced_potential_energy + h);
                worst = std::max({worst, below / h, above / h});
              }
          }
        std::cout << "h = " << h << ": " << stepping.n_steps()
                  << " steps, mean step " << end_time / stepping.n_steps()
                  << ", largest excursion beyond a level " << worst << " h\n";
        EXPECT_LT(worst, 1e-8);
      }
  }
} // namespace
