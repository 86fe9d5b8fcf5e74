// The neo-Hookean material with a quadratic volumetric function: W, P and the
// elasticity tensor against central differences, rigid invariance, the
// small-strain linearisation (that of NeoHookean), the rigorous volumetric
// ranges and the enclosures of the sums over cells against samples, the
// registration, and an elastic body of it: gradient, rigid invariance, free
// flight enclosures and an energy-stepping run that never leaves its terrace.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>

#include <estep/fem/elastic_body.h>
#include <estep/fem/meshes.h>
#include <estep/materials/material_registry.h>
#include <estep/materials/neo_hookean.h>
#include <estep/materials/quadratic_volume_neo_hookean.h>
#include <estep/time_integration/energy_stepping.h>

#include <gtest/gtest.h>

#include "../fem/test_bodies.h"
#include "../terrace_audit.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <tuple>
#include <vector>

namespace
{
  using estep::Interval;
  using estep::QuadraticVolumeNeoHookean;

  constexpr double                lambda0 = 0.0100, mu0 = 0.0066;
  const QuadraticVolumeNeoHookean material(lambda0, mu0);
  const estep::NeoHookean         neo_hookean(lambda0, mu0);

  constexpr double infinity = std::numeric_limits<double>::infinity();

  dealii::Tensor<2, 3>
  identity()
  {
    dealii::Tensor<2, 3> I;
    for (unsigned int d = 0; d < 3; ++d)
      I[d][d] = 1.;
    return I;
  }

  /** @p scale (I + a random matrix with entries in [-amplitude, amplitude]). */
  dealii::Tensor<2, 3>
  random_F(std::mt19937 &rng, const double amplitude, const double scale = 1.)
  {
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    dealii::Tensor<2, 3>                   F;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        F[i][j] = scale * ((i == j ? 1. : 0.) + u(rng));
    return F;
  }

  /** The rotation by @p angle about the axis @p axis (any length). */
  dealii::Tensor<2, 3>
  rotation(const std::array<double, 3> &axis, const double angle)
  {
    const double norm =
      std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const double n[3] = {axis[0] / norm, axis[1] / norm, axis[2] / norm};
    const double c = std::cos(angle), s = std::sin(angle);
    dealii::Tensor<2, 3> R;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        R[i][j] = (i == j ? c : 0.) + (1. - c) * n[i] * n[j];
    R[0][1] -= s * n[2];
    R[0][2] += s * n[1];
    R[1][0] += s * n[2];
    R[1][2] -= s * n[0];
    R[2][0] -= s * n[1];
    R[2][1] += s * n[0];
    return R;
  }

  // Extended-precision references of f, f', f'' (about 1e-19 relative).
  long double
  exact_f(const long double J)
  {
    return 0.5L * lambda0 * (J - 1.L) * (J - 1.L) - mu0 * std::log(J);
  }

  long double
  exact_df(const long double J)
  {
    return lambda0 * (J - 1.L) - mu0 / J;
  }

  long double
  exact_d2f(const long double J)
  {
    return lambda0 + mu0 / (J * J);
  }

  /** lower <= x <= upper for a long double x (no rounding to double). */
  bool
  holds(const Interval &I, const long double x)
  {
    return static_cast<long double>(I.lower) <= x &&
           x <= static_cast<long double>(I.upper);
  }

  TEST(QuadraticVolumeNeoHookean, ZeroAtIdentityAndClosedForm)
  {
    EXPECT_EQ(material.name(), "neo-Hookean quadratic volume");
    EXPECT_EQ(material.quadratic_modulus(), mu0);
    EXPECT_EQ(material.lambda(), lambda0);
    EXPECT_EQ(material.mu(), mu0);
    const dealii::Tensor<2, 3> I = identity();
    EXPECT_EQ(material.volumetric_energy(1.), 0.);
    EXPECT_EQ(material.energy_density(I), 0.);
    EXPECT_LT(material.first_piola_stress(I).norm(), 1e-18);
    EXPECT_NEAR(material.reference_energy_density(), 1.5 * mu0, 1e-18);
    // The minimiser of f: f'(J*) = 0.
    const double J_star = material.energy_minimiser();
    EXPECT_NEAR(J_star, 0.5 * (1. + std::sqrt(1. + 4. * mu0 / lambda0)), 1e-15);
    EXPECT_LT(std::abs(material.volumetric_derivative(J_star)), 1e-17);
    EXPECT_TRUE(std::isinf(
      QuadraticVolumeNeoHookean(0., mu0).energy_minimiser())); // lambda0 = 0

    std::mt19937 rng(1);
    for (unsigned int k = 0; k < 20; ++k)
      {
        const auto   F = random_F(rng, 0.3);
        const double J = dealii::determinant(F);
        const double W = 0.5 * lambda0 * (J - 1.) * (J - 1.) -
                         mu0 * std::log(J) + 0.5 * mu0 * (F.norm_square() - 3.);
        EXPECT_NEAR(material.energy_density(F), W, 1e-15);
        // P = mu (F - F^-T) + lambda (J - 1) J F^-T.
        const auto F_invT = dealii::transpose(dealii::invert(F));
        const auto P_ref = mu0 * (F - F_invT) + lambda0 * (J - 1.) * J * F_invT;
        EXPECT_LT((material.first_piola_stress(F) - P_ref).norm(), 1e-15);
      }
    dealii::Tensor<2, 3> inverted = I;
    inverted[0][0]                = -1.;
    EXPECT_TRUE(std::isinf(material.energy_density(inverted)));
    EXPECT_TRUE(std::isinf(material.volumetric_energy(0.)));
    EXPECT_TRUE(std::isinf(material.volumetric_energy(-0.5)));
  }

