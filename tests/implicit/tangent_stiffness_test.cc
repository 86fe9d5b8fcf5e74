// The tangent stiffness (Hessian of V) of the P1 neo-Hookean body against
// central differences of the gradient, its symmetry and sparsity, and the
// first elasticity tensor of the material against differences of P.
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <estep/fem/tangent_stiffness.h>
#include <estep/materials/neo_hookean.h>

#include <gtest/gtest.h>

#include "implicit_test_support.h"

#include <cmath>
#include <random>

namespace
{
  estep::Vector
  randomly_deformed(const estep::ElasticBody &body,
                    const double              amplitude,
                    const unsigned int        seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    estep::Vector                          q = body.reference_configuration();
    // A finite rotation and stretch plus random noise: far from the
    // reference state, every cell still positive.
    for (unsigned int i = 0; i < q.size(); i += 3)
      {
        const double x = q[i], y = q[i + 1], z = q[i + 2];
        q[i]     = 0.8 * x - 0.6 * y + u(rng);
        q[i + 1] = 0.6 * x + 0.8 * y + 0.2 * z + u(rng);
        q[i + 2] = 1.3 * z + u(rng);
      }
    return q;
  }

  TEST(MaterialTangent, ElasticityTensorMatchesDifferencesOfStress)
  {
    const estep::NeoHookean material(0.0100, 0.0066);
    dealii::Tensor<2, 3>    F;
    F[0][0] = 1.1, F[0][1] = 0.2, F[0][2] = -0.1;
    F[1][0] = 0.05, F[1][1] = 0.9, F[1][2] = 0.3;
    F[2][0] = -0.2, F[2][1] = 0.1, F[2][2] = 1.2;
    const dealii::Tensor<4, 3> A     = material.first_elasticity_tensor(F);
    const double               delta = 1e-6;
    double                     error = 0., scale = 0.;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int L = 0; L < 3; ++L)
        {
          dealii::Tensor<2, 3> Fp = F, Fm = F;
          Fp[k][L] += delta;
          Fm[k][L] -= delta;
          const dealii::Tensor<2, 3> dP = (material.first_piola_stress(Fp) -
                                           material.first_piola_stress(Fm)) /
                                          (2. * delta);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int I = 0; I < 3; ++I)
              {
                error = std::max(error, std::abs(dP[i][I] - A[i][I][k][L]));
                scale = std::max(scale, std::abs(A[i][I][k][L]));
                EXPECT_NEAR(A[i][I][k][L], A[k][L][i][I], 1e-16);
              }
        }
    EXPECT_LT(error, 1e-8 * scale);
  }

  TEST(MaterialTangent, SecondDerivativeDefaultMatchesExact)
  {
    const estep::NeoHookean material(0.0100, 0.0066);
    for (const double J : {0.5, 0.9, 1., 1.2, 2.})
      EXPECT_NEAR(material.volumetric_second_derivative(J),
                  material.Material::volumetric_second_derivative(J),
                  1e-8 * std::abs(material.volumetric_second_derivative(J)));
  }

  TEST(TangentStiffness, HessianMatchesCentralDifferencesOfGradient)
  {
    const auto          body = estep_test::cube_with_hessian(2);
    const estep::Vector q    = randomly_deformed(*body, 0.03, 7);
    ASSERT_TRUE(std::isfinite(body->energy(q)));
    ASSERT_TRUE(body->has_hessian());
    dealii::SparseMatrix<double> H(body->hessian_sparsity());
    body->hessian(q, H);

    // Whole columns: H e_j against (g(q + d e_j) - g(q - d e_j)) / 2d.
    const unsigned int n = body->n_dofs();
    estep::Vector      gp(n), gm(n), qp(q), column(n), e(n);
    const double       d         = 1e-6;
    double             max_error = 0., max_entry = 0.;
    for (unsigned int j = 0; j < n; j += 5)
      {
        qp    = q;
        qp[j] = q[j] + d;
        body->gradient(qp, gp);
        qp[j] = q[j] - d;
        body->gradient(qp, gm);
        e    = 0.;
        e[j] = 1.;
        H.vmult(column, e);
        for (unsigned int i = 0; i < n; ++i)
          {
            const double fd = (gp[i] - gm[i]) / (2. * d);
            max_error       = std::max(max_error, std::abs(fd - column[i]));
            max_entry       = std::max(max_entry, std::abs(column[i]));
          }
      }
    EXPECT_LT(max_error, 1e-7 * max_entry) << "max entry " << max_entry;

    // A random direction: H w against the directional difference.
    const estep::Vector w = estep_test::random_direction(n, 5);
    estep::Vector       Hw(n);
    H.vmult(Hw, w);
    qp = q;
    qp.add(d, w);
    body->gradient(qp, gp);
    qp = q;
    qp.add(-d, w);
    body->gradient(qp, gm);
    double error = 0.;
    for (unsigned int i = 0; i < n; ++i)
      error = std::max(error, std::abs((gp[i] - gm[i]) / (2. * d) - Hw[i]));
    EXPECT_LT(error, 1e-7 * Hw.linfty_norm());
  }

  TEST(TangentStiffness, SymmetricWithRigidNullSpaceAtReference)
  {
    const auto                   body = estep_test::cube_with_hessian(2);
    const estep::Vector          X    = body->reference_configuration();
    dealii::SparseMatrix<double> H(body->hessian_sparsity());
    body->hessian(randomly_deformed(*body, 0.02, 3), H);
    double asymmetry = 0., scale = 0.;
    for (auto it = H.begin(); it != H.end(); ++it)
      {
        asymmetry =
          std::max(asymmetry,
                   std::abs(it->value() - H.el(it->column(), it->row())));
        scale = std::max(scale, std::abs(it->value()));
      }
    EXPECT_LT(asymmetry, 1e-14 * scale);

    // At the reference state, translations and infinitesimal rotations are
    // zero modes of the stiffness (the gradient vanishes there).
    body->hessian(X, H);
    const unsigned int n = body->n_dofs();
    estep::Vector      mode(n), Hm(n);
    for (unsigned int c = 0; c < 3; ++c)
      {
        mode = 0.;
        for (unsigned int i = c; i < n; i += 3)
          mode[i] = 1.;
        H.vmult(Hm, mode);
        EXPECT_LT(Hm.linfty_norm(), 1e-14 * scale);
      }
    for (unsigned int i = 0; i < n; i += 3)
      {
        mode[i]     = -(X[i + 1] - 0.5);
        mode[i + 1] = X[i] - 0.5;
        mode[i + 2] = 0.;
      }
    H.vmult(Hm, mode);
    EXPECT_LT(Hm.linfty_norm(), 1e-14 * scale);
  }

  TEST(TangentStiffness, InvertedCellThrows)
  {
    const auto    body = estep_test::cube_with_hessian(1);
    estep::Vector q    = body->reference_configuration();
    for (unsigned int i = 2; i < q.size(); i += 3)
      q[i] = -q[i]; // a reflection inverts every cell
    dealii::SparseMatrix<double> H(body->hessian_sparsity());
    EXPECT_THROW(body->hessian(q, H), std::domain_error);
  }

  TEST(MechanicalSystem, DefaultHasNoHessian)
  {
    const auto body = estep_test::cube_with_hessian(1);
    // The plain ElasticBody part answers with the base-class defaults.
    const estep::ElasticBody &plain = *body;
    EXPECT_TRUE(plain.has_hessian()); // virtual: the subclass answers
    EXPECT_FALSE(plain.estep::MechanicalSystem::has_hessian());
    EXPECT_THROW(plain.estep::MechanicalSystem::hessian_sparsity(),
                 std::logic_error);
  }
} // namespace
