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
  Material::small_strain_lambda() const
  {
    return volumetric_second_derivative(1.) - quadratic_modulus();
  }



  double
  Material::small_strain_mu() const
  {
    return quadratic_modulus();
  }



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

  Interval
  Material::volumetric_second_derivative_range(const Interval &) const
  {
    return {-std::numeric_limits<double>::infinity(),
            std::numeric_limits<double>::infinity()};
  }

  double
  Material::volumetric_second_derivative(const double J) const
  {
    const double d = 1e-5 * J;
    return (volumetric_derivative(J + d) - volumetric_derivative(J - d)) /
           (2. * d);
  }

  dealii::Tensor<4, 3>
  Material::first_elasticity_tensor(const dealii::Tensor<2, 3> &F) const
  {
    const double               J     = dealii::determinant(F);
    const dealii::Tensor<2, 3> F_inv = dealii::invert(F);
    const double               df    = volumetric_derivative(J);
    const double               a     = volumetric_second_derivative(J) * J * J +
                     df * J; // coefficient of F^-T (x) F^-T
    const double         b = df * J;
    const double         c = quadratic_modulus();
    dealii::Tensor<4, 3> A;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int I = 0; I < 3; ++I)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            A[i][I][k][L] = (i == k && I == L ? c : 0.) +
                            a * F_inv[I][i] * F_inv[L][k] -
                            b * F_inv[L][i] * F_inv[I][k];
    return A;
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

  namespace
  {
    /** The range of x^2 for x in [lo, hi]. */
    Interval
    square(const double lo, const double hi)
    {
      return (lo <= 0. && hi >= 0.) ? Interval{0., std::max(lo * lo, hi * hi)} :
                                      Interval::hull(lo * lo, hi * hi);
    }
  } // namespace

  Interval
  Material::enclose_volumetric_curvature_sum(const double     *J_lo,
                                             const double     *J_hi,
                                             const double     *dJ_lo,
                                             const double     *dJ_hi,
                                             const double     *d2J_lo,
                                             const double     *d2J_hi,
                                             const double     *w,
                                             const std::size_t n,
                                             double &slope_magnitude) const
  {
    Interval sum     = Interval::point(0.);
    slope_magnitude  = 0.;
    const double inf = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k)
      {
        const Interval J{J_lo[k], J_hi[k]};
        const Interval f2 = volumetric_second_derivative_range(J);
        const Interval f1 = volumetric_derivative_range(J);
        if (!std::isfinite(f2.lower) || !std::isfinite(f2.upper) ||
            !std::isfinite(f1.lower) || !std::isfinite(f1.upper))
          return {-inf, inf};
        sum += w[k] * (f2 * square(dJ_lo[k], dJ_hi[k]) +
                       f1 * Interval{d2J_lo[k], d2J_hi[k]});
        slope_magnitude += w[k] *
                           std::max(std::abs(f1.lower), std::abs(f1.upper)) *
                           std::max(std::abs(dJ_lo[k]), std::abs(dJ_hi[k]));
      }
    return sum;
  }
} // namespace estep
