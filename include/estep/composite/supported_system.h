#ifndef estep_composite_supported_system_h
#define estep_composite_supported_system_h

#include <estep/composite/system_decorator.h>

#include <memory>
#include <vector>

namespace estep
{
  /**
   * Supports: a system made from a base system by fixing some of its points
   * where they are. The fixed points are removed from the degrees of freedom,
   * so that every integrator keeps them exactly in place (zero displacement,
   * zero velocity) and energy-stepping's conservation of the terraced energy
   * holds exactly for the remaining motion: the supported system is an
   * ordinary MechanicalSystem of its own.
   *
   * Coordinates: the positions of the free points (the base's points that are
   * not fixed, in increasing order), point-major with the base's spatial
   * dimension, so that compute_momenta() and kinetic_energy() still apply
   * (momenta of the free points only: the supports exert forces). The inverse
   * mass is the base's restricted to the free points.
   *
   * Every other function evaluates the base at the expanded state: the full
   * configuration made of the free points' positions and the fixed points'
   * positions given to the constructor (expand()), and the full velocity with
   * zero on the fixed points (expand_velocity()). The gradient and the normals
   * of constraint events are the base's restricted to the free points
   * (restrict()); the free flight is the base's along the expanded line (the
   * same function of s); the Hessian is the free-free block of the base's,
   * with its own sparsity pattern (built on first use from the base's);
   * observables are the base's of the expanded state.
   *
   * On several MPI ranks it shares the state where its base does
   * (kept_coordinates()): a rank keeps the free coordinates its base keeps,
   * and its own blocks of the free coordinates, where the sums over them are
   * taken. The gradient of those of its blocks that the base does not keep
   * comes from the ranks whose blocks of the base's coordinates hold them.
   *
   * The evaluations use internal scratch vectors (no allocation per call):
   * not thread-safe, like the systems it decorates. The base's free flight
   * receives vectors owned by this object that stay unchanged until the next
   * call of free_flight().
   */
  class SupportedSystem : public SystemDecorator
  {
  public:
    /**
     * The system @p base with the points @p fixed_points held at their
     * positions in @p configuration, a full configuration of the base
     * (base->n_dofs() entries; the free points' entries are not used). The
     * list may come in any order and name a point more than once; it is
     * kept sorted and without repetitions. Throws std::invalid_argument if
     * @p configuration has the wrong size, a point is out of range (not
     * below base->n_dofs() / base->spatial_dimension()) or no point is left
     * free.
     */
    SupportedSystem(std::shared_ptr<const MechanicalSystem> base,
                    std::vector<unsigned int>               fixed_points,
                    const Vector                           &configuration);

    ~SupportedSystem() override;

    /** spatial_dimension() times the number of free points. */
    unsigned int
    n_dofs() const override;

    /** The base's lumped inverse mass of the free points. */
    const Vector &
    inverse_mass() const override;

    /** V of the base at expand(@p q). */
    double
    energy(const Vector &q) const override;

    /** The base's gradient at expand(@p q), restricted to the free points. */
    void
    gradient(const Vector &q, Vector &g) const override;

    /** The base's flight from expand(@p q) with velocity
     * expand_velocity(@p v): the same f(s). */
    std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const override;

    /** The base's first event along the expanded flight, with its normal
     * restricted to the free points. */
    std::optional<ConstraintEvent>
    first_constraint_event(const Vector &q,
                           const Vector &v,
                           const double  s_max) const override;

    /** The base's touching constraints at expand(@p q), restricted to the
     * free points; those of fixed points alone are left out. */
    std::vector<SparseNormal>
    touching_constraints(const Vector &q) const override;

    /** The free-free block of the base's Hessian pattern (n_dofs() square,
     * diagonal included). Throws std::logic_error if the base has no Hessian.
     */
    const dealii::SparsityPattern &
    hessian_sparsity() const override;

