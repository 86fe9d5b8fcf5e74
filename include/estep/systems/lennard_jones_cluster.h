#ifndef estep_systems_lennard_jones_cluster_h
#define estep_systems_lennard_jones_cluster_h

#include <estep/systems/mechanical_system.h>

namespace estep
{
  /**
   * A cluster of equal particles interacting through the Lennard-Jones pair
   * potential phi(r) = 4 epsilon [(sigma / r)^12 - (sigma / r)^6] over all
   * pairs, without cutoff, in two or three dimensions. Units are those of the
   * arguments (estep's argon cluster uses reduced units, epsilon = sigma = mass
   * = 1).
   *
   * Its free flight is exact and cheap: along q + s v the squared distance of
   * each pair is a quadratic u(s) in s, phi is decreasing in u below u* =
   * 2^(1/3) sigma^2 and increasing above, and phi'(u) increases below u**
   * = 3.5^(1/3) sigma^2 and decreases above, so the enclosures of the value and
   * the slope are exact ranges per pair, summed over pairs.
   */
  class LennardJonesCluster : public MechanicalSystem
  {
  public:
    /**
     * @param dimension 2 or 3.
     * @param n_particles Number of particles.
     * @param mass Mass of each particle.
     * @param epsilon Depth of the pair potential well (energy).
     * @param sigma Distance at which the pair potential vanishes (length).
     */
    LennardJonesCluster(const unsigned int dimension,
                        const unsigned int n_particles,
                        const double       mass,
                        const double       epsilon,
                        const double       sigma);

    std::string
    name() const override;

    unsigned int
    spatial_dimension() const override;

    unsigned int
    n_dofs() const override;

    const Vector &
    inverse_mass() const override;

    double
    energy(const Vector &q) const override;

    void
    gradient(const Vector &q, Vector &g) const override;

    std::unique_ptr<FreeFlight>
    free_flight(const Vector &q, const Vector &v) const override;

    /** The particle positions x1, y1, (z1,) x2, ..., numbered from 1 as the
     * bodies of a scene are. */
    std::vector<std::string>
    observable_names() const override;

    std::vector<double>
    observables(const Vector &q, const Vector &v) const override;

    /** phi(u) with u the squared distance. */
    double
    pair_energy(const double u) const;

    /** d phi / d u with u the squared distance. */
    double
    pair_energy_derivative(const double u) const;

  private:
    const unsigned int dim;
    const unsigned int n_particles;
    const double       epsilon, sigma2;
    Vector             inverse_masses;
  };
} // namespace estep

#endif
