#ifndef estep_fem_elastic_body_h
#define estep_fem_elastic_body_h

#include <deal.II/base/types.h>

#include <estep/base/parallel_blocks.h>
#include <estep/fem/elastic_bodies.h>
#include <estep/fem/p1_cell_data.h>
#include <estep/materials/material.h>
#include <estep/systems/mechanical_system.h>

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
} // namespace dealii

namespace estep
{
  class ElasticFreeFlight;
  class GhostExchange;

  /**
   * A hyperelastic body discretised by linear tetrahedra (P1), as a
   * MechanicalSystem.
   *
   * Coordinates q are the current positions of the mesh vertices ("points"),
   * point-major: q[3 i + c] is component c of point i, with points numbered as
   * the DoFHandler of FESystem<3>(FE_SimplexP<3>(1), 3) numbers its vertex dofs
   * (see P1CellData). The
   * potential energy is
   * @f[ V(q) = \sum_e |\Omega_e| \, W(F_e(q)), @f]
   * with W the strain energy density of the Material relative to the undeformed
   * state (so the reference configuration has V = 0), F_e the (constant)
   * deformation gradient of cell e and |Omega_e| its reference volume; V =
   * +infinity as soon as one det F_e <= 0. The mass is the lumped (row-sum)
   * mass of density rho: rho |Omega_e| / 4 per vertex and cell, computed with
   * deal.II FEValues (FE_SimplexP, QGaussSimplex, MappingFE) once and checked
   * against the geometric formula.
   *
   * The constructor computes the P1CellData of the mesh and keeps no deal.II
   * object: energy(), gradient() and free_flight() loop over plain arrays.
   *
   * Its loops over cells run on the threads of thread_count() (see
   * parallel_blocks.h) and, in a run on several MPI ranks, on the ranks'
   * blocks of cells (see distributed_blocks.h; energy() and gradient() are
   * then collective, and every rank holds only the data of the cells it
   * computes, see distributed_cell_data.h, and reads the state only at the
   * points of those cells, see kept_coordinates()); they give the
   * same bits on any number of threads and ranks. Not thread-safe
   * itself: energy() and gradient() use internal scratch arrays.
   */
  class ElasticBody : public MechanicalSystem, public ElasticBodies
  {
  public:
    /**
     * The body occupying the tetrahedral mesh @p tria in its reference
     * (undeformed) state, of material @p material and mass density @p density >
     * 0 (mass per unit reference volume). Throws dealii::ExcMessage if the mesh
     * has non-tetrahedral, inverted or degenerate cells.
     */
    ElasticBody(const dealii::Triangulation<3, 3> &tria,
                std::shared_ptr<const Material>    material,
                const double                       density,
                const std::string                 &name = "elastic body");

    /**
     * The body of the mesh @p cell_data describes (make_p1_cell_data() of
     * its mesh and density), e.g. as make_p1_cell_data_on_first_rank() gives
     * each MPI rank its part. Throws dealii::ExcMessage if the arrays are
     * incomplete, do not hold this rank's cells, or a point has no mass.
     */
    ElasticBody(P1CellData                      cell_data,
                std::shared_ptr<const Material> material,
                const std::string              &name = "elastic body");

    ~ElasticBody() override;

    std::string
    name() const override;

    /** Always 3. */
    unsigned int
    spatial_dimension() const override;

    /** 3 n_vertices(). */
    unsigned int
    n_dofs() const override;

    const Vector &
    inverse_mass() const override;

    double
    energy(const Vector &q) const override;

    void
    gradient(const Vector &q, Vector &g) const override;

    /**
     * @name The state shared among MPI ranks
     * On several ranks each keeps current the points of the cells it
     * computes (those of its blocks and the chunks its points' gradient
     * needs, see distributed_cell_data.h) and its blocks of coordinates, in
     * ranges cut at the blocks' ends. The
     * gradient of the other ranks' points among them comes from the ranks
     * that compute it (deal.II's Utilities::MPI::NoncontiguousPartitioner),
     * instead of every point's from every rank. See MechanicalSystem.
     * @{
     */
    const std::vector<BlockRange> *
    kept_coordinates() const override;

    void
    kept_gradient(const Vector &q, Vector &g) const override;

    void
    complete_state(Vector &x) const override;

