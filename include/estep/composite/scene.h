#ifndef estep_composite_scene_h
#define estep_composite_scene_h

#include <estep/composite/system_decorator.h>
#include <estep/fem/elastic_bodies.h>

#include <functional>
#include <memory>

namespace estep
{
  class ContactSystem;

  /**
   * A user's scene as one MechanicalSystem: elastic bodies (in contact, if
   * asked), with whatever decorators the scene has (obstacles, gravity,
   * supports) stacked on top; and, for output, the bodies one by one.
   *
   * @p system is the outermost decorator (the system the integrator sees),
   * @p bodies the system of the bodies themselves (an ElasticBody or a
   * ContactSystem), and @p to_bodies maps a state of @p system to a state of
   * @p bodies (the identity, or the expansion of the supported points);
   * @p has_supports says whether supports hold points of the bodies.
   */
  class Scene : public SystemDecorator, public ElasticBodies
  {
  public:
    /** The map from a state (q, v) of the scene to one of its bodies'
     * system. */
    using StateMap = std::function<void(const Vector &q,
                                        const Vector &v,
                                        Vector       &q_bodies,
                                        Vector       &v_bodies)>;

    Scene(std::shared_ptr<const MechanicalSystem> system,
          std::shared_ptr<const ElasticBodies>    bodies,
          StateMap                                to_bodies,
          const std::string                      &name,
          const bool                              has_supports);

    /** The bodies' own system if they are in contact (a ContactSystem),
     * nullptr otherwise. */
    const ContactSystem *
    contact_system() const;

    /** The map from a state of the scene to one of its bodies' system. */
    const StateMap &
    state_map() const;

    std::string
    name() const override;

    unsigned int
    n_bodies() const override;

    const ElasticBody &
    body(const unsigned int b) const override;

    void
    body_state(const Vector      &q,
               const Vector      &v,
               const unsigned int b,
               Vector            &q_b,
               Vector            &v_b) const override;

    /** How many points of the state @p q of the scene lie inside an
     * obstacle (penalty contact with obstacles shows this way; 0 without
     * obstacles). */
    unsigned int
    n_points_in_obstacles(const Vector &q) const;

    /** Set the count n_points_in_obstacles() returns. */
    void
    set_obstacle_count(std::function<unsigned int(const Vector &)> count);

    /** Add a rigid obstacle's surface (for output): @p points (x, y, z each)
     * and @p triangles (indices into @p points). */
    void
    add_obstacle_surface(const std::vector<double>       &points,
                         const std::vector<unsigned int> &triangles);

    void
    obstacle_surface(std::vector<double>       &points,
                     std::vector<unsigned int> &triangles) const override;

    /** Whether nothing but the bodies themselves exchanges momentum with
     * them: no supports, no obstacles (uniform gravity leaves their relative
     * motion alone). */
    bool
    bodies_only_meet_each_other() const;

  private:
    std::function<unsigned int(const Vector &)> obstacle_count;
    std::vector<double>                         obstacle_points;
    std::vector<unsigned int>                   obstacle_triangles;
    std::shared_ptr<const ElasticBodies>        bodies;
    StateMap                                    to_bodies;
    std::string                                 scene_name;
    bool                                        has_supports;
    mutable Vector                              q_bodies, v_bodies;
  };
} // namespace estep

#endif
