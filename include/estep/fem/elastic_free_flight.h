#ifndef estep_fem_elastic_free_flight_h
#define estep_fem_elastic_free_flight_h

#include <estep/systems/free_flight.h>
#include <estep/systems/mechanical_system.h>

#include <array>
#include <vector>

namespace estep
{
  class ElasticBody;

  /**
   * The energy of an ElasticBody along the free flight q + s v, s >= 0.
   *
   * On each P1 cell the deformation gradient is linear in s, F_e(s) = F_e + s
   * G_e, so J_e(s) = det F_e(s) = c0 + c1 s + c2 s^2 + c3 s^3 with c0 = det
   * F_e, c1 = cof F_e : G_e, c2 = cof G_e : F_e, c3 = det G_e, and the
   * quadratic parts of the material add up to one global quadratic Q(s) = c/2
   * sum_e |Omega_e| |F_e(s)|^2 - W_0 |Omega|. The constructor computes the four
   * cubic coefficients per cell and Q; then f(s) = Q(s) + sum_e |Omega_e|
   * f_vol(J_e(s)) costs one cubic per cell plus the material's batch kernel (a
   * vectorised log for neo-Hookean).
   *
   * enclose(a, b): per cell the exact range of the cubic J_e over [a, b] (ends
   * and the critical points inside, precomputed on first use) and of its
   * derivative, widened by the rounding bound 16 u (|c0| + |c1| S + |c2| S^2 +
   * |c3| S^3), S = max(|a|, |b|); then the material's rigorous enclosure of the
   * volumetric sum and the exact range of Q.
   *
   * admissible_limit(): the smallest positive root over cells of J_e(s),
   * computed from below (see the implementation: monotone pieces between
   * critical points, bisection keeping a point where J_e exceeds its rounding
   * bound), cached on first call.
   *
   * Not thread-safe (mutable scratch arrays). The body must outlive this
   * object.
   */
  class ElasticFreeFlight : public FreeFlight
  {
  public:
    /** The flight of @p body from positions @p q with velocity @p v (q
     * admissible). */
    ElasticFreeFlight(const ElasticBody &body,
                      const Vector      &q,
                      const Vector      &v);

    double
    value(const double s) const override;

    LineValue
    value_and_derivative(const double s) const override;

    LineEnclosure
    enclose(const double a, const double b) const override;

    double
    admissible_limit() const override;

    /** 64 units of round-off of the sum of the magnitudes of the energy
     * terms at s = 0. */
    double
    value_tolerance() const override;

    /** The cubic coefficients c_k of J_e(s) of cell @p e. */
    std::array<double, 4>
    jacobian_cubic(const unsigned int e) const;

    /** The coefficients (Q0, Q1, Q2) of the global quadratic Q(s). */
    std::array<double, 3>
    quadratic_part() const;

  private:
    void
    compute_critical_points() const;

    /** Intersect @p enclosure of [a, b] with the second-order Taylor form
     * about the midpoint, where @p fm holds f and f' (needs the per-cell J
     * and J' ranges of [a, b] in the scratch arrays). */
    void
    tighten_by_taylor_form(const double     a,
                           const double     b,
                           const LineValue &fm,
                           LineEnclosure   &enclosure) const;

    const ElasticBody  &body;
    unsigned int        n_cells;
    std::vector<double> c0, c1, c2, c3;
    double              quadratic[3];
    /** Sum of the magnitudes of the terms of V at s = 0. */
    double gross_magnitude = 0.;

    mutable bool                critical_points_ready = false;
    mutable std::vector<double> critical_1, critical_2, slope_vertex;
    mutable bool                limit_ready = false;
    mutable double              limit       = 0.;
    mutable std::vector<double> scratch_1, scratch_2, scratch_3, scratch_4,
      scratch_5, scratch_6;
  };
} // namespace estep

#endif
