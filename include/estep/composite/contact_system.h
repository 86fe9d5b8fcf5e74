#ifndef estep_composite_contact_system_h
#define estep_composite_contact_system_h

#include <estep/composite/contact_parameters.h>
#include <estep/composite/static_surface.h>
#include <estep/contact/bounding_volume_hierarchy.h>
#include <estep/fem/elastic_bodies.h>
#include <estep/systems/mechanical_system.h>
#include <estep/systems/rigid_body_motion.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace estep
{
  class ElasticBody;

  namespace contact
  {
    class PenaltyContact;
  } // namespace contact

  /**
   * Several elastic bodies with contact between their boundaries, as one
   * MechanicalSystem.
   *
   * Coordinates: the points of all bodies concatenated, point-major; body b's
   * points follow its own numbering (ElasticBody) shifted by point_offset(b),
   * the sum of the point counts of the earlier bodies. The inverse mass is the
   * concatenation of the bodies' lumped inverse masses.
   *
   * Potential: V(q) = sum_b V_b(q_b) + I(q), with I the contact term:
   * - ContactParameters::Mode::penalty: I = 1/(2 eps) sum g over pairs of
   *   boundary triangles (contact::PenaltyContact), g = |A - B|^2 of their
   *   intersection segment; the free flight adds contact::PenaltyFlight with
   *   rigorous enclosures of I and dI/ds;
   * - impenetrability: I = 0 and first_constraint_event() reports the first
   *   vertex-face or edge-edge contact along a flight
   *   (contact::find_first_contact()) with the gradient of the contact
   *   distance as the normal;
   * - none: I = 0.
   * Pairs of triangles of the same body count only with self-contact on, and
   * never when they share a vertex.
   *
   * Static surfaces (rigid obstacles, StaticSurface): their points follow the
   * bodies' points (surface s from surface_point_offset(s)), with inverse
   * mass 1 so that the system stays well formed; they contribute no energy
   * of their own, and their triangles join the contact triangles after the
   * bodies' ones. All surfaces form one exclusion group: a surface never
   * contacts itself or another surface, only the bodies. The system does not
   * hold them in place: a user fixes surface_points() (SupportedSystem), so
   * that they have velocity zero in every flight and the penalty term and
   * the collision detection treat body-surface contact as any other.
   * Everything that describes the bodies (n_bodies(), body_motion(),
   * system_motion(), the rigid-motion observables, extract()) ignores the
   * surface points.
   *
   * The boundary triangles are each body's (P1CellData::boundary_triangle),
   * in the composite's point numbers.
   *
   * Not thread-safe (caches in the bodies and the contact term).
   */
  class ContactSystem : public MechanicalSystem, public ElasticBodies
  {
  public:
    /**
     * The system of @p bodies (at least one) interacting as @p parameters say.
     * Throws std::invalid_argument for an empty list or a bad parameter.
     */
    ContactSystem(std::vector<std::shared_ptr<const ElasticBody>> bodies,
                  const ContactParameters                        &parameters,
                  const std::string &name = "contact system");

    /**
     * The system of @p bodies (at least one) and the static @p surfaces
     * (checked with StaticSurface::check()) interacting as @p parameters say.
     * Throws std::invalid_argument for an empty list of bodies or a bad
     * parameter, std::runtime_error for a bad surface.
     */
    ContactSystem(std::vector<std::shared_ptr<const ElasticBody>> bodies,
                  std::vector<StaticSurface>                      surfaces,
                  const ContactParameters                        &parameters,
                  const std::string &name = "contact system");

    ~ContactSystem() override;

    std::string
    name() const override;

    /** Always 3. */
    unsigned int
    spatial_dimension() const override;

    unsigned int
    n_dofs() const override;

    const Vector &
    inverse_mass() const override;

    /** Sum of the body energies plus the contact term; +infinity if a body
     * is inadmissible. */
    double
    energy(const Vector &q) const override;

    void
    gradient(const Vector &q, Vector &g) const override;

    /**
     * @name The state shared among MPI ranks
     * On several ranks each keeps current the coordinates its bodies' cells
     * read (ElasticBody::coordinates_read()), every point of a boundary
     * triangle (the contact terms, the collision detection and the checks of
     * penetration read them on every rank alike) and its blocks of
     * coordinates. The bodies' gradient at a kept point that another rank
     * computes comes from that rank (GhostExchange); then every rank adds
     * the contact's part, at the boundary points. See MechanicalSystem.
     * @{
     */
    const std::vector<BlockRange> *
    kept_coordinates() const override;

    void
    kept_gradient(const Vector &q, Vector &g) const override;

    void
    complete_state(Vector &x) const override;
    /** @} */

    /**
     * Sum of the bodies' ElasticFreeFlight and, in penalty mode, the
     * PenaltyFlight. Enclosures: one second-order form of the sum about the
     * interval's centre (values and slopes of the parts added at the centre,
     * then the intervals; see LineTaylorForm), intersected with the sum of
     * the parts' enclosures; with the sum of the parts' bounds on V'' (where
     * every part has one: the bodies', the penalty's without a kink) and V,
     * V' at the interval's centre as the sample. value_tolerance(): the sum
     * of the parts'.
     */
    std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const override;

    /** Impenetrability mode: the first contact along q + s v, 0 <= s <=
     * s_max (see contact::find_first_contact() for the rule at s = 0). None
     * in the other modes. */
    std::optional<ConstraintEvent>
    first_constraint_event(const Vector &q,
                           const Vector &v,
                           const double  s_max) const override;

    /** Impenetrability mode: the pairs of contact::touching_contacts(). None
     * in the other modes. */
    std::vector<SparseNormal>
    touching_constraints(const Vector &q) const override;

    /** True in impenetrability mode. */
    bool
    has_constraints() const override;

    /**
     * For each body b = 1, 2, ...: "V<b>_x", "V<b>_y", "V<b>_z" (centre-of-mass
     * velocity) and "Omega<b>_x", ... (angular momentum about its centre of
     * mass / its mass); then "V_x", ..., "Omega_x", ... of the whole system
     * (about the system's centre of mass), "intersecting_pairs" (number
     * of intersecting pairs of boundary triangles, exact test), and the
     * bodies' own observables (e.g. tracked points).
     */
    std::vector<std::string>
    observable_names() const override;

    /** The values named by observable_names(). */
    std::vector<double>
    observables(const Vector &q, const Vector &v) const override;

    /** Number of bodies. */
    unsigned int
    n_bodies() const override;

    /** Body @p b. */
    const ElasticBody &
    body(const unsigned int b) const override;

    /** extract() of @p q and @p v. */
    void
    body_state(const Vector      &q,
               const Vector      &v,
               const unsigned int b,
               Vector            &q_b,
               Vector            &v_b) const override;

    /** The global number of body @p b's first point. */
    unsigned int
    point_offset(const unsigned int b) const;

    /** The body of point @p point (a global number below n_body_points()). */
    unsigned int
    body_of_point(const unsigned int point) const;

    /** Number of points of all bodies (the surfaces' points come after). */
    unsigned int
    n_body_points() const;

    /** Number of static surfaces. */
    unsigned int
    n_surfaces() const;

    /** Static surface @p s. */
    const StaticSurface &
    surface(const unsigned int s) const;

    /** The global number of surface @p s's first point. */
    unsigned int
    surface_point_offset(const unsigned int s) const;

    /** The global numbers of all surface points (increasing): the points a
     * user holds fixed. */
    std::vector<unsigned int>
    surface_points() const;

    /** The global configuration made of one vector per body (sizes as the
     * bodies' n_dofs()) followed by the surfaces' points. */
    Vector
    concatenate(const std::vector<Vector> &per_body) const;

    /** The global velocity made of one vector per body (sizes as the bodies'
     * n_dofs()), zero on the surfaces' points. */
    Vector
    concatenate_velocities(const std::vector<Vector> &per_body) const;

    /** Body @p b's part of the global vector @p x. */
    Vector
    extract(const Vector &x, const unsigned int b) const;

    /** The boundary triangles of all bodies, then the triangles of the
     * surfaces, in global point numbers. */
    const std::vector<contact::TriangleIndices> &
    boundary_triangles() const;

    /** The body of each boundary triangle; n_bodies() + s for the triangles
     * of surface s. */
    const std::vector<unsigned int> &
    triangle_bodies() const;

    /** The contact parameters. */
    const ContactParameters &
    parameters() const;

    /** The contact term I(q) alone (0 unless in penalty mode). */
    double
    contact_energy(const Vector &q) const;

    /**
     * Number of pairs of boundary triangles that intersect at q (exact test,
     * contact::triangles_intersect(); pairs sharing a vertex excluded, pairs
     * of one body only with self-contact), whatever the mode.
     */
    unsigned int
    n_intersecting_pairs(const Vector &q) const;

    /** The pairs of boundary triangles (indices into boundary_triangles())
     * that intersect at q, as n_intersecting_pairs() counts them, in
     * increasing order. */
    std::vector<std::pair<unsigned int, unsigned int>>
    intersecting_pairs(const Vector &q) const;

    /** Two bodies whose boundaries meet: some pair of their triangles
     * intersects. */
    struct Meeting
    {
      /** The bodies, first <= second; second = n_bodies() + s for surface
       * s. */
      unsigned int first, second;
      /** Whether a pair of their intersecting triangles crosses, not only
       * touches (contact::triangles_cross()). */
      bool crossing;
    };

    /** The pairs of bodies whose boundaries meet at q, in increasing order. */
    std::vector<Meeting>
    meeting_bodies(const Vector &q) const;

    /** For a configuration whose boundaries do not cross (no crossing
     * meeting_bodies()): the first body or surface (numbered as there) of which
     * a connected piece of the boundary lies wholly inside a body, and that
     * body. Where a piece lies in the box of that body, its vertices are
     * tested in turn until one lies off the body's boundary (further than
     * 1e-9 of the box's diagonal): the piece is inside if that vertex's
     * winding number exceeds 1/2. A piece all of whose vertices lie on
     * the body's boundary is not inside. */
    std::optional<std::pair<unsigned int, unsigned int>>
    nested_bodies(const Vector &q) const;

    /** A boundary point of one body found deep inside another. */
    struct Penetration
    {
      /** The body the point belongs to and the body it is inside. */
      unsigned int body, other_body;
      /** The point's global number. */
      unsigned int point;
      /** Its distance from the other body's boundary, and the length it
       * exceeds (penetration_limit() of the two bodies). */
      double depth, limit;
    };

    /**
     * The longest boundary edge of bodies @p b1 and @p b2 in their reference
     * configurations: the depth beyond which deep_penetration() reports a
     * point of one inside the other.
     */
    double
    penetration_limit(const unsigned int b1, const unsigned int b2) const;

    /**
     * A boundary point of one body that lies inside another body (the
     * winding number of the other's boundary about it exceeds 1/2) farther
     * from the other's boundary than penetration_limit(): the bodies have
     * passed into each other by more than an element, which no contact mode
     * lets them do when it works (a penalty keeps the penetration far below
     * the mesh size, the exact mode at zero). The first such point found, if
     * any. Static surfaces have no inside and are not checked; neither is a
     * body against itself. Only points inside the other body's bounding box
     * shrunk by the limit are located (distance, then winding number), and
     * only of bodies whose own box reaches into that shrunk box, so that the
     * check costs a box test per pair of bodies as long as no body reaches
     * that deep into another's box.
     */
    std::optional<Penetration>
    deep_penetration(const Vector &q) const;

    /** deep_penetration() in one sentence, naming the bodies, the depth and,
     * in penalty mode, the penalty parameter; empty if there is none. */
    std::string
    penetration(const Vector &q) const override;

    /** In penalty mode l^2 / (2 eps), l the longest boundary edge of all
     * bodies in their reference configurations; +infinity otherwise. */
    double
    penalty_energy_scale() const override;

    /** Rigid motion of body @p b at (q, v). */
    RigidBodyMotion
    body_motion(const Vector &q, const Vector &v, const unsigned int b) const;

    /** Rigid motion of all bodies together at (q, v) (surfaces
     * excluded). */
    RigidBodyMotion
    system_motion(const Vector &q, const Vector &v) const;

  private:
    std::string                                     system_name;
    std::vector<std::shared_ptr<const ElasticBody>> bodies;
    std::vector<StaticSurface>                      surfaces;
    ContactParameters                               contact_parameters;
    /** The first point of each body, then of each surface, then the total
     * number of points. */
    std::vector<unsigned int>                offsets;
    Vector                                   inv_mass;
    std::vector<contact::TriangleIndices>    triangles;
    std::vector<unsigned int>                triangle_body;
    std::vector<unsigned int>                exclusion_groups;
    std::unique_ptr<contact::PenaltyContact> penalty;
    /** The swept broad phase of impenetrable contact
     * (first_constraint_event()) and the static one of intersecting_pairs(),
     * which runs after every step (the contact monitor): kept from call to
     * call and refitted, built anew every 64 refits. */
    mutable contact::BoundingVolumeHierarchy ccd_tree, intersection_tree;
    /** Per body: its boundary points (global numbers), its boundary
     * triangles (indices into triangles) and its longest boundary edge in
     * the reference configuration. */
    std::vector<std::vector<unsigned int>> boundary_points, body_triangles;
    std::vector<double>                    longest_boundary_edge;
    mutable std::vector<Vector>            scratch_q, scratch_g;

    /** What kept_gradient() needs on several ranks (see there): the kept
     * coordinates, the coordinates of the bodies' own points (body after
     * body, each in the order of ElasticBody::gradient_of_own_points())
     * with where each body's start, and their exchange. */
    struct SharedState;
    mutable std::unique_ptr<SharedState> shared_state;
    /** The shared state for the current number of ranks. */
    SharedState &
    current_shared_state() const;

    /** The box of each body's boundary points at @p x. */
    std::vector<contact::BoundingBox>
    body_boxes(const double *x) const;
  };
} // namespace estep

#endif
