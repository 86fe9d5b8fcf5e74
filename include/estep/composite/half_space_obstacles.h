#ifndef estep_composite_half_space_obstacles_h
#define estep_composite_half_space_obstacles_h

#include <estep/composite/system_decorator.h>

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace estep
{
  class ContactSystem;

  /**
   * A rigid half-space obstacle: the body must stay where n . (x - p) >= 0;
   * the obstacle fills the rest of space. In 2D only the first two components
   * are used (the third must be 0).
   */
  struct HalfSpace
  {
    /** A point p on the boundary plane. */
    std::array<double, 3> point = {{0., 0., 0.}};
    /** The outward unit normal n of the obstacle (pointing into the free
     * region); HalfSpaceObstacles normalises it. */
    std::array<double, 3> normal = {{0., 0., 1.}};
  };

  /**
   * A MechanicalSystem with rigid, frictionless half-space obstacles added to
   * a base system (a SystemDecorator): some points of the base (the boundary
   * vertices of its bodies) must stay in front of every plane, at signed
   * distance d = n . (x - p) >= 0.
   *
   * Modes:
   * - Mode::impenetrability: V is the base's; first_constraint_event() adds
   *   the first point reaching a plane while moving into it (an energy step
   *   of infinite height: energy-stepping reflects the point's velocity on
   *   the plane's normal), see there;
   * - Mode::penalty with parameter eps > 0: V = V_base + I with
   *   I = 1/(2 eps) sum over points and planes of max(0, -d)^2, a convex
   *   C^1 term that is piecewise quadratic along a flight; the free flight,
   *   the gradient and (if the base has one) the Hessian include it.
   *
   * Round-off. d is always evaluated as signed_distance() does, from the
   * point's coordinates; the "touching band" of a point and plane is 16
   * units of round-off of that evaluation, touching_band() (sum |n_c| times
   * the largest magnitude of the point's and p's coordinates). Reflections
   * happen with the point at least one band in front of the plane, so that
   * the round-off of the next flights cannot put it behind.
   *
   * The points are sorted and duplicates removed. Not thread-safe if the base
   * is not.
   */
  class HalfSpaceObstacles : public SystemDecorator
  {
  public:
    /** How the obstacles act. */
    enum class Mode
    {
      /** Exact: constraint events (reflections) at the planes. */
      impenetrability,
      /** The penalty energy 1/(2 eps) sum max(0, -d)^2. */
      penalty
    };

    /**
     * The obstacles @p half_spaces acting on the points @p points (indices
     * of points of @p base, i.e. coordinates dim * i ... dim * i + dim - 1)
     * in @p mode; @p penalty_parameter is eps (penalty mode only, > 0);
     * @p penetration_limit the depth behind a plane at which penetration()
     * reports a point (infinite: never).
     * Throws std::invalid_argument for a zero or non-finite normal, a point
     * out of range, a base whose n_dofs() is not a multiple of its spatial
     * dimension, or a bad penalty parameter.
     */
    HalfSpaceObstacles(
      std::shared_ptr<const MechanicalSystem> base,
      std::vector<HalfSpace>                  half_spaces,
      std::vector<unsigned int>               points,
      const Mode                              mode,
      const double                            penalty_parameter = 0.,
      const double penetration_limit = std::numeric_limits<double>::infinity());

    ~HalfSpaceObstacles() override;

    /** The base's energy, plus I in penalty mode (+infinity if the base's
     * is). */
    double
    energy(const Vector &q) const override;

    /** The base's gradient, plus grad I = d / eps n on each point behind a
     * plane (penalty mode). */
    void
    gradient(const Vector &q, Vector &g) const override;

    /** The base's kept gradient plus grad I at the contact points. The
     * state is shared among MPI ranks as the base shares it where every rank
     * keeps every contact point (a ContactSystem's bodies keep their
     * boundaries), since the obstacles read those alone; else every
     * coordinate is kept. Decided when constructed (collective). */
    void
    kept_gradient(const Vector &q, Vector &g) const override;

    /**
     * Impenetrability mode: the base's flight. Penalty mode: the base's
     * flight plus I along the line, d_p(s) = d_p(0) + s n . v_p for each
     * point and plane (d_p(0) and the rate computed once, with a bound on
     * their round-off). Each pair contributes a piecewise quadratic in s:
     * its value and slope are monotone over any interval, so their exact
     * ranges follow from the ends (widened by the round-off bounds); its
     * curvature is (n . v)^2 / eps where the point is behind and 0 where it
     * is not, enclosed by [0, (n . v)^2 / eps] where it may penetrate
     * somewhere in the interval, by the upper value alone where it surely
     * penetrates everywhere, and by 0 where it surely does not. The
     * enclosure over [a, b]: the base's if no pair may penetrate there;
     * otherwise one second-order form about the centre (the base's
     * first-order form from its enclosure plus each pair's second-order
     * form, see LineTaylorForm), intersected with the sum of the parts'
     * ranges, with the sum of the parts' curvature bounds and V, V' at the
     * centre as the sample. value_tolerance(): the base's plus a bound on
     * the round-off of I at s = 0.
     */
    std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const override;

    /**
     * The earliest of the base's event and the first obstacle contact on the
     * flight q + s v, 0 <= s <= s_max (impenetrability mode; the base's
     * alone in penalty mode). An obstacle contact is a point reaching a
     * plane while moving into it (n . v_p < 0); its normal is n on that
     * point's coordinates (0 elsewhere). Conservative in floating point: the
     * reported s is the computed crossing s = d / (-n . v_p) stepped down
     * (std::nextafter, the step doubling after each try) until the point at
     * q + s v, computed as the integrator computes it, lies at least
     * touching_band() in front of the plane (both with and without a fused
     * multiply-add); a point whose crossing lies beyond s_max but that would
     * end there closer than the band is reported the same way from s_max.
     *
     * The rule at s = 0 (as the base contact's, at round-off scale): a point
     * moving into a plane and closer to it than 4 touching bands (on it, or
     * behind it) is a contact at s = 0; after its reflection it moves out and
     * is no longer one, so energy-stepping resolves simultaneous contacts
     * one by one at the same instant without looping. A point moving out of
     * a plane or parallel to it is never a contact, even behind it.
     */
    std::optional<ConstraintEvent>
    first_constraint_event(const Vector &q,
                           const Vector &v,
                           const double  s_max) const override;

    /** The base's touching constraints, and in impenetrability mode every
     * contact point within 4 touching bands of a plane, or behind it. */
    std::vector<SparseNormal>
    touching_constraints(const Vector &q) const override;

    /** True in impenetrability mode, and if the base has constraints. */
    bool
    has_constraints() const override;

    /** The base's Hessian plus n n^T / eps on the diagonal block of each
     * point behind a plane (penalty mode). Throws std::logic_error if the
     * base's sparsity pattern lacks an entry of such a block. */
    void
    hessian(const Vector &q, dealii::SparseMatrix<double> &H) const override;

    /** The base's penetration(), else a point deeper behind a plane than
     * the penetration limit of the constructor: a penalty too soft to hold
     * the bodies out of the obstacle. */
    std::string
    penetration(const Vector &q) const override;

    /** The base's names and "points_behind_obstacles". */
    std::vector<std::string>
    observable_names() const override;

    /** The base's values and n_points_behind(q). */
    std::vector<double>
    observables(const Vector &q, const Vector &v) const override;

    /** The mode. */
    Mode
    mode() const;

    /** The penalty parameter eps (0 in impenetrability mode). */
    double
    penalty_parameter() const;

    /** The half-spaces, with normalised normals. */
    const std::vector<HalfSpace> &
    half_spaces() const;

    /** The points that can touch the obstacles, sorted. */
    const std::vector<unsigned int> &
    points() const;

    /** Signed distance n . (x - p) of point @p point of @p q from the plane
     * of half-space @p k, as every function of this class computes it. */
    double
    signed_distance(const Vector      &q,
                    const unsigned int point,
                    const unsigned int k) const;

    /** The touching band of point @p point of @p q and half-space @p k: 16
     * units of round-off of signed_distance() (see the class). */
    double
    touching_band(const Vector      &q,
                  const unsigned int point,
                  const unsigned int k) const;

    /** Number of points behind at least one plane (d < 0) at @p q. */
    unsigned int
    n_points_behind(const Vector &q) const;

    /** A point behind a plane: the point, the half-space (from 0) and the
     * depth -d. */
    struct PointBehind
    {
      unsigned int point, half_space;
      double       depth;
    };

    /** The first of points() (in their order, each against the half-spaces
     * in theirs) deeper than @p depth behind a plane at @p q, if any. */
    std::optional<PointBehind>
    first_point_deeper_than(const Vector &q, const double depth) const;

    /** The largest depth -d of a point behind a plane at @p q (0 if none). */
    double
    max_penetration(const Vector &q) const;

    /** The penalty term I(q) alone (0 in impenetrability mode). */
    double
    obstacle_energy(const Vector &q) const;

  private:
    std::vector<HalfSpace>    planes;
    std::vector<unsigned int> contact_points;
    Mode                      obstacle_mode;
    double                    eps;
    double                    depth_limit;
    unsigned int              dim;

    /** Add grad I at the contact points to @p g (penalty mode). */
    void
    add_obstacle_gradient(const Vector &q, Vector &g) const;
  };

  /** The points of the bodies' boundary triangles of @p system (every
   * body's boundary vertices, in global point numbers; not the static
   * surfaces' points), sorted. */
  std::vector<unsigned int>
  boundary_points(const ContactSystem &system);
} // namespace estep

#endif
