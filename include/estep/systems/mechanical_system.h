#ifndef estep_systems_mechanical_system_h
#define estep_systems_mechanical_system_h

#include <deal.II/lac/vector.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/parallel_blocks.h>
#include <estep/systems/free_flight.h>

#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
  class SparsityPattern;
  template <typename number>
  class SparseMatrix;
} // namespace dealii

namespace estep
{
  /** The vector type of configurations, velocities and gradients. */
  using Vector = dealii::Vector<double>;

  /** A constraint's normal by its nonzero components: (coordinate, value),
   * a coordinate at most once. */
  using SparseNormal = std::vector<std::pair<unsigned int, double>>;

  /**
   * A constraint hit along a free flight (an energy step of infinite height).
   */
  struct ConstraintEvent
  {
    /** Flight parameter (time since the start of the flight) of the first
     * contact. */
    double s;
    /** Gradient of the constraint function at the contact point: the reflection
     * direction. */
    Vector normal;
  };

  /**
   * A Lagrangian system L = 1/2 v^T M v - V(q) with a constant diagonal
   * (lumped) mass matrix M: the one interface that every time integrator meets.
   * An integrator never sees a mesh.
   *
   * Conventions:
   * - the coordinates q are point positions stored point by point: component c
   * of point i is q[spatial_dimension() * i + c]. Linear and angular momentum
   * are computed from this layout (see compute_momenta());
   * - energies are relative to a reference state where that is natural (the
   * undeformed body);
   * - V(q) = +infinity marks an inadmissible configuration (an inverted
   * element).
   */
  class MechanicalSystem
  {
  public:
    virtual ~MechanicalSystem() = default;

    /** A short name for output. */
    virtual std::string
    name() const = 0;

    /** Dimension of the space the points live in (2 or 3). */
    virtual unsigned int
    spatial_dimension() const = 0;

    /** Number of generalized coordinates. */
    virtual unsigned int
    n_dofs() const = 0;

    /** The diagonal of M^-1 (the lumped inverse mass), one entry per
     * coordinate. */
    virtual const Vector &
    inverse_mass() const = 0;

    /** V(q); +infinity if q is inadmissible. */
    virtual double
    energy(const Vector &q) const = 0;

    /** g = grad V(q). q must be admissible. */
    virtual void
    gradient(const Vector &q, Vector &g) const = 0;

    /** The restriction of V to the line q + s v, s >= 0 (see FreeFlight). */
    virtual std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const = 0;

    /**
     * The first constraint event on the flight q + s v with 0 < s <= s_max, if
     * the system has constraints (infinite energy steps, e.g. impenetrability)
     * and one is hit. The default has no constraints.
     */
    virtual std::optional<ConstraintEvent>
    first_constraint_event(const Vector &q,
                           const Vector &v,
                           const double  s_max) const;

    /**
     * The normals of every constraint that touches at @p q, whether its
     * points approach or part (several contact pairs at one instant), each
     * turned so that a velocity w with normal . w > 0 parts it. Energy
     * stepping reflects off all of them at once when reflections off one at
     * a time do not part them. The default: none.
     */
    virtual std::vector<SparseNormal>
    touching_constraints(const Vector &q) const;

    /** Whether first_constraint_event() can report events: an integrator
     * that does not ask for them cannot run the system. The default: false. */
    virtual bool
    has_constraints() const;

    /**
     * @name Optional second derivatives (used by the implicit integrators).
     * @{
     */

    /** Whether hessian() is available. The default: false. */
    virtual bool
    has_hessian() const;

    /**
     * The sparsity pattern of the Hessian (n_dofs() x n_dofs(), symmetric,
     * diagonal included), valid for the lifetime of the system. The default
     * throws (std::logic_error).
     */
    virtual const dealii::SparsityPattern &
    hessian_sparsity() const;

    /**
     * H = d^2 V / dq^2 at the admissible configuration @p q (the tangent
     * stiffness), written into @p H, which must have been initialised with
     * hessian_sparsity(). The default throws (std::logic_error).
     */
    virtual void
    hessian(const Vector &q, dealii::SparseMatrix<double> &H) const;
    /** @} */

    /**
     * @name A state shared among MPI ranks
     * In a run on several MPI ranks a system may let each rank keep only part
     * of the state current: the coordinates that its own share of the work
     * reads. An integrator that supports this (energy-stepping) updates only
     * those between its steps, takes the gradient there (kept_gradient()),
     * and completes a state (complete_state()) before anything else sees it.
     * Any other integrator keeps every coordinate, as by default.
     * @{
     */

