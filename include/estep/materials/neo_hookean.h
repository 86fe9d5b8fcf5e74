#ifndef estep_materials_neo_hookean_h
#define estep_materials_neo_hookean_h

#include <estep/materials/material.h>

namespace estep
{
  /**
   * The compressible neo-Hookean material
   * @f[ W(F) = \frac{\lambda_0}{2} (\log J)^2 - \mu_0 \log J + \frac{\mu_0}{2}
   *            (\mathrm{tr}(F^T F) - 3), @f]
   * i.e. f(J) = lambda0/2 (log J)^2 - mu0 log J and c = mu0 in the split form
   * of Material (f(1) = 0, so W_0 = 3 mu0/2). P = mu0 (F - F^-T) + lambda0 log
   * J F^-T.
   *
   * In terms of L = log J, f = lambda0/2 (L - mu0/lambda0)^2 - mu0^2/(2
   * lambda0): f decreases for J < J* = exp(mu0/lambda0) and increases beyond,
   * so its range over a J-interval follows from the logarithms of the two ends.
   * The batch kernels use batch_log() (glibc's vector logarithm) and tight
   * loops over plain arrays.
   *
   * lambda0 >= 0 and mu0 > 0 are the Lame constants of the linearised material
   * (stresses).
   */
  class NeoHookean : public Material
  {
  public:
    /** The material with Lame constants @p lambda0 >= 0 and @p mu0 > 0. */
    NeoHookean(const double lambda0, const double mu0);

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

    std::string
    name() const override;

    double
    quadratic_modulus() const override;

    double
    volumetric_energy(const double J) const override;

    double
    volumetric_derivative(const double J) const override;

    /** f''(J) = (lambda0 + mu0 - lambda0 log J) / J^2. */
    double
    volumetric_second_derivative(const double J) const override;

    Interval
    volumetric_energy_range(const Interval &J) const override;

    /** f'' decreases up to J = exp(3/2 + mu0/lambda0) and increases after. */
    Interval
    volumetric_second_derivative_range(const Interval &J) const override;

    /** Batch version with vectorised logs: f'' = (lambda0 + mu0 - lambda0
     * log J) / J^2 and f' = (lambda0 log J - mu0) / J, enclosed by interval
     * division. */
    Interval
    enclose_volumetric_curvature_sum(const double     *J_lo,
                                     const double     *J_hi,
                                     const double     *dJ_lo,
                                     const double     *dJ_hi,
                                     const double     *d2J_lo,
                                     const double     *d2J_hi,
                                     const double     *w,
                                     const std::size_t n,
                                     double &slope_magnitude) const override;

    Interval
    volumetric_derivative_range(const Interval &J) const override;

    double
    sum_volumetric_energy(const double     *J,
                          const double     *w,
                          const std::size_t n) const override;

    LineValue
    sum_volumetric_energy_and_slope(const double     *J,
                                    const double     *dJ,
                                    const double     *w,
                                    const std::size_t n) const override;

    void
    volumetric_derivatives(const double     *J,
                           double           *df,
                           const std::size_t n) const override;

    LineEnclosure
    enclose_volumetric_sum(const double     *J_lo,
                           const double     *J_hi,
                           const double     *dJ_lo,
                           const double     *dJ_hi,
                           const double     *w,
                           const std::size_t n) const override;

  private:
    double lambda0;
    double mu0;
  };
} // namespace estep

#endif