  TEST(QuadraticVolumeNeoHookean, StressMatchesCentralDifferencesOfEnergy)
  {
    std::mt19937 rng(2);
    const double h     = 1e-6;
    double       error = 0., scale = 0.;
    // Moderate deformations, strong compression and strong expansion.
    for (const double s : {1., 0.6, 1.5})
      for (unsigned int k = 0; k < 10; ++k)
        {
          const auto F = random_F(rng, 0.3, s);
          ASSERT_GT(dealii::determinant(F), 0.);
          const auto P = material.first_piola_stress(F);
          scale        = std::max(scale, P.norm());
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              {
                auto Fp = F, Fm = F;
                Fp[i][j] += h;
                Fm[i][j] -= h;
                const double fd =
                  (material.energy_density(Fp) - material.energy_density(Fm)) /
                  (2. * h);
                error = std::max(error, std::abs(P[i][j] - fd));
              }
        }
    std::cout << "P against central differences of W: max error " << error
              << " (largest |P| " << scale << ")\n";
    EXPECT_LT(error, 1e-9 * scale);
  }

  TEST(QuadraticVolumeNeoHookean, ElasticityTensorMatchesDifferencesOfStress)
  {
    std::mt19937 rng(3);
    const double delta = 1e-6;
    double       error = 0., scale = 0., asymmetry = 0.;
    for (const double s : {1., 0.6, 1.5})
      for (unsigned int n = 0; n < 5; ++n)
        {
          const auto F = random_F(rng, 0.3, s);
          ASSERT_GT(dealii::determinant(F), 0.);
          const dealii::Tensor<4, 3> A = material.first_elasticity_tensor(F);
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int L = 0; L < 3; ++L)
              {
                dealii::Tensor<2, 3> Fp = F, Fm = F;
                Fp[k][L] += delta;
                Fm[k][L] -= delta;
                const dealii::Tensor<2, 3> dP =
                  (material.first_piola_stress(Fp) -
                   material.first_piola_stress(Fm)) /
                  (2. * delta);
                for (unsigned int i = 0; i < 3; ++i)
                  for (unsigned int I = 0; I < 3; ++I)
                    {
                      error =
                        std::max(error, std::abs(dP[i][I] - A[i][I][k][L]));
                      scale = std::max(scale, std::abs(A[i][I][k][L]));
                      asymmetry =
                        std::max(asymmetry,
                                 std::abs(A[i][I][k][L] - A[k][L][i][I]));
                    }
              }
        }
    std::cout << "A against central differences of P: max error " << error
              << " (largest |A_iIkL| " << scale << "), asymmetry " << asymmetry
              << "\n";
    EXPECT_LT(error, 1e-8 * scale);
    EXPECT_LT(asymmetry, 1e-15 * scale);

