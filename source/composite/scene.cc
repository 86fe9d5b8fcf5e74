#include <estep/composite/contact_system.h>
#include <estep/composite/scene.h>

namespace estep
{
  Scene::Scene(std::shared_ptr<const MechanicalSystem> system,
               std::shared_ptr<const ElasticBodies>    bodies,
               StateMap                                to_bodies,
               const std::string                      &name,
               const bool                              has_supports)
    : SystemDecorator(std::move(system))
    , bodies(std::move(bodies))
    , to_bodies(std::move(to_bodies))
    , scene_name(name)
    , has_supports(has_supports)
  {
    // The scene adds nothing to V.
    shares_base_state = true;
  }



  const ContactSystem *
  Scene::contact_system() const
  {
    return dynamic_cast<const ContactSystem *>(bodies.get());
  }



  const Scene::StateMap &
  Scene::state_map() const
  {
    return to_bodies;
  }



  std::string
  Scene::name() const
  {
    return scene_name;
  }



  unsigned int
  Scene::n_bodies() const
  {
    return bodies->n_bodies();
  }



  const ElasticBody &
  Scene::body(const unsigned int b) const
  {
    return bodies->body(b);
  }



  void
  Scene::body_state(const Vector      &q,
                    const Vector      &v,
                    const unsigned int b,
                    Vector            &q_b,
                    Vector            &v_b) const
  {
    to_bodies(q, v, q_bodies, v_bodies);
    bodies->body_state(q_bodies, v_bodies, b, q_b, v_b);
  }



  unsigned int
  Scene::n_points_in_obstacles(const Vector &q) const
  {
    return obstacle_count ? obstacle_count(q) : 0;
  }



  void
  Scene::set_obstacle_count(std::function<unsigned int(const Vector &)> count)
  {
    obstacle_count = std::move(count);
  }



  void
  Scene::add_obstacle_surface(const std::vector<double>       &points,
                              const std::vector<unsigned int> &triangles)
  {
    const unsigned int first = obstacle_points.size() / 3;
    obstacle_points.insert(obstacle_points.end(), points.begin(), points.end());
    for (const unsigned int p : triangles)
      obstacle_triangles.push_back(first + p);
  }



  void
  Scene::obstacle_surface(std::vector<double>       &points,
                          std::vector<unsigned int> &triangles) const
  {
    points    = obstacle_points;
    triangles = obstacle_triangles;
  }


  bool
  Scene::bodies_only_meet_each_other() const
  {
    return !has_supports && obstacle_triangles.empty();
  }
} // namespace estep
