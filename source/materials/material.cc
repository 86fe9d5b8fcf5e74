#include <estep/materials/material.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace estep
{
  namespace
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    constexpr double unit     = std::numeric_limits<double>::epsilon();
  } // namespace

  double
  Material::reference_energy_density() const
  {
    return volumetric_energy(1.) + 1.5 * quadratic_modulus();
  }

  double
  Material::energy_density(const dealii::Tensor<2, 3> &F) const
  {
    const double J = dealii::determinant(F);
    if (!(J > 0.))
      return infinity;
    return volumetric_energy(J) + 0.5 * quadratic_modulus() * F.norm_square() -
           reference_energy_density();
  }

  dealii::Tensor<2, 3>
  Material::first_piola_stress(const dealii::Tensor<2, 3> &F) const
  {
    const double J = dealii::determinant(F);
    return (volumetric_derivative(J) * J) *
             dealii::transpose(dealii::invert(F)) +
           quadratic_modulus() * F;
  }

  double
  Material::sum_volumetric_energy(const double     *J,
                                  const double     *w,
                                  const std::size_t n) const
  {
    double sum = 0.;
    for (std::size_t i = 0; i < n; ++i)
      {
        if (!(J[i] > 0.))
          return infinity;
        sum += w[i] * volumetric_energy(J[i]);
      }
    return sum;
  }

  LineValue
  Material::sum_volumetric_energy_and_slope(const double     *J,
                                            const double     *dJ,
                                            const double     *w,
                                            const std::size_t n) const
  {
    LineValue r{0., 0.};
    for (std::size_t i = 0; i < n; ++i)
      {
        if (!(J[i] > 0.))
          return {infinity, 0.};
        r.value += w[i] * volumetric_energy(J[i]);
        r.derivative += w[i] * volumetric_derivative(J[i]) * dJ[i];
      }
    return r;
  }

  void
  Material::volumetric_derivatives(const double     *J,
                                   double           *df,
                                   const std::size_t n) const
  {
    for (std::size_t i = 0; i < n; ++i)
      df[i] = volumetric_derivative(J[i]);
  }

  LineEnclosure
  Material::enclose_volumetric_sum(const double     *J_lo,
                                   const double     *J_hi,
                                   const double     *dJ_lo,
                                   const double     *dJ_hi,
                                   const double     *w,
                                   const std::size_t n) const
  {
    LineEnclosure r{{0., 0.}, {0., 0.}};
    double        value_magnitude = 0., slope_magnitude = 0.;
    for (std::size_t i = 0; i < n; ++i)
      {
        const Interval J{J_lo[i], J_hi[i]};
        const Interval f = volumetric_energy_range(J);
        r.value.lower += w[i] * f.lower;
        r.value.upper += w[i] * f.upper;
        value_magnitude +=
          w[i] * std::max(std::isfinite(f.lower) ? std::abs(f.lower) : 0.,
                          std::isfinite(f.upper) ? std::abs(f.upper) : 0.);
        if (!(J.lower > 0.))
          {
            r.derivative    = {-infinity, infinity};
            slope_magnitude = 0.;
            continue;
          }
        const Interval d =
          volumetric_derivative_range(J) * Interval{dJ_lo[i], dJ_hi[i]};
        r.derivative.lower += w[i] * d.lower;
        r.derivative.upper += w[i] * d.upper;
        slope_magnitude +=
          w[i] * std::max(std::abs(d.lower), std::abs(d.upper));
      }
    // Summation round-off, in any order: (n - 1) u sum |terms|, with a safety
    // factor.
    const double factor = 2. * (static_cast<double>(n) + 32.) * unit;
    r.value.lower -= factor * value_magnitude;
    r.value.upper += factor * value_magnitude;
    r.derivative.lower -= factor * slope_magnitude;
    r.derivative.upper += factor * slope_magnitude;
    return r;
  }
} // namespace estep
