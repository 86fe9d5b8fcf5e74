// The terrace audit shared by the energy-stepping tests: V sampled densely
// inside a flight stays between the flight's two levels.
#ifndef estep_tests_terrace_audit_h
#define estep_tests_terrace_audit_h

#include <estep/time_integration/energy_stepping.h>

#include <algorithm>

namespace estep_test
{
  /**
   * The largest excursion of V beyond the two levels of the last flight of
   * @p stepping, in units of the energy step, over @p n_samples points evenly
   * spaced strictly inside the flight (0 or negative: V stayed on its
   * terrace).
   */
  inline double
  terrace_excursion(const estep::EnergyStepping &stepping,
                    const unsigned int           n_samples = 64)
  {
    const double t0 = stepping.previous_time(), t1 = stepping.time();
    const double h     = stepping.energy_step();
    double       worst = -1.;
    for (unsigned int k = 1; k <= n_samples; ++k)
      {
        const estep::Snapshot x =
          stepping.dense_output(t0 + k * (t1 - t0) / (n_samples + 1));
        const double below = x.terraced_potential_energy - x.potential_energy;
        const double above =
          x.potential_energy - (x.terraced_potential_energy + h);
        worst = std::max({worst, below / h, above / h});
      }
    return worst;
  }
} // namespace estep_test

#endif