    // The exact f'' against the default (a central difference of f').
    for (const double J : {0.05, 0.5, 0.9, 1., 1.2, 2., 10.})
      EXPECT_NEAR(material.volumetric_second_derivative(J),
                  material.estep::Material::volumetric_second_derivative(J),
                  1e-8 * material.volumetric_second_derivative(J));
  }

  TEST(QuadraticVolumeNeoHookean, InvariantUnderRotations)
  {
    std::mt19937 rng(4);
    double       energy_error = 0., stress_error = 0.;
    for (unsigned int k = 0; k < 20; ++k)
      {
        const auto F = random_F(rng, 0.3);
        const auto R = rotation({{1. + k, 2., -3.}}, 0.3 + 0.4 * k);
        const auto P = material.first_piola_stress(F);
        energy_error = std::max(energy_error,
                                std::abs(material.energy_density(R * F) -
                                         material.energy_density(F)));
        stress_error =
          std::max(stress_error,
                   (material.first_piola_stress(R * F) - R * P).norm());
      }
    std::cout << "W(RF) - W(F): " << energy_error
              << ", P(RF) - R P(F): " << stress_error << "\n";
    EXPECT_LT(energy_error, 1e-16);
    EXPECT_LT(stress_error, 1e-16);
  }

  // At F = I both materials have f'(1) = -mu0 and f''(1) = lambda0 + mu0: the
  // same elasticity tensor, that of isotropic linear elasticity with the Lame
  // constants lambda0, mu0. They part at third order (f'''(1) = -2 mu0 here,
  // -3 lambda0 - 2 mu0 for NeoHookean).
  TEST(QuadraticVolumeNeoHookean, LinearisationEqualsNeoHookeans)
  {
    EXPECT_EQ(material.volumetric_derivative(1.),
              neo_hookean.volumetric_derivative(1.));
    EXPECT_EQ(material.volumetric_second_derivative(1.),
              neo_hookean.volumetric_second_derivative(1.));
    EXPECT_EQ(material.quadratic_modulus(), neo_hookean.quadratic_modulus());

    const dealii::Tensor<2, 3> I     = identity();
    const dealii::Tensor<4, 3> A     = material.first_elasticity_tensor(I),
                               A_neo = neo_hookean.first_elasticity_tensor(I);
    double difference = 0., from_lame = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int J = 0; J < 3; ++J)
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            {
              const double linear =
                lambda0 * (i == J) * (k == L) +
                mu0 * ((i == k) * (J == L) + (i == L) * (J == k));
              difference =
                std::max(difference,
                         std::abs(A[i][J][k][L] - A_neo[i][J][k][L]));
              from_lame = std::max(from_lame, std::abs(A[i][J][k][L] - linear));
            }
    std::cout << "A(I): difference to neo-Hookean " << difference
              << ", to the Lame tensor " << from_lame << "\n";
    EXPECT_LT(difference, 1e-18);
    EXPECT_LT(from_lame, 1e-18);

    // Small strains F = I + eps H (tr H != 0): W agrees to O(eps^3) and P to
    // O(eps^2), both with the leading term of the linear theory.
    std::mt19937 rng(5);
    // H = 0.5 I + a random matrix: the cubic term, lambda0/2 (tr H)^3 eps^3,
    // dominates the next one already at eps = 1e-2.
    const dealii::Tensor<2, 3> H = random_F(rng, 0.3) - 0.5 * I;
    std::vector<double>        energy_gap, stress_gap;
    for (const double eps : {1e-1, 1e-2, 1e-3})
      {
        const dealii::Tensor<2, 3> F = I + eps * H;
        const double               W = material.energy_density(F),
                     W_neo           = neo_hookean.energy_density(F);
        // Linear elasticity: W = mu e:e + lambda/2 (tr e)^2, e = sym(eps H).
        const dealii::Tensor<2, 3> e = 0.5 * eps * (H + dealii::transpose(H));
        const double W_linear        = mu0 * dealii::scalar_product(e, e) +
                                0.5 * lambda0 * trace(e) * trace(e);
        EXPECT_NEAR(W / W_linear, 1., 20. * eps);
        energy_gap.push_back(std::abs(W - W_neo));
        stress_gap.push_back(
          (material.first_piola_stress(F) - neo_hookean.first_piola_stress(F))
            .norm());
      }
    const double energy_order = std::log10(energy_gap[1] / energy_gap[2]),
                 stress_order = std::log10(stress_gap[1] / stress_gap[2]);
    std::cout << "small strain: |W - W_neo| " << energy_gap[0] << ", "
              << energy_gap[1] << ", " << energy_gap[2] << " (order "
              << energy_order << "), |P - P_neo| " << stress_gap[0] << ", "
              << stress_gap[1] << ", " << stress_gap[2] << " (order "
              << stress_order << ")\n";
    EXPECT_NEAR(energy_order, 3., 0.05);
    EXPECT_NEAR(stress_order, 2., 0.05);
  }

  /** The check of one interval of J: the ranges hold f, f', f'' as the point
   * functions compute them and as they are (extended precision), at the ends
   * and at samples inside (evenly spaced, and log-spaced). */
  void
  check_ranges(const double lo, const double hi)
  {
    const Interval      J{lo, hi};
    const Interval      f   = material.volumetric_energy_range(J);
    const Interval      df  = material.volumetric_derivative_range(J);
    const Interval      d2f = material.volumetric_second_derivative_range(J);
    std::vector<double> samples = {lo, hi};
    for (unsigned int m = 1; m < 64; ++m)
      samples.push_back(lo + (hi - lo) * m / 64.);
    if (lo > 0.)
      for (unsigned int m = 1; m < 64; ++m)
        samples.push_back(lo * std::pow(hi / lo, m / 64.));
    samples.push_back(std::nextafter(lo, hi));
    samples.push_back(std::nextafter(hi, lo));
    for (double x : samples)
      {
        x = std::clamp(x, lo, hi);
        EXPECT_TRUE(f.contains(material.volumetric_energy(x)))
          << "f(" << x << ") = " << material.volumetric_energy(x) << " not in ["
          << f.lower << ", " << f.upper << "] for J in [" << lo << ", " << hi
          << "]";
        EXPECT_TRUE(holds(f, exact_f(x)))
          << "J in [" << lo << ", " << hi << "], x = " << x;
        EXPECT_TRUE(df.contains(material.volumetric_derivative(x)))
          << "f'(" << x << ") = " << material.volumetric_derivative(x)
          << " not in [" << df.lower << ", " << df.upper << "] for J in [" << lo
          << ", " << hi << "]";
        EXPECT_TRUE(holds(df, exact_df(x)));
        EXPECT_TRUE(d2f.contains(material.volumetric_second_derivative(x)))
          << "f''(" << x << ") for J in [" << lo << ", " << hi << "]";
        EXPECT_TRUE(holds(d2f, exact_d2f(x)));
      }
  }

  TEST(QuadraticVolumeNeoHookean, VolumetricRangesContainSamples)
  {
    std::mt19937                           rng(6);
    std::uniform_real_distribution<double> u(0., 1.);
    const double                           J_star = material.energy_minimiser();
    // Ends log-uniform in [1e-12, 1e6] (J close to 0 and large J), uniform
    // near 1 and near J*; wide, narrow and point intervals.
    for (unsigned int k = 0; k < 600; ++k)
      {
        double a, b;
        switch (k % 3)
          {
            case 0:
              a = std::pow(10., -12. + 18. * u(rng));
              b = std::pow(10., -12. + 18. * u(rng));
              break;
            case 1:
              a = 1. + 0.2 * (u(rng) - 0.5);
              b = 1. + 0.2 * (u(rng) - 0.5);
              break;
            default:
              a = J_star * (1. + 0.1 * (u(rng) - 0.5));
              b = J_star * (1. + 0.1 * (u(rng) - 0.5));
          }
        if (k % 5 == 1)
          b = a * (1. + 1e-9); // narrow
        if (k % 5 == 2)
          b = a; // a point
        if (a > b)
          std::swap(a, b);
        check_ranges(a, b);
      }
    for (const auto &[a, b] : {std::pair{1e-300, 1e-299},
                               std::pair{1e-300, 1e300},
                               std::pair{1e-8, 1.},
                               std::pair{1., 1.},
                               std::pair{1e5, 1e8},
                               std::pair{J_star, J_star},
                               std::pair{0.999 * J_star, 1.001 * J_star}})
      check_ranges(a, b);

    // Point intervals are tight: a few ulps of the magnitudes.
    double widest = 0.;
    for (const double x : {1e-10, 0.01, 0.5, 0.99, 1.01, 2., J_star, 1e4})
      {
        const Interval f  = material.volumetric_energy_range({x, x});
        const Interval df = material.volumetric_derivative_range({x, x});
        const double   magnitude =
          0.5 * lambda0 * (x - 1.) * (x - 1.) + mu0 * std::abs(std::log(x));
        widest =
          std::max({widest,
                    f.width() / magnitude,
                    df.width() / (lambda0 * std::abs(x - 1.) + mu0 / x)});
      }
    std::cout << "point intervals: widths at most " << widest
              << " of the magnitudes\n";
    EXPECT_LT(widest, 1e-13);

    // An interval around the minimiser holds the minimum, tightly: its
    // margin is a few ulps of the magnitude of f at the ends.
    const long double f_min = exact_f(J_star);
    for (const auto &[a, b] : {std::pair{0.5, 2.},
                               std::pair{0.9 * J_star, 1.1 * J_star},
                               std::pair{1e-3, 1e3}})
      {
        const Interval f         = material.volumetric_energy_range({a, b});
        const auto     magnitude = [](const double J) {
          return 0.5 * lambda0 * (J - 1.) * (J - 1.) +
                 mu0 * std::abs(std::log(J));
        };
        const double end_magnitude = std::max(magnitude(a), magnitude(b));
        EXPECT_LE(f.lower, f_min);
        EXPECT_GT(f.lower, f_min - 1e-14 * end_magnitude);
      }
    // Without an interior minimum (lambda0 = 0: f = -mu0 log J decreases).
    const QuadraticVolumeNeoHookean shear_only(0., mu0);
    const Interval g = shear_only.volumetric_energy_range({0.5, 2.});
    EXPECT_LE(g.lower, shear_only.volumetric_energy(2.));
    EXPECT_GT(g.lower, -mu0 * std::log(2.) * (1. + 1e-14));
    EXPECT_GE(g.upper, shear_only.volumetric_energy(0.5));

    // Intervals that reach J <= 0: f is unbounded above, f' and f'' unknown;
    // the lower bound of f still holds the values down to J -> 0.
    for (const double b : {1e-3, 0.5, 1., J_star, 10.})
      for (const double a : {-1., 0.})
        {
          const Interval f = material.volumetric_energy_range({a, b});
          EXPECT_EQ(f.upper, infinity);
          for (double x = b; x > 1e-300; x *= 0.01)
            {
              EXPECT_LE(f.lower, material.volumetric_energy(x)) << x;
              EXPECT_TRUE(holds(f, exact_f(x)));
            }
          EXPECT_EQ(material.volumetric_derivative_range({a, b}).lower,
                    -infinity);
          EXPECT_EQ(material.volumetric_second_derivative_range({a, b}).upper,
                    infinity);
        }
    const Interval inverted = material.volumetric_energy_range({-2., -1.});
    EXPECT_EQ(inverted.lower, infinity);

    // f overflows beyond J = 1e153: the lower bound is then one below every
    // value of f, finite.
    for (const auto &[a, b] :
         {std::pair{1e200, 1e300}, std::pair{0.5, 1e300}, std::pair{0., 1e300}})
      {
        const Interval f = material.volumetric_energy_range({a, b});
        EXPECT_TRUE(std::isfinite(f.lower));
        EXPECT_LE(f.lower, f_min);
        EXPECT_GT(f.lower, f_min - 1e-14);
        EXPECT_EQ(f.upper, infinity);
        if (a > 0.)
          check_ranges(a, b);
      }
  }

  TEST(QuadraticVolumeNeoHookean, BatchKernelsMatchScalarPath)
  {
    std::mt19937                           rng(7);
    std::uniform_real_distribution<double> u(0.2, 2.5);
    const std::size_t                      n = 1001;
    std::vector<double>                    J(n), dJ(n), w(n), df(n);
    for (std::size_t i = 0; i < n; ++i)
      {
        J[i]  = u(rng);
        dJ[i] = u(rng) - 1.;
        w[i]  = 0.1 * u(rng);
      }
    // The same loops as the defaults over the scalar functions: bit for bit.
    EXPECT_EQ(material.sum_volumetric_energy(J.data(), w.data(), n),
              material.estep::Material::sum_volumetric_energy(J.data(),
                                                              w.data(),
                                                              n));
    const auto vs = material.sum_volumetric_energy_and_slope(J.data(),
                                                             dJ.data(),
                                                             w.data(),
                                                             n);
    const auto vs_default =
      material.estep::Material::sum_volumetric_energy_and_slope(J.data(),
                                                                dJ.data(),
                                                                w.data(),
                                                                n);
    EXPECT_EQ(vs.value, vs_default.value);
    EXPECT_EQ(vs.derivative, vs_default.derivative);
    material.volumetric_derivatives(J.data(), df.data(), n);
    for (std::size_t i = 0; i < n; ++i)
      EXPECT_EQ(df[i], material.volumetric_derivative(J[i]));

    // Inadmissible entries.
    J[7] = 0.;
    EXPECT_TRUE(
      std::isinf(material.sum_volumetric_energy(J.data(), w.data(), n)));
    J[7] = -0.1;
    EXPECT_TRUE(std::isinf(
      material.sum_volumetric_energy_and_slope(J.data(), dJ.data(), w.data(), n)
        .value));
  }

  // The enclosures of the sums over cells (Material's defaults over the
  // ranges) hold sampled sums: as sum_volumetric_energy_and_slope() computes
  // them, and for the curvature w (f''(J) J'^2 + f'(J) J'').
  TEST(QuadraticVolumeNeoHookean, EnclosuresOfCellSumsHoldSamples)
  {
    std::mt19937                           rng(8);
    std::uniform_real_distribution<double> u(0., 1.);
    double                                 worst_value_width = 0.;
    for (const double centre_spread : {1e-3, 0.05, 0.8})
      for (const double relative_width : {0., 1e-6, 1e-2})
        for (const std::size_t n :
             {std::size_t(1), std::size_t(7), std::size_t(258)})
          {
            std::vector<double> J_lo(n), J_hi(n), d_lo(n), d_hi(n), dd_lo(n),
              dd_hi(n), w(n);
            for (std::size_t i = 0; i < n; ++i)
              {
                // Centres in [1 - spread, 1 + spread] (spread 0.8: J down to
                // 0.2) and, for some cells, far out (J up to 50).
                double centre = 1. + centre_spread * (2. * u(rng) - 1.);
                if (i % 5 == 3)
                  centre = 0.5 + 50. * u(rng);
                const double width = relative_width * centre * u(rng);
                J_lo[i]            = centre - width;
                J_hi[i]            = centre + width;
                d_lo[i]            = 2. * u(rng) - 1.5;
                d_hi[i]            = d_lo[i] + u(rng);
                dd_lo[i]           = 2. * u(rng) - 1.;
                dd_hi[i]           = dd_lo[i] + 0.1 * u(rng);
                w[i]               = 0.01 * u(rng);
              }
            const estep::LineEnclosure e = material.enclose_volumetric_sum(
              J_lo.data(), J_hi.data(), d_lo.data(), d_hi.data(), w.data(), n);
            double         slope = 0.;
            const Interval c =
              material.enclose_volumetric_curvature_sum(J_lo.data(),
                                                        J_hi.data(),
                                                        d_lo.data(),
                                                        d_hi.data(),
                                                        dd_lo.data(),
                                                        dd_hi.data(),
                                                        w.data(),
                                                        n,
                                                        slope);
            ASSERT_TRUE(std::isfinite(c.lower) && std::isfinite(c.upper));
            double magnitude = 0.;
            for (std::size_t i = 0; i < n; ++i)
              magnitude += w[i] * std::abs(material.volumetric_energy(J_lo[i]));
            if (relative_width == 0.)
              worst_value_width =
                std::max(worst_value_width, e.value.width() / magnitude);
            std::vector<double> Js(n), dJs(n);
            for (unsigned int sample = 0; sample < 100; ++sample)
              {
                double curvature = 0., slope_sum = 0.;
                for (std::size_t i = 0; i < n; ++i)
                  {
                    const double t  = sample == 0 ? 0. :
                                      sample == 1 ? 1. :
                                                    u(rng);
                    Js[i]           = J_lo[i] + t * (J_hi[i] - J_lo[i]);
                    dJs[i]          = d_lo[i] + u(rng) * (d_hi[i] - d_lo[i]);
                    const double dd = dd_lo[i] + u(rng) * (dd_hi[i] - dd_lo[i]);
                    curvature +=
                      w[i] * (material.volumetric_second_derivative(Js[i]) *
                                dJs[i] * dJs[i] +
                              material.volumetric_derivative(Js[i]) * dd);
                    slope_sum +=
                      w[i] *
                      std::abs(material.volumetric_derivative(Js[i]) * dJs[i]);
                  }
                const estep::LineValue s =
                  material.sum_volumetric_energy_and_slope(Js.data(),
                                                           dJs.data(),
                                                           w.data(),
                                                           n);
                EXPECT_TRUE(e.value.contains(s.value))
                  << "spread " << centre_spread << ", width " << relative_width
                  << ", n " << n;
                EXPECT_TRUE(e.derivative.contains(s.derivative))
                  << "spread " << centre_spread << ", width " << relative_width
                  << ", n " << n;
                EXPECT_TRUE(c.contains(curvature))
                  << "spread " << centre_spread << ", width " << relative_width
                  << ", n " << n;
                EXPECT_LE(slope_sum, slope * (1. + 1e-12));
              }
          }
    std::cout << "enclosures of sums over point boxes: widths at most "
              << worst_value_width << " of the sums of |w f|\n";
    EXPECT_LT(worst_value_width, 1e-11);

    // A box reaching J <= 0: the value is unbounded above and the slope and
    // curvature unknown.
    const double lo[2] = {0.5, -0.1}, hi[2] = {0.6, 0.2}, d[2] = {1., 1.},
                 w[2] = {1., 1.};
    const estep::LineEnclosure e =
      material.enclose_volumetric_sum(lo, hi, d, d, w, 2);
    EXPECT_EQ(e.value.upper, infinity);
    EXPECT_LE(e.value.lower,
              material.volumetric_energy(0.6) +
                material.volumetric_energy(0.2));
    EXPECT_EQ(e.derivative.lower, -infinity);
    EXPECT_EQ(e.derivative.upper, infinity);
    double         slope = 0.;
    const Interval c     = material.enclose_volumetric_curvature_sum(
      lo, hi, d, d, d, d, w, 2, slope);
    EXPECT_EQ(c.lower, -infinity);
    EXPECT_EQ(c.upper, infinity);
  }

  TEST(QuadraticVolumeNeoHookean, RejectsBadConstants)
  {
    EXPECT_THROW(QuadraticVolumeNeoHookean(0.01, 0.), std::exception);
    EXPECT_THROW(QuadraticVolumeNeoHookean(-1., 0.01), std::exception);
    EXPECT_THROW(QuadraticVolumeNeoHookean(infinity, 0.01), std::exception);
  }

  TEST(QuadraticVolumeNeoHookean, RegisteredWithItsOwnParameters)
  {
    const auto *plugin =
      estep::material_registry().find("neo-Hookean quadratic volume");
    ASSERT_NE(plugin, nullptr);
    ASSERT_NE(estep::material_registry().find("neo-Hookean"), nullptr);

    dealii::ParameterHandler prm;
    prm.enter_subsection("Material");
    estep::declare_material_parameters(prm);
    // The same defaults as neo-Hookean's.
    for (const char *entry : {"Lambda", "Mu"})
      {
        prm.enter_subsection("Neo-Hookean");
        const std::string neo_hookean_default = prm.get(entry);
        prm.leave_subsection();
        prm.enter_subsection("Neo-Hookean quadratic volume");
        EXPECT_EQ(prm.get(entry), neo_hookean_default) << entry;
        prm.leave_subsection();
      }
    prm.set("Model", "neo-Hookean quadratic volume");
    prm.enter_subsection("Neo-Hookean quadratic volume");
    prm.set("Lambda", "0.02");
    prm.leave_subsection();
    const estep::MaterialChoice choice =
      estep::parse_material_parameters(prm, "Material");
    const auto *chosen =
      dynamic_cast<const QuadraticVolumeNeoHookean *>(choice.material.get());
    ASSERT_NE(chosen, nullptr);
    EXPECT_EQ(chosen->lambda(), 0.02);
    EXPECT_EQ(chosen->mu(), 0.0066);
    EXPECT_EQ(choice.density, 0.1);

    // A bad value is reported with its entry.
    prm.enter_subsection("Neo-Hookean quadratic volume");
    prm.set("Mu", "0");
    prm.leave_subsection();
    try
      {
        estep::parse_material_parameters(prm, "Material");
        ADD_FAILURE() << "Mu = 0 accepted";
      }
    catch (const std::runtime_error &error)
      {
        EXPECT_NE(std::string(error.what())
                    .find("Material/Neo-Hookean quadratic volume/Mu"),
                  std::string::npos)
          << error.what();
      }
    prm.leave_subsection();
  }

  // ---------------------------------------------------------------------------
  // An elastic body of this material.

  /** The seed's cube mesh (n^3 hexahedra of 24 tets) of this material, rho =
   * 0.1. */
  std::shared_ptr<const estep::ElasticBody>
  cube(const unsigned int n)
  {
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, n);
    return std::make_shared<const estep::ElasticBody>(
      tria,
      std::make_shared<QuadraticVolumeNeoHookean>(lambda0, mu0),
      0.100,
      "cube");
  }

  TEST(QuadraticVolumeBody, UndeformedEnergyAndGradientVanish)
  {
    const auto          body = cube(2);
    const estep::Vector X    = body->reference_configuration();
    EXPECT_EQ(body->material().name(), "neo-Hookean quadratic volume");
    EXPECT_NEAR(body->energy(X), 0., 1e-16);
    estep::Vector g;
    body->gradient(X, g);
    EXPECT_LT(g.linfty_norm(), 1e-16);
  }

  TEST(QuadraticVolumeBody, GradientMatchesCentralDifferencesOfEnergy)
  {
    const auto          body = cube(2);
    const estep::Vector q    = estep_test::perturbed(*body, 0.03, 11);
    ASSERT_TRUE(std::isfinite(body->energy(q)));
    estep::Vector g;
    body->gradient(q, g);
    const double scale = g.linfty_norm();
    ASSERT_GT(scale, 1e-6);
    double error = 0.;
    for (unsigned int k = 0; k < body->n_dofs(); ++k)
      {
        const double  h  = 1e-6;
        estep::Vector qp = q, qm = q;
        qp[k] += h;
        qm[k] -= h;
        const double fd = (body->energy(qp) - body->energy(qm)) / (2. * h);
        error           = std::max(error, std::abs(g[k] - fd));
      }
    std::cout << "body gradient against central differences of V: max error "
              << error << " (largest |g| " << scale << ")\n";
    EXPECT_LT(error, 1e-7 * scale);
  }

  TEST(QuadraticVolumeBody, InvariantUnderRigidMotion)
  {
    const auto          body = cube(3);
    const estep::Vector q    = estep_test::perturbed(*body, 0.01, 13);
    const auto          R    = rotation({{1., 2., 3.}}, 0.7);
    const double        t[3] = {0.3, -1.2, 2.5};
    estep::Vector       moved(q.size());
    for (unsigned int i = 0; i < q.size(); i += 3)
      for (unsigned int a = 0; a < 3; ++a)
        moved[i + a] =
          R[a][0] * q[i] + R[a][1] * q[i + 1] + R[a][2] * q[i + 2] + t[a];
    const double  V = body->energy(q), V_moved = body->energy(moved);
    estep::Vector g, g_moved;
    body->gradient(q, g);
    body->gradient(moved, g_moved);
    double gradient_error = 0.;
    for (unsigned int i = 0; i < q.size(); i += 3)
      for (unsigned int a = 0; a < 3; ++a)
        gradient_error =
          std::max(gradient_error,
                   std::abs(g_moved[i + a] -
                            (R[a][0] * g[i] + R[a][1] * g[i + 1] +
                             R[a][2] * g[i + 2])));
    std::cout << "rigid motion: V " << V << ", change " << V_moved - V
              << "; gradient not equivariant by " << gradient_error
              << " (largest |g| " << g.linfty_norm() << ")\n";
    EXPECT_NEAR(V_moved, V, 1e-12 * V);
    EXPECT_LT(gradient_error, 1e-11 * g.linfty_norm());
  }

  // The free flights of the body enclose their sampled values, slopes and
  // curvatures (through the material's default enclosures of the cell sums).
  TEST(QuadraticVolumeBody, FlightEnclosuresContainSamples)
  {
    const auto body = cube(3);
    for (const double noise : {0.3, 5.})
      {
        const estep::Vector q = estep_test::perturbed(*body, 0.004, 22);
        estep::Vector       v = body->rigid_velocity(q,
                                               {{0.1, 0., 0.}},
                                               {{0., 0., 1.}},
                                               {{0.5, 0.5, 0.5}});
        v += estep_test::random_vector(body->n_dofs(), noise, 122);
        const auto   flight = body->free_flight(q, v);
        const double limit  = flight->admissible_limit();
        ASSERT_GT(limit, 0.);
        const double                           horizon = std::min(limit, 0.5);
        std::mt19937                           rng(5);
        std::uniform_real_distribution<double> u(0., horizon);
        unsigned int                           n_outside = 0, n_samples = 0;
        for (unsigned int k = 0; k < 40; ++k)
          {
            double a = u(rng), b = u(rng);
            if (a > b)
              std::swap(a, b);
            if (k % 4 == 0)
              b = a + 1e-6 * horizon; // narrow
            const auto enclosure = flight->enclose(a, b);
            for (unsigned int m = 0; m <= 20; ++m)
              {
                const double s  = a + (b - a) * m / 20.;
                const auto   lv = flight->value_and_derivative(s);
                ++n_samples;
                if (!enclosure.value.contains(lv.value) ||
                    !enclosure.value.contains(flight->value(s)) ||
                    !enclosure.derivative.contains(lv.derivative))
                  ++n_outside;
                const double delta = 1e-5 * horizon;
                if (k % 4 != 0 && s - delta > a && s + delta < b)
                  {
                    const double curvature =
                      (flight->value_and_derivative(s + delta).derivative -
                       flight->value_and_derivative(s - delta).derivative) /
                      (2. * delta);
                    const double slack =
                      1e-6 * (std::abs(enclosure.curvature.lower) +
                              std::abs(enclosure.curvature.upper));
                    EXPECT_GE(curvature, enclosure.curvature.lower - slack);
                    EXPECT_LE(curvature, enclosure.curvature.upper + slack);
                  }
              }
          }
        EXPECT_EQ(n_outside, 0u) << "of " << n_samples << ", noise " << noise;
      }
  }

  // Energy-stepping on a small spinning cube of this material (deformed at the
  // start, so that V climbs and descends): V sampled inside every flight stays
  // on the flight's terrace, and the terraced energy T + (L + c) h is
  // conserved to round-off.
  TEST(QuadraticVolumeBody, EnergySteppingStaysOnItsTerraces)
  {
    const auto body = cube(3);
    for (const auto &[h, offset, amplitude] :
         {std::tuple{1e-5, 0., 0.}, std::tuple{3e-5, 0.75, 2e-3}})
      {
        const estep::Vector   q0 = amplitude > 0. ?
                                     estep_test::perturbed(*body, amplitude, 5) :
                                     body->reference_configuration();
        const estep::Vector   v0 = body->rigid_velocity(q0,
                                                      {{0., 0., 0.}},
                                                      {{0., 0., 1.}},
                                                      {{.5, .5, .5}});
        estep::EnergyStepping stepping(*body, h, offset);
        stepping.initialize(0., q0, v0);
        const double E0       = stepping.terraced_energy();
        const double end_time = 3.;
        double       worst = -1., energy_error = 0., V_max = 0.;
        while (stepping.time() < end_time)
          {
            stepping.step(end_time);
            worst = std::max(worst, estep_test::terrace_excursion(stepping));
            energy_error =
              std::max(energy_error,
                       std::abs(stepping.terraced_energy() - E0) / E0);
            V_max = std::max(V_max, body->energy(stepping.position()));
            ASSERT_LT(worst, 1e-8) << "at t = " << stepping.time();
            ASSERT_LT(energy_error, 1e-13) << "at t = " << stepping.time();
          }
        std::cout << "h = " << h << ", offset " << offset << ", start "
                  << amplitude << ": " << stepping.n_steps()
                  << " steps, largest V " << V_max << " (" << V_max / h
                  << " h), largest excursion beyond a level " << worst
                  << " h, terraced energy error " << energy_error
                  << " relative\n";
        EXPECT_GT(stepping.n_steps(), 50u);
        EXPECT_GT(V_max, 10. * h); // the body deforms: many terraces
        EXPECT_LT(worst, 1e-8);
        EXPECT_LT(energy_error, 1e-13);
      }
  }
} // namespace
