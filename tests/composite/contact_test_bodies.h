// Shared construction of the small balls of the contact-system tests.
#ifndef estep_tests_composite_contact_test_bodies_h
#define estep_tests_composite_contact_test_bodies_h

#include <deal.II/grid/tria.h>

#include <estep/composite/contact_system.h>
#include <estep/fem/ball_mesh.h>
#include <estep/fem/elastic_body.h>
#include <estep/materials/neo_hookean.h>

#include <array>
#include <memory>
#include <random>

namespace estep_test
{
  /** A ball of radius 1 about @p centre, gmsh mesh size @p size, neo-Hookean
   * (lambda0, mu0), density rho. */
  inline std::shared_ptr<const estep::ElasticBody>
  ball(const std::array<double, 3> &centre,
       const double                 size,
       const double                 lambda0,
       const double                 mu0,
       const double                 rho)
  {
    dealii::Triangulation<3> tria;
    estep::make_ball_mesh(tria, size, 1., centre);
    return std::make_shared<const estep::ElasticBody>(
      tria, std::make_shared<estep::NeoHookean>(lambda0, mu0), rho, "ball");
  }

  /** Two balls of radius 1 with centres (0, 0, 0) and (distance, 0, 0). */
  inline std::unique_ptr<estep::ContactSystem>
  two_balls(const double                    distance,
            const double                    size,
            const estep::ContactParameters &parameters,
            const double                    lambda0 = 10.,
            const double                    mu0     = 5.,
            const double                    rho     = 1.)
  {
    return std::make_unique<estep::ContactSystem>(
      std::vector<std::shared_ptr<const estep::ElasticBody>>{
        ball({{0., 0., 0.}}, size, lambda0, mu0, rho),
        ball({{distance, 0., 0.}}, size, lambda0, mu0, rho)},
      parameters,
      "two balls");
  }

  /** A random vector with entries in [-amplitude, amplitude]. */
  inline estep::Vector
  random_vector(const unsigned int n,
                const double       amplitude,
                const unsigned int seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    estep::Vector                          v(n);
    for (auto &x : v)
      x = u(rng);
    return v;
  }

  /** The reference configuration of all bodies of @p system. */
  inline estep::Vector
  reference(const estep::ContactSystem &system)
  {
    std::vector<estep::Vector> parts;
    for (unsigned int b = 0; b < system.n_bodies(); ++b)
      parts.push_back(system.body(b).reference_configuration());
    return system.concatenate(parts);
  }

  /** Rigid velocities: body b moves with v0[b] and spins with omega[b] about
   * its centre of mass. */
  inline estep::Vector
  rigid_velocities(const estep::ContactSystem               &system,
                   const estep::Vector                      &q,
                   const std::vector<std::array<double, 3>> &v0,
                   const std::vector<std::array<double, 3>> &omega)
  {
    std::vector<estep::Vector> parts;
    const estep::Vector        zero(q.size());
    for (unsigned int b = 0; b < system.n_bodies(); ++b)
      {
        const auto motion = system.body_motion(q, zero, b);
        parts.push_back(system.body(b).rigid_velocity(
          system.extract(q, b), v0[b], omega[b], motion.centre));
      }
    return system.concatenate(parts);
  }
} // namespace estep_test

#endif
