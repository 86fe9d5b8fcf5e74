#ifndef estep_materials_quadratic_volume_neo_hookean_h
#define estep_materials_quadratic_volume_neo_hookean_h

#include <estep/materials/material.h>

namespace estep
{
  /**
   * A compressible neo-Hookean material with a quadratic volumetric function,
   * @f[ W(F) = \frac{\lambda_0}{2} (J - 1)^2 - \mu_0 \log J + \frac{\mu_0}{2}
   *            (\mathrm{tr}(F^T F) - 3), @f]
   * i.e. f(J) = lambda0/2 (J - 1)^2 - mu0 log J and c = mu0 in the split form
   * of Material (f(1) = 0, so W_0 = 3 mu0/2 and W(I) = 0). P = mu0 (F - F^-T)
   * + lambda0 (J - 1) J F^-T vanishes at F = I, and the linearisation at F = I
   * is that of NeoHookean with the same constants: isotropic linear
   * elasticity with the Lame constants lambda0 and mu0 (f''(1) = lambda0 +
   * mu0 and f'(1) = -mu0 for both). The two materials differ at finite
   * volume changes: here the volumetric stress grows linearly in J under
   * expansion, whereas the logarithmic one of NeoHookean softens.
   *
   * The volumetric function is convex,
   * @f[ f'(J) = \lambda_0 (J - 1) - \frac{\mu_0}{J}, \qquad
   *     f''(J) = \lambda_0 + \frac{\mu_0}{J^2} > 0, @f]
   * with f' increasing and f'' decreasing in J; f has its minimum where f' =
   * 0, at J* = (1 + sqrt(1 + 4 mu0/lambda0))/2 > 1 (no minimum for lambda0 =
   * 0: f then decreases). The ranges of f, f' and f'' over an interval of J
   * therefore follow from its ends (and from f(J*) when J* lies inside),
   * widened by a bound of the round-off of the point functions. Only f needs a
   * logarithm; the batch kernels are plain loops (std::log), and the
   * enclosures of the sums over cells are those of Material, built on the
   * rigorous range functions.
   *
   * lambda0 >= 0 and mu0 > 0 are the Lame constants of the linearised material
   * (stresses).
   */
  class QuadraticVolumeNeoHookean : public Material
  {
  public:
    /** The material with Lame constants @p lambda0 >= 0 and @p mu0 > 0. */
    QuadraticVolumeNeoHookean(const double lambda0, const double mu0);

    /** First Lame constant. */
    double
    lambda() const
    {
      return lambda0;
    }

    /** Shear modulus. */
    double
    mu() const
    {
      return mu0;
    }

    /** The volume ratio J* > 1 at which f is smallest (+infinity if lambda0 =
     * 0). */
    double
    energy_minimiser() const
    {
      return J_star;
    }

    std::string
    name() const override;

    /** c = mu0. */
    double
    quadratic_modulus() const override;

    /** f(J) = lambda0/2 (J - 1)^2 - mu0 log J; +infinity for J <= 0. */
    double
    volumetric_energy(const double J) const override;

    /** f'(J) = lambda0 (J - 1) - mu0 / J. */
    double
    volumetric_derivative(const double J) const override;

    /** f''(J) = lambda0 + mu0 / J^2 (exact). */
    double
    volumetric_second_derivative(const double J) const override;

    /**
     * The range of f over @p J: f at the ends, and f(J*) when the minimiser J*
     * lies inside, widened by the round-off of volumetric_energy(). The upper
     * bound is +infinity when J.lower <= 0 or when f overflows (J.upper >
     * 1e153; the lower bound is then one that holds for every J); the result
     * is (+infinity, +infinity) when J.upper <= 0.
     */
    Interval
    volumetric_energy_range(const Interval &J) const override;

    /** [f'(J.lower), f'(J.upper)] (f' increases), widened by the round-off of
     * volumetric_derivative(); (-infinity, infinity) when J.lower <= 0 or
     * when f' overflows. */
    Interval
    volumetric_derivative_range(const Interval &J) const override;

    /** [f''(J.upper), f''(J.lower)] (f'' decreases), widened by the round-off
     * of volumetric_second_derivative(); (-infinity, infinity) when J.lower
     * <= 0, and unbounded above when J.lower^2 underflows. */
    Interval
    volumetric_second_derivative_range(const Interval &J) const override;

    /** A plain loop over f (std::log per cell). */
    double
    sum_volumetric_energy(const double     *J,
                          const double     *w,
                          const std::size_t n) const override;

    /** A plain loop over f and f' (std::log per cell). */
    LineValue
    sum_volumetric_energy_and_slope(const double     *J,
                                    const double     *dJ,
                                    const double     *w,
                                    const std::size_t n) const override;

    /** A plain loop over f' (no logarithm). */
    void
    volumetric_derivatives(const double     *J,
                           double           *df,
                           const std::size_t n) const override;

  private:
    double lambda0;
    double mu0;
    /** The minimiser of f, (1 + sqrt(1 + 4 mu0/lambda0))/2, or +infinity. */
    double J_star;
    /** f(J_star) as volumetric_energy() computes it (-infinity if J_star is
     * infinite). */
    double f_min;
    /** A lower bound of every value volumetric_energy() returns (-infinity if
     * f_min is). */
    double global_lower;
  };
} // namespace estep

#endif
