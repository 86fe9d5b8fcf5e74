#ifndef estep_materials_material_h
#define estep_materials_material_h

#include <deal.II/base/tensor.h>

#include <estep/base/interval.h>
#include <estep/systems/free_flight.h>

#include <cstddef>
#include <string>

namespace estep
{
  /**
   * A hyperelastic material whose strain energy density (per unit reference
   * volume) has the split form
   * @f[ W(F) = f(J) + \frac{c}{2} \mathrm{tr}(F^T F) - W_0, \qquad J = \det F,
   * @f] with a volumetric function f (+infinity for J <= 0), a constant c >= 0
   * (quadratic_modulus()) and the constant W_0 = f(1) + 3c/2 that makes W(I) =
   * 0. The compressible neo-Hookean material (NeoHookean) is the standard
   * member of this family; other volumetric functions (e.g. kappa/2 (J - 1)^2 -
   * mu log J) give further ones.
   *
   * Why this form: along a free flight of P1 tetrahedra F(s) = F + s G, so J(s)
   * is a cubic and tr(F^T F)(s) a quadratic in s. The quadratic parts of all
   * elements add up to one global quadratic and only f needs per-element work.
   * ElasticBody therefore asks the material for f only, through the batch
   * functions below: one virtual call per sweep over all cells, never one per
   * cell. The defaults of the batch functions loop over the scalar virtual
   * functions (correct, slower); a material that is used for long runs
   * overrides them with tight loops (NeoHookean does, with a vectorised
   * logarithm).
   *
   * To add a material: derive from this class and implement the six pure
   * virtual functions. The range functions must be rigorous: they must contain
   * every value that volumetric_energy() and volumetric_derivative() return for
   * J in the interval, round-off included (widen the result by a few ulps when
   * in doubt).
   *
   * Units: W and f are energies per unit reference volume, c is a stress (same
   * units).
   */
  class Material
  {
  public:
    virtual ~Material() = default;

    /** A short name for output. */
    virtual std::string
    name() const = 0;

    /** The constant c of the quadratic part c/2 tr(F^T F) (mu0 for
     * neo-Hookean). */
    virtual double
    quadratic_modulus() const = 0;

    /** f(J); +infinity for J <= 0. */
    virtual double
    volumetric_energy(const double J) const = 0;

    /** f'(J) for J > 0. */
    virtual double
    volumetric_derivative(const double J) const = 0;

    /**
     * An interval holding f(J) for every J in @p J (rigorous, see the class
     * documentation). J.lower may be <= 0: then the upper bound is +infinity.
     */
    virtual Interval
    volumetric_energy_range(const Interval &J) const = 0;

    /**
     * An interval holding f'(J) for every J in @p J (rigorous). J.lower may be
     * <= 0: then the result may be unbounded.
     */
    virtual Interval
    volumetric_derivative_range(const Interval &J) const = 0;

    /**
     * An interval holding f''(J) for every J in @p J (rigorous), used for the
     * second-order (Taylor) enclosures of a free flight. The default,
     * (-infinity, infinity), means "unknown": the flight then relies on its
     * first-order enclosures alone.
     */
    virtual Interval
    volumetric_second_derivative_range(const Interval &J) const;

    /**
     * The Lame constants of the material linearised about the reference state:
     * lambda = f''(1) - c and mu = c (from P = f'(J) J F^-T + c F with f'(1) =
     * -c, which makes the reference state stress-free).
     */
    double
    small_strain_lambda() const;

    /** See small_strain_lambda(). */
    double
    small_strain_mu() const;

    /** W_0 = f(1) + 3c/2, the energy density of the undeformed state that is
     * subtracted. */
    double
    reference_energy_density() const;

    /** W(F) - W(I) for a full deformation gradient; +infinity if det F <= 0. */
    double
    energy_density(const dealii::Tensor<2, 3> &F) const;

    /** The first Piola-Kirchhoff stress P = dW/dF = f'(J) J F^-T + c F. det F
     * must be > 0. */
    dealii::Tensor<2, 3>
    first_piola_stress(const dealii::Tensor<2, 3> &F) const;

