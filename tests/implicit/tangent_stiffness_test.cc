// The tangent stiffness (Hessian of V) of the P1 body against central
// differences of the gradient (neo-Hookean and the quadratic-volume
// neo-Hookean material), its symmetry and sparsity, and the first elasticity
// tensor of the materials against differences of P.
#include <deal.II/grid/tria.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <estep/fem/meshes.h>
#include <estep/fem/tangent_stiffness.h>
#include <estep/materials/neo_hookean.h>
#include <estep/materials/quadratic_volume_neo_hookean.h>

#include <gtest/gtest.h>

#include "implicit_test_support.h"

#include <cmath>
#include <iostream>
#include <memory>
#include <random>
#include <vector>

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

  /** The materials whose tangents are checked, with the same Lame constants.
   */
  std::vector<std::shared_ptr<const estep::Material>>
  materials()
  {
    return {std::make_shared<estep::NeoHookean>(0.0100, 0.0066),
            std::make_shared<estep::QuadraticVolumeNeoHookean>(0.0100, 0.0066)};
  }

  /** The seed cube (n^3 hexahedra of 24 tets) of @p material, with a Hessian.
   */
  std::unique_ptr<estep::ElasticBodyWithHessian>
  cube_of(const std::shared_ptr<const estep::Material> &material,
          const unsigned int                            n)
  {
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, n);
    return std::make_unique<estep::ElasticBodyWithHessian>(tria,
                                                           material,
                                                           0.100,
                                                           "cube");
  }

  TEST(MaterialTangent, ElasticityTensorMatchesDifferencesOfStress)
  {
    for (const auto &material : materials())
      {
        dealii::Tensor<2, 3> F;
        F[0][0] = 1.1, F[0][1] = 0.2, F[0][2] = -0.1;
        F[1][0] = 0.05, F[1][1] = 0.9, F[1][2] = 0.3;
        F[2][0] = -0.2, F[2][1] = 0.1, F[2][2] = 1.2;
        const dealii::Tensor<4, 3> A     = material->first_elasticity_tensor(F);
        const double               delta = 1e-6;
        double                     error = 0., scale = 0.;
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int L = 0; L < 3; ++L)
            {
              dealii::Tensor<2, 3> Fp = F, Fm = F;
              Fp[k][L] += delta;
              Fm[k][L] -= delta;
              const dealii::Tensor<2, 3> dP =
                (material->first_piola_stress(Fp) -
                 material->first_piola_stress(Fm)) /
                (2. * delta);
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int I = 0; I < 3; ++I)
                  {
                    error = std::max(error, std::abs(dP[i][I] - A[i][I][k][L]));
                    scale = std::max(scale, std::abs(A[i][I][k][L]));
                    EXPECT_NEAR(A[i][I][k][L], A[k][L][i][I], 1e-16);
                  }
            }
        EXPECT_LT(error, 1e-8 * scale) << material->name();
      }
  }

  TEST(MaterialTangent, SecondDerivativeDefaultMatchesExact)
  {
    for (const auto &material : materials())
      for (const double J : {0.5, 0.9, 1., 1.2, 2.})
        EXPECT_NEAR(material->volumetric_second_derivative(J),
                    material->Material::volumetric_second_derivative(J),
                    1e-8 * std::abs(material->volumetric_second_derivative(J)))
          << material->name();
  }

  /**
   * The Hessian of @p body at @p q against central differences of its
   * gradient: every fifth column, and the product with a random direction.
   */
  void
  check_hessian_against_differences(const estep::ElasticBodyWithHessian &body,
                                    const estep::Vector                 &q)
  {
    ASSERT_TRUE(std::isfinite(body.energy(q)));
    ASSERT_TRUE(body.has_hessian());
    dealii::SparseMatrix<double> H(body.hessian_sparsity());
    body.hessian(q, H);

    // Whole columns: H e_j against (g(q + d e_j) - g(q - d e_j)) / 2d.
    const unsigned int n = body.n_dofs();
    estep::Vector      gp(n), gm(n), qp(q), column(n), e(n);
    const double       d         = 1e-6;
    double             max_error = 0., max_entry = 0.;
    for (unsigned int j = 0; j < n; j += 5)
      {
        qp    = q;
        qp[j] = q[j] + d;
        body.gradient(qp, gp);
        qp[j] = q[j] - d;
        body.gradient(qp, gm);
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
    std::cout << body.material().name()
              << ": Hessian columns against central differences of the "
                 "gradient: max error "
              << max_error << " (largest entry " << max_entry << ")\n";
    EXPECT_LT(max_error, 1e-7 * max_entry) << "max entry " << max_entry;

    // A random direction: H w against the directional difference.
    const estep::Vector w = estep_test::random_direction(n, 5);
    estep::Vector       Hw(n);
    H.vmult(Hw, w);
    qp = q;
    qp.add(d, w);
    body.gradient(qp, gp);
    qp = q;
    qp.add(-d, w);
    body.gradient(qp, gm);
    double error = 0.;
    for (unsigned int i = 0; i < n; ++i)
      error = std::max(error, std::abs((gp[i] - gm[i]) / (2. * d) - Hw[i]));
    std::cout << "  H w against the directional difference: max error " << error
              << " (largest |H w| " << Hw.linfty_norm() << ")\n";
    EXPECT_LT(error, 1e-7 * Hw.linfty_norm());
  }

  TEST(TangentStiffness, HessianMatchesCentralDifferencesOfGradient)
  {
    const auto body = estep_test::cube_with_hessian(2);
    check_hessian_against_differences(*body, randomly_deformed(*body, 0.03, 7));
  }

  TEST(TangentStiffness, QuadraticVolumeHessianMatchesDifferencesOfGradient)
  {
    const auto body = cube_of(materials()[1], 2);
    ASSERT_EQ(body->material().name(), "neo-Hookean quadratic volume");
    check_hessian_against_differences(*body, randomly_deformed(*body, 0.03, 7));
  }

  // The two materials have the same linearisation at F = I: the same
  // stiffness at the reference configuration.
  TEST(TangentStiffness, BothMaterialsAgreeAtReference)
  {
    const auto neo_hookean         = cube_of(materials()[0], 2),
               quadratic           = cube_of(materials()[1], 2);
    const estep::Vector          X = neo_hookean->reference_configuration();
    dealii::SparseMatrix<double> H0(neo_hookean->hessian_sparsity()),
      H1(quadratic->hessian_sparsity());
    neo_hookean->hessian(X, H0);
    quadratic->hessian(X, H1);
    double difference = 0., scale = 0.;
    for (auto it = H0.begin(); it != H0.end(); ++it)
      {
        difference =
          std::max(difference,
                   std::abs(it->value() - H1.el(it->row(), it->column())));
        scale = std::max(scale, std::abs(it->value()));
      }
    std::cout << "stiffness at the reference configuration: the materials "
                 "differ by "
              << difference << " (largest entry " << scale << ")\n";
    EXPECT_LT(difference, 1e-15 * scale);
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
