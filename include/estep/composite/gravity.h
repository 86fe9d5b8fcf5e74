#ifndef estep_composite_gravity_h
#define estep_composite_gravity_h

#include <estep/composite/system_decorator.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace estep
{
  /**
   * A system under a uniform gravitational acceleration g: the base system
   * plus the potential of the weights of its points,
   * @f[ V(q) = V_{base}(q) - \sum_p m_p \, g \cdot x_p
   *         = V_{base}(q) - \sum_i w_i q_i, \qquad w_i = m_i g_{c(i)}, @f]
   * with the lumped masses m_i = 1 / inverse_mass()[i] of the base and c(i) =
   * i mod spatial_dimension() the component of coordinate i (the coordinates
   * are point positions, point-major). The weights w_i are computed once, in
   * the constructor.
   *
   * - energy(): V_base plus the linear term, summed with a compensated dot
   *   product (Ogita, Rump and Oishi's Dot2), so that the linear term is
   *   within a few units of round-off of sum_i |w_i q_i| whatever the number
   *   of points; V_base itself where that is not finite.
   * - gradient(): the base's minus w. The Hessian is the base's (inherited).
   * - free_flight(): the base's flight plus c0 + c1 s, c0 = -w . q and c1 =
   *   -w . v (both compensated); see there.
   * - observables: the base's, then "gravitational_potential" (the linear
   *   term alone, gravitational_potential()).
   *
   * A point of infinite mass (inverse mass 0) has no weight in a component
   * where g is zero; elsewhere the constructor refuses it. Points named
   * weightless have no weight at all, whatever their mass (the points of a
   * rigid obstacle surface, whose mass is a placeholder).
   *
   * As thread-safe as the base (the decorator itself keeps no scratch).
   */
  class Gravity : public SystemDecorator
  {
  public:
    /**
     * The system @p base under the acceleration @p acceleration (its first
     * spatial_dimension() components; in 2D the third must be zero). Throws
     * std::invalid_argument for a non-finite acceleration, a 2D system with
     * a third component, or a point with a non-positive or non-finite inverse
     * mass in a component where g is not zero. The points
     * @p weightless_points (indices of points, not of coordinates) have no
     * weight.
     */
    Gravity(std::shared_ptr<const MechanicalSystem> base,
            const std::array<double, 3>            &acceleration,
            const std::vector<unsigned int>        &weightless_points = {});

    /** The gravitational acceleration g (zero third component in 2D). */
    const std::array<double, 3> &
    acceleration() const;

    /** The weights w_i = m_i g_{c(i)}, one per coordinate: minus the
     * gradient of the gravitational potential. */
    const Vector &
    weights() const;

    /** The gravitational potential alone, -sum_i w_i q_i (compensated_dot()
     * of every coordinate of @p q; not collective). */
    double
    gravitational_potential(const Vector &q) const;

    /** V_base(q) + gravitational_potential(q); V_base(q) itself where it is not
     * finite. */
    double
    energy(const Vector &q) const override;

    /** grad V_base(q) - w. */
    void
    gradient(const Vector &q, Vector &g) const override;

    /** The base's kept gradient minus w at the kept coordinates: gravity
     * shares the state as the base shares it, since the weights' part of V
     * and of a flight is a sum over the blocks of coordinates (as
     * compensated_dot() takes it), of which each rank computes its own. */
    void
    kept_gradient(const Vector &q, Vector &g) const override;

    /**
     * The base's flight plus the linear term l(s) = c0 + c1 s, c0 = -w . q,
     * c1 = -w . v, computed once per flight (compensated dot products) and
     * evaluated with one rounding (a fused multiply-add).
     *
     * Enclosures over [a, b]: the base's plus the hull of l(a) and l(b)
     * (the computed l is monotone in s), widened by the rounding of l; the
     * slope enclosure is the base's shifted by c1. Where the base reports a
     * sample in [a, b], both are intersected with the first-order form of
     * the sum about it (LineTaylorForm::from_enclosure() of the base plus the
     * exact form of l), whose value range follows the slope of the sum, so
     * that the enclosure stays narrow where the base's slope cancels the
     * weight's (a body resting on a support). The curvature is the base's
     * (l'' = 0); the sample is the base's sample point with the sum's value
     * and slope there, as value_and_derivative() computes them.
     *
     * value_tolerance(): the base's plus 8 units of round-off (epsilon) of
     * sum_i |w_i q_i|: the flight's l(s) and the linear term of energy() at q
     * + s v each lie within about one unit of round-off of that sum of the
     * exact -w . (q + s v) near s = 0.
     */
    std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const override;

    /** The base's names, then "gravitational_potential". */
    std::vector<std::string>
    observable_names() const override;

    /** The base's values, then gravitational_potential(q). */
    std::vector<double>
    observables(const Vector &q, const Vector &v) const override;

  private:
    std::array<double, 3> g;
    Vector                w;
    /** The coordinates whose weights may be nonzero: those that are phase
     * modulo step (along one axis, dim and the axis; else all). */
    unsigned int step = 1, phase = 0;

    /** w . @p x as compensated_dot() computes it, with sum_i |w_i x_i| into
     * @p magnitude if given; from the kept coordinates of @p x (collective)
     * where the base shares its state. */
    double
    weighted_sum(const Vector &x, double *magnitude = nullptr) const;
  };

  /**
   * The dot product sum_i x_i y_i of two vectors of equal size, computed as in
   * twice the working precision and then rounded (Dot2 of Ogita, Rump and
   * Oishi, 2005; in blocks of block_size coordinates, on the threads, the
   * blocks' running sums joined in block order by the same error-free
   * sums, so the bits do not depend on the threads): its error is at most one
   * unit of round-off of the result plus gamma_n^2 sum_i |x_i y_i| (gamma_n = n
   * u / (1 - n u), u the unit round-off), below one unit of round-off of sum_i
   * |x_i y_i| for n up to 10^7. Optionally, @p magnitude receives sum_i |x_i
   * y_i| (plainly summed).
   */
  double
  compensated_dot(const Vector &x,
                  const Vector &y,
                  double       *magnitude = nullptr);
} // namespace estep

#endif
