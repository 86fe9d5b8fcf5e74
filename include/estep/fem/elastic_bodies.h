#ifndef estep_fem_elastic_bodies_h
#define estep_fem_elastic_bodies_h

#include <estep/systems/mechanical_system.h>

#include <vector>

namespace estep
{
  class ElasticBody;

  /**
   * A system whose state is made of elastic bodies, seen body by body: what
   * field output needs to write each body's fields. ElasticBody (one body),
   * ContactSystem and the scenes provide it.
   */
  class ElasticBodies
  {
  public:
    virtual ~ElasticBodies() = default;

    /** Number of bodies. */
    virtual unsigned int
    n_bodies() const = 0;

    /** Body @p b. */
    virtual const ElasticBody &
    body(const unsigned int b) const = 0;

    /** Body @p b's configuration @p q_b and velocity @p v_b in the state
     * (@p q, @p v) of the system. */
    virtual void
    body_state(const Vector      &q,
               const Vector      &v,
               const unsigned int b,
               Vector            &q_b,
               Vector            &v_b) const = 0;

    /**
     * The rigid obstacles to draw with the bodies, as a triangle surface:
     * @p points (x, y, z each) and @p triangles (three point indices each).
     * The default has none.
     */
    virtual void
    obstacle_surface(std::vector<double>       &points,
                     std::vector<unsigned int> &triangles) const;
  };

  /**
   * The cells of the elastic bodies of @p system, which a run on several MPI
   * processes shares among them; 0 if the system is not made of elastic
   * bodies (it is not an ElasticBodies).
   */
  unsigned long long
  elastic_cells(const MechanicalSystem &system);
} // namespace estep

#endif
