#include <deal.II/base/tensor.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <estep/fem/p1_cell_data.h>
#include <estep/fem/tangent_stiffness.h>
#include <estep/materials/material.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace estep
{
  TangentStiffness::TangentStiffness(const P1CellData &data,
                                     const Material   &material)
    : data(data)
    , material(material)
    , sparsity(std::make_unique<dealii::SparsityPattern>())
  {
    const unsigned int                           n = 3 * data.n_points;
    dealii::DynamicSparsityPattern               dsp(n, n);
    std::vector<dealii::types::global_dof_index> dofs(12);
    for (unsigned int e = 0; e < data.n_cells; ++e)
      {
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int c = 0; c < 3; ++c)
            dofs[3 * a + c] = 3 * data.point[a][e] + c;
        for (const auto row : dofs)
          dsp.add_entries(row, dofs.begin(), dofs.end());
      }
    sparsity->copy_from(dsp);
  }



  TangentStiffness::TangentStiffness(const ElasticBody &body)
    : TangentStiffness(body.every_cell_data(), body.material())
  {}



  TangentStiffness::~TangentStiffness() = default;



  const dealii::SparsityPattern &
  TangentStiffness::sparsity_pattern() const
  {
    return *sparsity;
  }



  void
  TangentStiffness::assemble(const Vector                 &q,
                             dealii::SparseMatrix<double> &H) const
  {
    AssertDimension(q.size(), 3 * data.n_points);
    AssertDimension(H.m(), 3 * data.n_points);
    H = 0.;
    dealii::FullMatrix<double>                   cell_matrix(12, 12);
    std::vector<dealii::types::global_dof_index> dofs(12);
    for (unsigned int e = 0; e < data.n_cells; ++e)
      {
        // Shape-function gradients dN_a/dX_I: rows 1..3 from the cell data,
        // row 0 minus their sum.
        double grad[4][3];
        for (unsigned int I = 0; I < 3; ++I)
          {
            grad[0][I] = 0.;
            for (unsigned int a = 0; a < 3; ++a)
              {
                grad[a + 1][I] = data.shape_gradient[3 * a + I][e];
                grad[0][I] -= grad[a + 1][I];
              }
          }
        dealii::Tensor<2, 3> F;
        for (unsigned int a = 0; a < 4; ++a)
          {
            const unsigned int p = data.point[a][e];
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int I = 0; I < 3; ++I)
                F[i][I] += q[3 * p + i] * grad[a][I];
          }
        if (!(dealii::determinant(F) > 0.))
          throw std::domain_error(
            "TangentStiffness: cell " + std::to_string(e) +
            " is inverted (det F <= 0); the energy has no Hessian there.");
        const dealii::Tensor<4, 3> A = material.first_elasticity_tensor(F);

        // G[a][i][k][L] = sum_I dN_a/dX_I A_iIkL, then K = vol G . dN_b.
        double G[4][3][3][3];
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int L = 0; L < 3; ++L)
                {
                  double s = 0.;
                  for (unsigned int I = 0; I < 3; ++I)
                    s += grad[a][I] * A[i][I][k][L];
                  G[a][i][k][L] = s;
                }
        const double volume = data.volume[e];
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int b = 0; b < 4; ++b)
              for (unsigned int k = 0; k < 3; ++k)
                {
                  double s = 0.;
                  for (unsigned int L = 0; L < 3; ++L)
                    s += G[a][i][k][L] * grad[b][L];
                  cell_matrix(3 * a + i, 3 * b + k) = volume * s;
                }
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int c = 0; c < 3; ++c)
            dofs[3 * a + c] = 3 * data.point[a][e] + c;
        H.add(dofs, cell_matrix);
      }
  }



  ElasticBodyWithHessian::~ElasticBodyWithHessian() = default;



  bool
  ElasticBodyWithHessian::has_hessian() const
  {
    return true;
  }



  const TangentStiffness &
  ElasticBodyWithHessian::tangent_stiffness() const
  {
    if (!stiffness)
      stiffness = std::make_unique<TangentStiffness>(*this);
    return *stiffness;
  }



  const dealii::SparsityPattern &
  ElasticBodyWithHessian::hessian_sparsity() const
  {
    return tangent_stiffness().sparsity_pattern();
  }



  void
  ElasticBodyWithHessian::hessian(const Vector                 &q,
                                  dealii::SparseMatrix<double> &H) const
  {
    tangent_stiffness().assemble(q, H);
  }
} // namespace estep
