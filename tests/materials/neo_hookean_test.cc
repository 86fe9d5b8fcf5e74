// The neo-Hookean material: W, P, its volumetric ranges and the batch kernels
// against the scalar path.
#include <deal.II/base/tensor.h>

#include <estep/materials/batch_log.h>
#include <estep/materials/neo_hookean.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace
{
  using estep::Interval;
  using estep::NeoHookean;

  const NeoHookean material(0.0100, 0.0066);

  dealii::Tensor<2, 3>
  random_F(std::mt19937 &rng, const double amplitude)
  {
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    dealii::Tensor<2, 3>                   F;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        F[i][j] = (i == j ? 1. : 0.) + u(rng);
    return F;
  }

  TEST(NeoHookean, ZeroAtIdentityAndClosedForm)
  {
    dealii::Tensor<2, 3> I;
    for (unsigned int d = 0; d < 3; ++d)
      I[d][d] = 1.;
    EXPECT_EQ(material.energy_density(I), 0.);
    EXPECT_NEAR(material.reference_energy_density(), 1.5 * 0.0066, 1e-18);
    std::mt19937 rng(1);
    for (unsigned int k = 0; k < 20; ++k)
      {
        const auto   F = random_F(rng, 0.3);
        const double J = dealii::determinant(F), L = std::log(J);
        const double W =
          0.005 * L * L - 0.0066 * L + 0.0033 * (F.norm_square() - 3.);
        EXPECT_NEAR(material.energy_density(F), W, 1e-15);
      }
    dealii::Tensor<2, 3> inverted = I;
    inverted[0][0]                = -1.;
    EXPECT_TRUE(std::isinf(material.energy_density(inverted)));
  }

  TEST(NeoHookean, StressIsDerivativeOfEnergy)
  {
    std::mt19937 rng(2);
    for (unsigned int k = 0; k < 10; ++k)
      {
        const auto F = random_F(rng, 0.3);
        const auto P = material.first_piola_stress(F);
        // Closed form: P = mu (F - F^-T) + lambda log J F^-T.
        const auto F_invT = dealii::transpose(dealii::invert(F));
        const auto P_ref  = 0.0066 * (F - F_invT) +
                           0.0100 * std::log(dealii::determinant(F)) * F_invT;
        EXPECT_LT((P - P_ref).norm(), 1e-15);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              const double h  = 1e-6;
              auto         Fp = F, Fm = F;
              Fp[i][j] += h;
              Fm[i][j] -= h;
              const double fd =
                (material.energy_density(Fp) - material.energy_density(Fm)) /
                (2. * h);
              EXPECT_NEAR(P[i][j], fd, 1e-9);
            }
      }
  }

  TEST(NeoHookean, VolumetricRangesContainSamples)
  {
    std::mt19937                           rng(3);
    std::uniform_real_distribution<double> u(0.05, 3.);
    for (unsigned int k = 0; k < 500; ++k)
      {
        double a = u(rng), b = u(rng);
        if (k % 5 == 0)
          b = a * (1. + 1e-9); // very narrow
        const Interval J = Interval::hull(a, b);
        const Interval f = material.volumetric_energy_range(J);
        const Interval d = material.volumetric_derivative_range(J);
        for (unsigned int m = 0; m <= 50; ++m)
          {
            const double x = J.lower + (J.upper - J.lower) * m / 50.;
            EXPECT_TRUE(f.contains(material.volumetric_energy(x)));
            EXPECT_TRUE(d.contains(material.volumetric_derivative(x)));
          }
      }
    // Across J* = exp(mu/lambda): the minimum -mu^2/(2 lambda) must be inside.
    const double   J_star = std::exp(0.66);
    const Interval f =
      material.volumetric_energy_range({0.5 * J_star, 2. * J_star});
    EXPECT_LE(f.lower, -0.0066 * 0.0066 / 0.02);
    EXPECT_GT(f.lower, -0.0066 * 0.0066 / 0.02 * (1. + 1e-12));
  }

  TEST(NeoHookean, BatchKernelsMatchScalarPath)
  {
    std::mt19937                           rng(4);
    std::uniform_real_distribution<double> u(0.2, 2.5);
    const std::size_t                      n = 1001;
    std::vector<double> J(n), dJ(n), w(n), L(n), L_ref(n), df(n);
    for (std::size_t i = 0; i < n; ++i)
      {
        J[i]  = u(rng);
        dJ[i] = u(rng) - 1.;
        w[i]  = 0.1 * u(rng);
      }
    estep::batch_log(J.data(), L.data(), n);
    estep::batch_log_scalar(J.data(), L_ref.data(), n);
    for (std::size_t i = 0; i < n; ++i)
      EXPECT_NEAR(L[i], L_ref[i], 4e-16 * (1. + std::abs(L_ref[i])));

    double value = 0., slope = 0.;
    for (std::size_t i = 0; i < n; ++i)
      {
        value += w[i] * material.volumetric_energy(J[i]);
        slope += w[i] * material.volumetric_derivative(J[i]) * dJ[i];
      }
    EXPECT_NEAR(material.sum_volumetric_energy(J.data(), w.data(), n),
                value,
                1e-14);
    const auto vs = material.sum_volumetric_energy_and_slope(J.data(),
                                                             dJ.data(),
                                                             w.data(),
                                                             n);
    EXPECT_NEAR(vs.value, value, 1e-14);
    EXPECT_NEAR(vs.derivative, slope, 1e-14);
    material.volumetric_derivatives(J.data(), df.data(), n);
    for (std::size_t i = 0; i < n; ++i)
      EXPECT_NEAR(df[i], material.volumetric_derivative(J[i]), 1e-15);

    // The batch enclosure agrees with the default (scalar) one and holds the
    // point sums.
    const auto e = material.enclose_volumetric_sum(
      J.data(), J.data(), dJ.data(), dJ.data(), w.data(), n);
    const auto e2 = material.estep::Material::enclose_volumetric_sum(
      J.data(), J.data(), dJ.data(), dJ.data(), w.data(), n);
    EXPECT_TRUE(e.value.contains(value));
    EXPECT_TRUE(e.derivative.contains(slope));
    EXPECT_TRUE(e2.value.contains(value));
    EXPECT_TRUE(e2.derivative.contains(slope));
    EXPECT_LT(e.value.width(), 1e-12);

    // Inadmissible entries.
    J[7] = -0.1;
    EXPECT_TRUE(
      std::isinf(material.sum_volumetric_energy(J.data(), w.data(), n)));
  }

  // On wide boxes of J (one cell, J' = 1, J'' = 0) the curvature enclosure
  // holds f''(J) at both ends of the box: its bounds are taken at the right
  // ends of the range of log J.
  TEST(NeoHookean, CurvatureEnclosureHoldsTheEndsOfWideBoxes)
  {
    for (const auto &[lo, hi] : {std::pair{0.5, 2.},
                                 std::pair{0.2, 0.9},
                                 std::pair{1.1, 5.},
                                 std::pair{0.95, 1.05}})
      {
        const double   one = 1., zero = 0., w = 1.;
        double         slope = 0.;
        const Interval c     = material.enclose_volumetric_curvature_sum(
          &lo, &hi, &one, &one, &zero, &zero, &w, 1, slope);
        for (const double J : {lo, hi})
          EXPECT_TRUE(c.contains(material.volumetric_second_derivative(J)))
            << "J in [" << lo << ", " << hi << "]: f''(" << J
            << ") = " << material.volumetric_second_derivative(J) << " not in ["
            << c.lower << ", " << c.upper << "]";
      }
  }

  // The curvature enclosure over boxes of J, J', J'' holds sampled sums of
  // w (f''(J) J'^2 + f'(J) J''), near J = 1 (bounds of log J without
  // logarithms) and far from it, with a partial last batch of four cells; it
  // is about as tight as the material-independent default.
  TEST(NeoHookean, CurvatureEnclosureHoldsSamples)
  {
    std::mt19937                           rng(5);
    std::uniform_real_distribution<double> u(0., 1.);
    for (const double spread : {1e-3, 0.05, 0.8})
      for (const std::size_t n :
           {std::size_t(1), std::size_t(7), std::size_t(258)})
        {
          std::vector<double> J_lo(n), J_hi(n), d_lo(n), d_hi(n), dd_lo(n),
            dd_hi(n), w(n);
          for (std::size_t i = 0; i < n; ++i)
            {
              const double centre = 1. + spread * (2. * u(rng) - 1.),
                           width  = 1e-3 * spread * u(rng);
              J_lo[i]             = centre - width;
              J_hi[i]             = centre + width;
              d_lo[i]             = 2. * u(rng) - 1.5;
              d_hi[i]             = d_lo[i] + u(rng);
              dd_lo[i]            = 2. * u(rng) - 1.;
              dd_hi[i]            = dd_lo[i] + 0.1 * u(rng);
              w[i]                = 0.01 * u(rng);
            }
          double         slope = 0., slope_default = 0.;
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
          const Interval c_default =
            material.estep::Material::enclose_volumetric_curvature_sum(
              J_lo.data(),
              J_hi.data(),
              d_lo.data(),
              d_hi.data(),
              dd_lo.data(),
              dd_hi.data(),
              w.data(),
              n,
              slope_default);
          EXPECT_LE(c.width(), 1.01 * c_default.width() + 1e-15)
            << "spread " << spread << ", n " << n;
          for (unsigned int sample = 0; sample < 200; ++sample)
            {
              double sum = 0., slope_sum = 0.;
              for (std::size_t i = 0; i < n; ++i)
                {
                  const double t = sample == 0 ? 0. : sample == 1 ? 1. : u(rng);
                  const double Ji = J_lo[i] + t * (J_hi[i] - J_lo[i]);
                  const double d  = d_lo[i] + u(rng) * (d_hi[i] - d_lo[i]);
                  const double dd = dd_lo[i] + u(rng) * (dd_hi[i] - dd_lo[i]);
                  sum +=
                    w[i] * (material.volumetric_second_derivative(Ji) * d * d +
                            material.volumetric_derivative(Ji) * dd);
                  slope_sum +=
                    w[i] * std::abs(material.volumetric_derivative(Ji) * d);
                }
              EXPECT_TRUE(c.contains(sum))
                << "spread " << spread << ", n " << n;
              EXPECT_LE(slope_sum, slope * (1. + 1e-12));
            }
        }
  }

  TEST(NeoHookean, RejectsBadConstants)
  {
    EXPECT_THROW(NeoHookean(0.01, 0.), std::exception);
    EXPECT_THROW(NeoHookean(-1., 0.01), std::exception);
  }
} // namespace