    /** For a system made of bodies that shares its state among the ranks
     * (ContactSystem): on several ranks, a flag per coordinate, set for those
     * the cells this rank computes read (kept_coordinates() adds this rank's
     * blocks of coordinates); empty on one rank. */
    const std::vector<char> &
    coordinates_read() const;

    /** On several ranks, the coordinates of this rank's own points, whose
     * gradient it computes, in the order of gradient_of_own_points(). */
    const std::vector<dealii::types::global_dof_index> &
    own_coordinates() const;

    /** The gradient of this rank's points at @p q, read at the kept
     * coordinates: into @p g (resized to n_dofs()) where they are in place
     * (own_coordinates() is a range), else into a scratch array; returns
     * where they are, in the order of own_coordinates(), valid until the
     * next call. Not collective. */
    const double *
    gradient_of_own_points(const Vector &q, Vector &g) const;
    /** @} */

    /** An ElasticFreeFlight (see there) of this body along q + s v. */
    std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const override;

    /** The same as free_flight(), with its concrete type. */
    std::unique_ptr<ElasticFreeFlight>
    make_free_flight(const Vector &q, const Vector &v) const;

    /** Number of tetrahedra. */
    unsigned int
    n_cells() const;

    /** Number of vertices (points). */
    unsigned int
    n_vertices() const;

    /** Reference volume of the body. */
    double
    volume() const;

    /** Total mass. */
    double
    mass() const;

    /** Density (mass per unit reference volume). */
    double
    density() const;

    /** The lumped mass of point @p i. */
    double
    point_mass(const unsigned int i) const;

    /** The reference (undeformed) configuration: q = X. */
    Vector
    reference_configuration() const;

    /** The index of the point nearest to @p X in the reference configuration.
     */
    unsigned int
    closest_point(const std::array<double, 3> &X) const;

    /**
     * The velocity field of a rigid motion, v_i = v0 + omega x (x_i - centre),
     * evaluated at the positions @p q (e.g. reference_configuration()).
     */
    Vector
    rigid_velocity(const Vector                &q,
                   const std::array<double, 3> &v0,
                   const std::array<double, 3> &omega,
                   const std::array<double, 3> &centre) const;

    /** The material. */
    const Material &
    material() const;

    /** The precomputed per-cell data of the hot loops: of every cell, but
     * in a run on several MPI ranks of the cells this rank computes (see
     * P1CellData::chunk_start). */
    const P1CellData &
    cell_data() const;

    /**
     * The data of every cell: cell_data() if it holds them all, else (on
     * several MPI ranks) gathered from the ranks on the first call, which is
     * then collective. For what needs every cell on every rank: the Hessian
     * of the implicit methods.
     */
    const P1CellData &
    every_cell_data() const;

    /** @name One body seen as ElasticBodies (for field output). @{ */
    unsigned int
    n_bodies() const override;

    const ElasticBody &
    body(const unsigned int b) const override;

    void
    body_state(const Vector      &q,
               const Vector      &v,
               const unsigned int b,
               Vector            &q_b,
               Vector            &v_b) const override;
    /** @} */

    /**
     * The Cauchy stress of the cells @p cells at the configuration @p q, for
     * output: @p cauchy holds 9 entries per cell (row-major), sigma = f'(J) I
     * + c/J F F^T (from P = f'(J) J F^-T + c F), and @p von_mises the von
     * Mises stress (3/2 s:s)^(1/2) of its deviator s, for cells.begin,
     * cells.begin + 1, ... Every cell must have J > 0. On several ranks,
     * cells that this rank does not hold need every_cell_data() first.
     */
    void
    cell_stresses(const Vector        &q,
                  const BlockRange     cells,
                  std::vector<double> &cauchy,
                  std::vector<double> &von_mises) const;

    /**
     * Per-cell fields of the cells @p cells at the configuration @p q, for
     * output: the volume ratio J = det F and the strain energy density W(F) -
     * W(I) (energy per unit reference volume; +infinity where J <= 0). On
     * several ranks, cells that this rank does not hold need
     * every_cell_data() first.
     */
    void
    cell_fields(const Vector        &q,
                const BlockRange     cells,
                std::vector<double> &J,
                std::vector<double> &energy_density) const;

