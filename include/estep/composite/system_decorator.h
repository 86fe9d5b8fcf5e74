#ifndef estep_composite_system_decorator_h
#define estep_composite_system_decorator_h

#include <estep/systems/mechanical_system.h>

#include <memory>

namespace estep
{
  /**
   * A MechanicalSystem made from another one (the base) by adding one thing:
   * a potential term (gravity), constraints (rigid obstacles), or a change of
   * coordinates (supports). Every function forwards to the base; a decorator
   * overrides what it changes. Decorators stack: a scene is its bodies in
   * contact, decorated by obstacles, gravity and supports.
   */
  class SystemDecorator : public MechanicalSystem
  {
  public:
    /** @p base must not be null. */
    explicit SystemDecorator(std::shared_ptr<const MechanicalSystem> base);

    /** The decorated system. */
    const MechanicalSystem &
    base() const;

    std::string
    name() const override;

    unsigned int
    spatial_dimension() const override;

    unsigned int
    n_dofs() const override;

    const Vector &
    inverse_mass() const override;

    double
    energy(const Vector &q) const override;

    void
    gradient(const Vector &q, Vector &g) const override;

    std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const override;

    std::optional<ConstraintEvent>
    first_constraint_event(const Vector &q,
                           const Vector &v,
                           const double  s_max) const override;

    bool
    has_constraints() const override;

    std::vector<SparseNormal>
    touching_constraints(const Vector &q) const override;

    bool
    has_hessian() const override;

    const dealii::SparsityPattern &
    hessian_sparsity() const override;

    void
    hessian(const Vector &q, dealii::SparseMatrix<double> &H) const override;

    std::vector<std::string>
    observable_names() const override;

    std::vector<double>
    observables(const Vector &q, const Vector &v) const override;

    std::string
    penetration(const Vector &q) const override;

    double
    penalty_energy_scale() const override;

    /**
     * @name The state shared among MPI ranks
     * As the base shares it if shares_base_state, else every coordinate (see
     * MechanicalSystem). kept_gradient(): the base's kept_gradient() if
     * shared, else gradient(); a decorator that adds to the gradient
     * overrides it with base_kept_gradient() and its own part at the kept
     * coordinates.
     * @{
     */
    const std::vector<BlockRange> *
    kept_coordinates() const override;

    void
    kept_gradient(const Vector &q, Vector &g) const override;

    void
    complete_state(Vector &x) const override;
    /** @} */

  protected:
    std::shared_ptr<const MechanicalSystem> base_system;

    /** Whether the state is shared among MPI ranks as the base shares it:
     * set by a decorator whose own terms read only coordinates that the
     * base keeps on every rank, and which adds its part of the gradient in
     * kept_gradient(). False by default. */
    bool shares_base_state = false;

    /** The base's kept_gradient() if the state is shared as the base shares
     * it, else the base's gradient(). */
    void
    base_kept_gradient(const Vector &q, Vector &g) const;
  };
} // namespace estep

#endif
