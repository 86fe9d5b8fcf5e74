// Shared construction of the test bodies (built once per test program).
#ifndef estep_tests_fem_test_bodies_h
#define estep_tests_fem_test_bodies_h

#include <deal.II/grid/tria.h>

#include <estep/fem/elastic_body.h>
#include <estep/fem/meshes.h>
#include <estep/materials/neo_hookean.h>

#include <memory>
#include <random>

namespace estep_test
{
  /** The spinning-cube body: n^3 hexahedra of 24 tets, lambda0 = 0.01,
   * mu0 = 0.0066, rho = 0.1. */
  inline std::shared_ptr<const estep::ElasticBody>
  cube_body(const unsigned int n)
  {
    dealii::Triangulation<3> tria;
    estep::make_seed_cube_mesh(tria, n);
    return std::make_shared<const estep::ElasticBody>(
      tria, std::make_shared<estep::NeoHookean>(0.0100, 0.0066), 0.100, "cube");
  }

  /** The n = 8 spinning cube, built once. */
  inline const estep::ElasticBody &
  seed_cube()
  {
    static const auto body = cube_body(8);
    return *body;
  }

  /** The reference configuration with every coordinate perturbed by up to @p
   * amplitude. */
  inline estep::Vector
  perturbed(const estep::ElasticBody &body,
            const double              amplitude,
            const unsigned int        seed)
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    estep::Vector                          q = body.reference_configuration();
    for (auto &x : q)
      x += u(rng);
    return q;
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
} // namespace estep_test

#endif