    /**
     * The coordinates this rank keeps current, as sorted disjoint ranges, or
     * nullptr if it needs every coordinate (the default, and on one rank).
     * The ranges hold this rank's blocks of coordinates (rank_blocks() of
     * the n_blocks(n_dofs()) blocks, see distributed_blocks.h), where sums
     * over coordinates are taken; energy(), free_flight() and penetration()
     * read only the kept coordinates of their arguments.
     */
    virtual const std::vector<BlockRange> *
    kept_coordinates() const;

    /** grad V(q) at the kept coordinates (the others of @p g left as they
     * are), from q at the kept coordinates. Collective. The default:
     * gradient(). */
    virtual void
    kept_gradient(const Vector &q, Vector &g) const;

    /** Set every coordinate of @p x that this rank does not keep to its
     * value on the rank that computes it. Collective. The default: nothing
     * (every coordinate is kept). */
    virtual void
    complete_state(Vector &x) const;
    /** @} */

    /** Names of extra per-state quantities written to the history (e.g. a
     * tracked point). */
    virtual std::vector<std::string>
    observable_names() const;

    /** Values of the quantities named by observable_names() at state (q, v). */
    virtual std::vector<double>
    observables(const Vector &q, const Vector &v) const;

    /**
     * Whether bodies of the system have passed into each other at @p q
     * further than the system can represent (e.g. through a penalty too soft
     * to keep them apart): a sentence saying which and how deep, or empty.
     * The time loop asks after every step and ends a run with status
     * penetrated. The default: empty (no bodies).
     */
    virtual std::string
    penetration(const Vector &q) const;

    /**
     * The energy a contact penalty of the system stores in an intersection
     * one element deep (ContactSystem in penalty mode: l^2 / (2 eps), l the
     * longest boundary edge); an integrator that only sees energy changes of
     * a given size (energy-stepping) cannot stop bodies with a smaller one.
     * The default: +infinity (no penalty).
     */
    virtual double
    penalty_energy_scale() const;
  };

  /** Linear and angular momentum of a state. In 2D only the z components are
   * meaningful. */
  struct Momenta
  {
    double linear[3]  = {0., 0., 0.};
    double angular[3] = {0., 0., 0.};
  };

  /** Momenta of (q, v) from the point layout and lumped mass of @p system
   * (about the origin). */
  Momenta
  compute_momenta(const MechanicalSystem &system,
                  const Vector           &q,
                  const Vector           &v);

  /** Kinetic energy 1/2 v^T M v with the lumped mass of @p system. */
  double
  kinetic_energy(const MechanicalSystem &system, const Vector &v);

  /** @p work(r) for the ranges r of coordinates that this rank keeps
   * current (MechanicalSystem::kept_coordinates(): every coordinate, in
   * blocks, unless the system's state is shared among MPI ranks), on the
   * threads. */
  template <typename Work>
  void
  for_each_kept_range(const MechanicalSystem &system, const Work &work)
  {
    const unsigned int n = system.n_dofs();
    if (const std::vector<BlockRange> *kept = system.kept_coordinates())
      for_each_block(kept->size(),
                     [&](const unsigned int i) { work((*kept)[i]); });
    else
      for_each_block(n_blocks(n),
                     [&](const unsigned int b) { work(block_range(b, n)); });
  }

  /**
   * The sum of @p term(b) over the blocks b of @p system's coordinates
   * (parallel_blocks.h), added in block order. On several MPI ranks that
   * share the system's state (MechanicalSystem::kept_coordinates()) each
   * computes the terms of its own blocks, which it keeps, and they are
   * shared (collective); else every rank computes them all. The same bits
   * on any number of threads and ranks.
   */
  template <typename T, typename Term>
  T
  sum_over_coordinate_blocks(const MechanicalSystem &system, const Term &term)
  {
    const unsigned int n_coordinate_blocks = n_blocks(system.n_dofs());
    return system.kept_coordinates() ?
             sum_over_distributed_blocks<T>(n_coordinate_blocks, term) :
             sum_over_blocks<T>(n_coordinate_blocks, term);
  }

  /** Whether every coordinate of each of @p vectors (states of @p system)
   * is finite, checked over the blocks of coordinates as
   * sum_over_coordinate_blocks() takes them: collective, and from the kept
   * coordinates alone where the system shares its state. */
  bool
  all_finite(const MechanicalSystem                     &system,
             const std::initializer_list<const Vector *> vectors);
} // namespace estep

#endif