    /** The free-free block of the base's Hessian at expand(@p q); @p H must
     * have been initialised with hessian_sparsity(). */
    void
    hessian(const Vector &q, dealii::SparseMatrix<double> &H) const override;

    /** Where the base shares its state among MPI ranks: the free
     * coordinates whose base coordinates the base keeps, and this rank's
     * blocks of the free coordinates. Else nullptr. */
    const std::vector<BlockRange> *
    kept_coordinates() const override;

    /** The base's kept_gradient() at the expanded configuration, restricted
     * to the free points, and at this rank's blocks of free coordinates that
     * the base does not keep, the gradient of the ranks that compute it.
     * Collective. */
    void
    kept_gradient(const Vector &q, Vector &g) const override;

    /** The base's complete_state() of the expanded state. Collective. */
    void
    complete_state(Vector &x) const override;

    /** The base's observables of the expanded state. */
    std::vector<double>
    observables(const Vector &q, const Vector &v) const override;

    /** The base's penetration() of the expanded configuration. */
    std::string
    penetration(const Vector &q) const override;

    /** The full configuration of the base: @p q_free (n_dofs() entries) on
     * the free points, the positions given to the constructor on the fixed
     * ones. */
    Vector
    expand(const Vector &q_free) const;

    /** The full velocity of the base: @p v_free on the free points, zero on
     * the fixed ones. */
    Vector
    expand_velocity(const Vector &v_free) const;

    /** The free points' part of @p full, a vector of base().n_dofs()
     * entries (a configuration, velocity or gradient of the base). */
    Vector restrict(const Vector &full) const;

    /** Number of fixed points. */
    unsigned int
    n_fixed_points() const;

    /** The fixed points (base numbering), increasing. */
    const std::vector<unsigned int> &
    fixed_points() const;

    /** The free points (base numbering), increasing: free point k of this
     * system is point free_points()[k] of the base. */
    const std::vector<unsigned int> &
    free_points() const;

  private:
    /** Write @p q_free into the free entries of @p full (whose fixed entries
     * are left as they are). */
    void
    scatter(const Vector &q_free, Vector &full) const;

    /** scatter() of the kept coordinates alone (kept_coordinates()), which
     * are all the base reads of its energy, gradient, flight and
     * penetration. */
    void
    scatter_kept(const Vector &q_free, Vector &full) const;

    /** Write the free entries of @p full into @p part (resized if needed). */
    void
    gather(const Vector &full, Vector &part) const;

    /** Build the block pattern and the base-sized matrix, once. */
    void
    build_hessian_structure() const;

    const unsigned int        dim;
    std::vector<unsigned int> fixed_point_list;
    std::vector<unsigned int> free_point_list;
    /** The base's coordinate of each free coordinate. */
    std::vector<unsigned int> free_dofs;
    /** The free coordinate of each base coordinate
     * (the largest unsigned int on the fixed points). */
    std::vector<unsigned int> reduced_dofs;
    Vector                    inv_mass;
    /** The full configuration with the fixed points' positions: the template
     * of expand(). */
    Vector full_configuration;

    /** Scratch: expanded configuration, velocity and gradient of energy(),
     * gradient(), first_constraint_event(), hessian(), observables(). */
    mutable Vector scratch_q, scratch_v, scratch_g;
    /** The expanded line of the last free_flight(). */
    mutable Vector flight_q, flight_v;

    /** What a state shared among MPI ranks needs (see kept_coordinates()):
     * the kept coordinates, those whose gradient this rank sends and those
     * it receives, and their exchange. */
    struct SharedState;
    mutable std::unique_ptr<SharedState> shared_state;
    /** The shared state for the current number of ranks, or nullptr where
     * the base does not share its state. */
    SharedState *
    current_shared_state() const;

    /** The block pattern and the base's Hessian (built on first use). */
    mutable std::unique_ptr<dealii::SparsityPattern>      sparsity;
    mutable std::unique_ptr<dealii::SparseMatrix<double>> full_hessian;
  };
} // namespace estep

#endif