    /**
     * Track the point nearest to @p X (reference coordinates) in the history:
     * its current position becomes the observables @p name_x, @p name_y,
     * @p name_z.
     */
    void
    track_point(const std::string &name, const std::array<double, 3> &X);

    /** The lower and upper corners of the smallest box with faces normal to
     * the axes that holds the reference configuration. */
    std::pair<std::array<double, 3>, std::array<double, 3>>
    reference_bounding_box() const;

    /** The tracked points' current coordinates: "<name>_x", "<name>_y", ... */
    std::vector<std::string>
    observable_names() const override;

    std::vector<double>
    observables(const Vector &q, const Vector &v) const override;

  private:
    std::string                     body_name;
    std::shared_ptr<const Material> body_material;
    P1CellData                      data;
    Vector                          inv_mass;
    /** Scratch of energy(): J per cell. */
    mutable std::vector<double> scratch_J;
    /** Positions with one padding entry (the lane kernels read four doubles
     * per point). */
    mutable std::vector<double> scratch_positions;
    /**
     * How gradient() is shared. The blocks of cells are divided among the MPI
     * ranks (rank_blocks()), and each rank's among its threads in as many
     * contiguous parts. A point belongs to the part whose blocks hold its
     * first cell; the part computes its points' gradient with the serial
     * loop's scatter over every cell that touches them (its own and, at its
     * end, a few of the next part's), in their order. The scatter adds each
     * point's forces in the serial order, so every part gives its points the
     * bits of the serial loop, however the points are divided. Each rank then
     * sends its points' gradient to every rank. Built for the numbers of
     * threads and ranks of the first gradient, and again when they change.
     */
    struct GradientParts
    {
      GradientParts() = default;
      GradientParts(const P1CellData &data, const unsigned int threads);
      /** The numbers of threads and ranks it was built for. */
      unsigned int threads = 0, ranks = 0;
      /** The points of each rank in increasing order, rank after rank, how
       * many points each rank has, and where this rank's points start. */
      std::vector<unsigned int> points, points_per_rank;
      unsigned int              first = 0;
      /** Whether points is 0, 1, 2, ...: then each rank's gradient is
       * computed, and gathered, in place. */
      bool in_order = false;
      struct Part
      {
        /** Its points, as positions among this rank's points. */
        std::vector<unsigned int> positions;
        /** The cells whose forces its points need: runs of whole chunks
         * (P1CellData::gradient_chunk), in increasing order. */
        std::vector<BlockRange> cells;
        /** The points these cells touch lie in [lowest, highest]. */
        unsigned int lowest = 0, highest = 0;
      };
      std::vector<Part> parts;
      /** On several ranks, the coordinates this rank's cells read (see
       * coordinates_read()) and those it keeps current (see
       * kept_coordinates()). */
      std::vector<char>       read;
      std::vector<BlockRange> kept;
      /** The coordinates of this rank's points, in the order of its
       * points' gradient (as gradient_of_own_points() lists them). */
      std::vector<dealii::types::global_dof_index> owned;
    };
    mutable GradientParts gradient_parts;
    /** The gradient parts for the current numbers of threads and ranks. */
    const GradientParts &
    current_gradient_parts() const;
    /** Every rank's points' values, each rank's @p own (3 per point, in
     * the order of its points), into @p x on every rank. Collective. */
    void
    gather_own_points(const double *own, Vector &x) const;
    /** Sends the gradient of kept_gradient() to the ranks that keep the
     * points (built on the first call on several ranks; the ranks are those
     * of MPI_COMM_WORLD, whatever the number of threads). */
    mutable std::unique_ptr<GhostExchange> ghost_exchange;
    /** Per part, the forces its scatter adds up (only [lowest, highest]
     * used); this rank's points' gradient, where not in place. */
    mutable std::vector<std::vector<double>> part_forces;
    mutable std::vector<double>              scratch_mine, scratch_all;
    /** every_cell_data() on several ranks, once gathered. */
    mutable std::unique_ptr<P1CellData> gathered_cells;

    /** The data that holds @p cells: cell_data(), or every_cell_data() if
     * already gathered. */
    const P1CellData &
    data_of(const BlockRange cells) const;
    /** Tracked points: name and point index. */
    std::vector<std::pair<std::string, unsigned int>> tracked_points;
  };
} // namespace estep

#endif