    /**
     * f''(J) for J > 0, the second derivative of the volumetric function (used
     * by the tangent stiffness of the implicit integrators). The default is a
     * central difference of volumetric_derivative() with the step 1e-5 J
     * (relative accuracy about 1e-10 for smooth f); materials override it
     * with the exact formula (NeoHookean does).
     */
    virtual double
    volumetric_second_derivative(const double J) const;

    /**
     * The first elasticity tensor A = dP/dF = d^2W/dF^2 at @p F (det F > 0):
     * @f[ A_{iIkL} = c\,\delta_{ik}\delta_{IL}
     *      + (f''(J) J^2 + f'(J) J) F^{-1}_{Ii} F^{-1}_{Lk}
     *      - f'(J) J F^{-1}_{Li} F^{-1}_{Ik}, @f]
     * stored as A[i][I][k][L]. It has the major symmetry A_iIkL = A_kLiI (W
     * is a potential).
     */
    dealii::Tensor<4, 3>
    first_elasticity_tensor(const dealii::Tensor<2, 3> &F) const;

    /**
     * @name Batch kernels: one call per sweep over all cells.
     * @{
     */

    /** Sum over i < n of w[i] f(J[i]); +infinity if any J[i] <= 0. */
    virtual double
    sum_volumetric_energy(const double     *J,
                          const double     *w,
                          const std::size_t n) const;

    /**
     * value = sum w[i] f(J[i]) and derivative = sum w[i] f'(J[i]) dJ[i] (the
     * slope along a line where dJ[i] is the rate of change of J[i]); value is
     * +infinity if any J[i] <= 0.
     */
    virtual LineValue
    sum_volumetric_energy_and_slope(const double     *J,
                                    const double     *dJ,
                                    const double     *w,
                                    const std::size_t n) const;

    /**
     * df[i] = f'(J[i]) for i < n; all J[i] > 0.
     *
     * ElasticBody's gradient calls it on runs of cells that threads and
     * processes cut differently. Each run starts a multiple of 8 cells after
     * a start of the serial loop's batches, and only the body's last batch
     * has a length that is not a multiple of 8. So a run gives the same bits
     * on any number of threads and processes if df[i] depends only on J[i],
     * on i mod 8 and on whether i is among the last n mod 8 entries: a
     * vector path of at most 8 lanes from the batch's start with a scalar
     * tail, as batch_log() takes, keeps to this.
     */
    virtual void
    volumetric_derivatives(const double     *J,
                           double           *df,
                           const std::size_t n) const;

    /**
     * Rigorous enclosures of sum w[i] f(J_i) and of sum w[i] f'(J_i) dJ_i over
     * all J_i in [J_lo[i], J_hi[i]] and dJ_i in [dJ_lo[i], dJ_hi[i]] (w[i] >=
     * 0). The enclosures also hold the values computed by
     * sum_volumetric_energy() and sum_volumetric_energy_and_slope() (in any
     * summation order) for such arguments.
     */
    virtual LineEnclosure
    enclose_volumetric_sum(const double     *J_lo,
                           const double     *J_hi,
                           const double     *dJ_lo,
                           const double     *dJ_hi,
                           const double     *w,
                           const std::size_t n) const;

    /**
     * An interval holding sum_k w[k] (f''(J_k) J_k'^2 + f'(J_k) J_k'') for all
     * J_k in [J_lo[k], J_hi[k]], J_k' in [dJ_lo[k], dJ_hi[k]] and J_k'' in
     * [d2J_lo[k], d2J_hi[k]]: the second derivative of the volumetric energy
     * along a free flight. @p slope_magnitude receives an upper bound of
     * sum_k w[k] |f'(J_k) J_k'|. The default loops over the cells with
     * volumetric_derivative_range() and
     * volumetric_second_derivative_range() (and is (-inf, inf) when the
     * latter is unknown).
     */
    virtual Interval
    enclose_volumetric_curvature_sum(const double     *J_lo,
                                     const double     *J_hi,
                                     const double     *dJ_lo,
                                     const double     *dJ_hi,
                                     const double     *d2J_lo,
                                     const double     *d2J_hi,
                                     const double     *w,
                                     const std::size_t n,
                                     double           &slope_magnitude) const;
    /** @} */
  };
} // namespace estep

#endif
