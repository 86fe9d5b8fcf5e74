// The observed order of convergence of a sequence of runs, shared by the
// order tests.
#ifndef estep_tests_fitted_slope_h
#define estep_tests_fitted_slope_h

#include <cmath>
#include <vector>

namespace estep_test
{
  /** The least-squares slope of log(y) against log(x). */
  inline double
  fitted_slope(const std::vector<double> &x, const std::vector<double> &y)
  {
    double sx = 0., sy = 0., sxx = 0., sxy = 0.;
    for (unsigned int k = 0; k < x.size(); ++k)
      {
        const double lx = std::log(x[k]), ly = std::log(y[k]);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
      }
    const double n = x.size();
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
  }
} // namespace estep_test

#endif
