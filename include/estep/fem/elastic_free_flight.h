#ifndef estep_fem_elastic_free_flight_h
#define estep_fem_elastic_free_flight_h

#include <estep/systems/free_flight.h>
#include <estep/systems/line_taylor_form.h>
#include <estep/systems/mechanical_system.h>

#include <array>
#include <memory>
#include <optional>
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
   * enclose(a, b): per cell, in one pass, J_e and J_e' at the centre m and
   * enclosures of J_e, J_e' and J_e'' over [a, b] from the exact expansion of
   * the cubic about m (widened by a rounding bound); then the second-order
   * form f(m) + f'(m) t + f''([a, b]) t^2 / 2 (a LineTaylorForm with W = 0)
   * with the material's rigorous enclosure of the volumetric part of f''; the
   * enclosure reports that curvature and f, f' at m as its sample. Where f'' is
   * unbounded (an element may invert in [a, b]), the sum of the per-cell ranges
   * of the material's volumetric term and the exact range of Q instead.
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

    /** The cubic coefficients c_k of J_e(s) of cell @p e (one this rank
     * computes). */
    std::array<double, 4>
    jacobian_cubic(const unsigned int e) const;

    /** The coefficients (Q0, Q1, Q2) of the global quadratic Q(s). */
    std::array<double, 3>
    quadratic_part() const;

  private:
    /** The volumetric part of f at @p s, summed over blocks of cells, with
     * its slope if @p slope (0 otherwise). */
    LineValue
    volumetric_part(const double s, const bool slope) const;

    /** f and f' at @p s from their @p volumetric part: the quadratic part
     * added, or (+infinity, 0) where the volumetric part is not finite. */
    LineValue
    with_quadratic_part(const double s, LineValue volumetric) const;

    /** f and f' at the centre m of @p about (into @p fm) and, in the same
     * pass over the cells, the second-order (Taylor) form about m (a form of
     * 0 about m, with its radius r) from them and the enclosure of f'' over
     * [m - r, m + r]; empty if f'' is unbounded there or f(m) is not
     * finite. */
    std::optional<LineTaylorForm>
    taylor_form(const LineTaylorForm &about, LineValue &fm) const;

    /** The sum of the per-cell ranges of f and f' over [a, b], which lies in
     * [m - half_width, m + half_width]. */
    LineEnclosure
    natural_form(const double a,
                 const double b,
                 const double m,
                 const double half_width) const;

    /** Where cell @p e is in the per-cell arrays: those of the cells the
     * body holds (P1CellData::at()). */
    unsigned int
    at(const unsigned int e) const;

    const ElasticBody &body;
    unsigned int       n_cells;
    /** The number of cells the body holds (P1CellData::volume.size()). */
    unsigned int n_held = 0;
    /** The four arrays of cubic coefficients and two scratch arrays (J and J'
     * of value() and value_and_derivative()), n_held entries each, in one
     * allocation. */
    std::unique_ptr<double[]> storage;
    double                   *c0, *c1, *c2, *c3;
    double                   *scratch;
    double                    quadratic[3];
    /** Sum of the magnitudes of the terms of V at s = 0. */
    double gross_magnitude = 0.;

    mutable bool   limit_ready = false;
    mutable double limit       = 0.;
  };
} // namespace estep

#endif
