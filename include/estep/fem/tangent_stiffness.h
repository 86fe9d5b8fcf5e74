#ifndef estep_fem_tangent_stiffness_h
#define estep_fem_tangent_stiffness_h

#include <estep/fem/elastic_body.h>
#include <estep/systems/mechanical_system.h>

#include <memory>

namespace dealii
{
  class SparsityPattern;
  template <typename number>
  class SparseMatrix;
} // namespace dealii

namespace estep
{
  struct P1CellData;
  class Material;

  /**
   * The tangent stiffness (Hessian) H = d^2 V / dq^2 of a P1 elastic body,
   * assembled into a deal.II SparseMatrix from the per-cell data P1CellData and
   * the first elasticity tensor of the Material
   * (Material::first_elasticity_tensor()):
   * @f[ H_{(a i),(b k)} = \sum_e |\Omega_e| \sum_{I,L}
   *     \partial_I N_a \, A_{iIkL}(F_e) \, \partial_L N_b , @f]
   * with a, b the four vertices of cell e, i, k spatial components and
   * dN/dX the constant reference shape-function gradients. Rows and columns are
   * numbered as the body's coordinates (3 point + component).
   *
   * The sparsity pattern couples every two points that share a cell (3 x 3
   * blocks); it is built once, in the constructor, from the cell data.
   */
  class TangentStiffness
  {
  public:
    /**
     * The tangent stiffness of the cells @p data of material @p material. Both
     * are referenced, not copied, and must outlive this object.
     */
    TangentStiffness(const P1CellData &data, const Material &material);

    /** The tangent stiffness of @p body (referenced; must outlive this). */
    explicit TangentStiffness(const ElasticBody &body);

    ~TangentStiffness();

    /** The sparsity pattern of H (3 n_points square, symmetric). */
    const dealii::SparsityPattern &
    sparsity_pattern() const;

    /**
     * Assemble H at the configuration @p q (point-major positions) into @p H,
     * which must be initialised with sparsity_pattern(). Throws
     * std::domain_error if a cell is inverted (det F <= 0), where V = +infinity
     * has no Hessian.
     */
    void
    assemble(const Vector &q, dealii::SparseMatrix<double> &H) const;

  private:
    const P1CellData                        &data;
    const Material                          &material;
    std::unique_ptr<dealii::SparsityPattern> sparsity;
  };



  /**
   * An ElasticBody that also provides its Hessian (the MechanicalSystem
   * second-derivative interface) through a TangentStiffness, for the implicit
   * integrators. It is constructed exactly like an ElasticBody; the sparsity
   * pattern is built on the first call of hessian_sparsity() or hessian().
   *
   * Why a subclass: ElasticBody itself is being optimised separately; once that
   * settles, the three overrides can move into ElasticBody and this class
   * becomes an alias.
   */
  class ElasticBodyWithHessian : public ElasticBody
  {
  public:
    /** The constructors of ElasticBody. */
    using ElasticBody::ElasticBody;

    ~ElasticBodyWithHessian() override;

    /** True. */
    bool
    has_hessian() const override;

    const dealii::SparsityPattern &
    hessian_sparsity() const override;

    void
    hessian(const Vector &q, dealii::SparseMatrix<double> &H) const override;

    /** The tangent stiffness object (built on first use). */
    const TangentStiffness &
    tangent_stiffness() const;

  private:
    mutable std::unique_ptr<TangentStiffness> stiffness;
  };
} // namespace estep

#endif
