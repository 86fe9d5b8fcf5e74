#ifndef estep_tests_harmonic_oscillator_h
#define estep_tests_harmonic_oscillator_h

// A linear test system with a closed-form motion, for the order tests of the
// time integrators: two coupled oscillators with unequal masses.

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <estep/systems/mechanical_system.h>

#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace estep::testing
{
  /**
   * One point in the plane with the lumped mass M = diag(2, 1/2) and the
   * potential V(q) = 1/2 q^T K q, K = [[3, -1], [-1, 3/2]] (the two
   * coordinates are coupled). The generalised eigenproblem K phi = omega^2 M
   * phi has omega^2 = 1 and 7/2, so the motion is quasi-periodic with periods
   * 2 pi and 3.36. The masses differ from 1 and from each other, so that an
   * integrator that confuses M with M^-1 or ignores it goes wrong.
   *
   * exact_state() is the closed-form motion by modal superposition. The
   * Hessian is K (for the implicit integrators); the free flight is not
   * provided (throws).
   */
  class HarmonicOscillator : public MechanicalSystem
  {
  public:
    HarmonicOscillator()
      : inverse_masses(2)
    {
      inverse_masses[0] = 1. / mass[0];
      inverse_masses[1] = 1. / mass[1];
      dealii::DynamicSparsityPattern dsp(2, 2);
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
          dsp.add(i, j);
      sparsity.copy_from(dsp);
    }

    std::string
    name() const override
    {
      return "harmonic oscillator";
    }

    unsigned int
    spatial_dimension() const override
    {
      return 2;
    }

    unsigned int
    n_dofs() const override
    {
      return 2;
    }

    const Vector &
    inverse_mass() const override
    {
      return inverse_masses;
    }

    double
    energy(const Vector &q) const override
    {
      return 0.5 * (K[0][0] * q[0] * q[0] + 2. * K[0][1] * q[0] * q[1] +
                    K[1][1] * q[1] * q[1]);
    }

    void
    gradient(const Vector &q, Vector &g) const override
    {
      g.reinit(2);
      g[0] = K[0][0] * q[0] + K[0][1] * q[1];
      g[1] = K[1][0] * q[0] + K[1][1] * q[1];
    }

    std::unique_ptr<FreeFlight>
    free_flight(const Vector &, const Vector &) const override
    {
      throw std::logic_error("HarmonicOscillator has no free flight.");
    }

    bool
    has_hessian() const override
    {
      return true;
    }

    const dealii::SparsityPattern &
    hessian_sparsity() const override
    {
      return sparsity;
    }

    void
    hessian(const Vector &, dealii::SparseMatrix<double> &H) const override
    {
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
          H.set(i, j, K[i][j]);
    }

    /** Total energy 1/2 v^T M v + V(q). */
    double
    total_energy(const Vector &q, const Vector &v) const
    {
      return 0.5 * (mass[0] * v[0] * v[0] + mass[1] * v[1] * v[1]) + energy(q);
    }

    /**
     * The exact state (q, v) at time @p t of the motion that starts from
     * (q0, v0) at time 0: q(t) = sum_k phi_k (a_k cos omega_k t + b_k / omega_k
     * sin omega_k t) with a_k, b_k the M-projections of q0, v0 on the modes.
     */
    void
    exact_state(const double  t,
                const Vector &q0,
                const Vector &v0,
                Vector       &q,
                Vector       &v) const
    {
      q.reinit(2);
      v.reinit(2);
      // det(K - lambda M) = 0: m0 m1 lambda^2 - (k00 m1 + k11 m0) lambda +
      // det K = 0.
      const double a    = mass[0] * mass[1];
      const double b    = -(K[0][0] * mass[1] + K[1][1] * mass[0]);
      const double c    = K[0][0] * K[1][1] - K[0][1] * K[1][0];
      const double root = std::sqrt(b * b - 4. * a * c);
      for (const double lambda :
           {(-b - root) / (2. * a), (-b + root) / (2. * a)})
        {
          // (K - lambda M) phi = 0 from its first row.
          const std::array<double, 2> phi = {
            {-K[0][1], K[0][0] - lambda * mass[0]}};
          const double norm =
            mass[0] * phi[0] * phi[0] + mass[1] * phi[1] * phi[1];
          const double alpha =
            (mass[0] * phi[0] * q0[0] + mass[1] * phi[1] * q0[1]) / norm;
          const double beta =
            (mass[0] * phi[0] * v0[0] + mass[1] * phi[1] * v0[1]) / norm;
          const double omega = std::sqrt(lambda);
          const double C = std::cos(omega * t), S = std::sin(omega * t);
          for (unsigned int i = 0; i < 2; ++i)
            {
              q[i] += phi[i] * (alpha * C + beta / omega * S);
              v[i] += phi[i] * (-alpha * omega * S + beta * C);
            }
        }
    }

    /** The initial state of the tests. */
    static void
    initial_state(Vector &q0, Vector &v0)
    {
      q0.reinit(2);
      v0.reinit(2);
      q0[0] = 0.6;
      q0[1] = -0.3;
      v0[0] = 0.2;
      v0[1] = 0.9;
    }

    const double mass[2] = {2., 0.5};
    const double K[2][2] = {{3., -1.}, {-1., 1.5}};

  private:
    Vector                  inverse_masses;
    dealii::SparsityPattern sparsity;
  };
} // namespace estep::testing

#endif
