#include <deal.II/base/parameter_handler.h>
#include <deal.II/grid/tria.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/exception_text.h>
#include <estep/composite/contact_parameters.h>
#include <estep/composite/contact_system.h>
#include <estep/fem/ball_mesh.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/meshes.h>
#include <estep/materials/material_registry.h>
#include <estep/problems/problem.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace estep
{
  namespace
  {
    void
    declare_colliding_balls_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Double;
      const double max = Double::max_double_value;
      declare_material_subsection(prm); // this problem reads it
      prm.enter_subsection("Colliding balls");
      {
        prm.declare_entry("Radius",
                          "1",
                          Double(0., max),
                          "Radius of both balls.");
        prm.declare_entry(
          "Size ratio",
          "1",
          Double(0., max),
          "Radius of ball 2 over the radius of ball 1; ball 2's mesh is ball "
          "1's mesh scaled by it (the same counts). The Hertz estimate is "
          "given for equal balls only.");
        prm.declare_entry(
          "Mesh size",
          "0.3",
          Double(0., max),
          "Target edge length of the ball meshes relative to their radius "
          "(0.3: 898 tetrahedra and 258 vertices per ball; the reference "
          "text's mesh had 864 and 250).");
        prm.declare_entry(
          "Gap",
          "0.5",
          Double(0., max),
          "Distance between the two surfaces along the x axis at t = 0.");
        prm.declare_entry("Speed",
                          "5",
                          Double(0., max),
                          "Speed of ball 2 towards ball 1 (along -x).");
        prm.declare_entry(
          "Spin",
          "2.5",
          Double(-max, max),
          "Angular velocity of ball 2 about the y axis, perpendicular to "
          "the line of centres.");
      }
      prm.leave_subsection();
      ContactParameters::declare_parameters(prm);
    }



    Problem
    create_colliding_balls_problem(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Colliding balls");
      const double R     = prm.get_double("Radius");
      const double ratio = prm.get_double("Size ratio");
      const double size  = prm.get_double("Mesh size");
      const double gap   = prm.get_double("Gap");
      const double speed = prm.get_double("Speed");
      const double spin  = prm.get_double("Spin");
      prm.leave_subsection();
      for (const auto &[entry, value] : {std::pair{"Radius", R},
                                         std::pair{"Size ratio", ratio},
                                         std::pair{"Mesh size", size}})
        if (!(value > 0.))
          throw std::runtime_error(std::string("Colliding balls/") + entry +
                                   ": must be positive.");
      prm.enter_subsection("Material");
      const MaterialChoice choice = parse_material_parameters(prm, "Material");
      prm.leave_subsection();
      const double      density = choice.density;
      ContactParameters contact;
      contact.parse_parameters(prm);

      const auto                 &material = choice.material;
      const std::array<double, 3> centre_1 = {{0., 0., 0.}},
                                  centre_2 = {{(1. + ratio) * R + gap, 0., 0.}};
      std::vector<std::shared_ptr<const ElasticBody>> bodies;
      std::vector<Vector>                             q, v;
      for (const auto &[scale, centre, velocity, omega] :
           {std::tuple{1.,
                       centre_1,
                       std::array<double, 3>{{0., 0., 0.}},
                       std::array<double, 3>{{0., 0., 0.}}},
            std::tuple{ratio,
                       centre_2,
                       std::array<double, 3>{{-speed, 0., 0.}},
                       std::array<double, 3>{{0., spin, 0.}}}})
        {
          const auto make_ball = [&](dealii::Triangulation<3> &tria) {
            try
              {
                make_ball_mesh(tria, size, scale * R, centre);
                order_cells_compactly(tria);
              }
            catch (const std::exception &e)
              {
                throw std::runtime_error("Colliding balls/Mesh size: " +
                                         one_line_message(e));
              }
          };
          auto body = std::make_shared<ElasticBody>(
            make_p1_cell_data_on_first_rank(make_ball, density),
            material,
            "ball");
          q.push_back(body->reference_configuration());
          v.push_back(body->rigid_velocity(q.back(), velocity, omega, centre));
          bodies.push_back(body);
        }

      // Hertz's estimate of the contact duration of two equal elastic spheres
      // meeting head-on at relative speed v0 (as the reference text writes
      // it).
      const double lambda = choice.material->small_strain_lambda();
      const double mu     = choice.material->small_strain_mu();
      const double E      = mu * (3. * lambda + 2. * mu) / (lambda + mu);
      const double nu     = lambda / (2. * (lambda + mu));
      const double hertz =
        4.53 *
        std::pow((1. - nu * nu) / E * 4. / 3. * R * R * R * density, 0.4) *
        std::pow(2. / (speed * R), 0.2);

      Problem problem;
      problem.description.add("balls", 2u)
        .add("cells per ball", bodies[0]->n_cells())
        .add("vertices per ball", bodies[0]->n_vertices())
        .add("masses",
             std::vector<double>{bodies[0]->mass(), bodies[1]->mass()})
        .add("Young's modulus", E)
        .add("Poisson's ratio", nu)
        .add("contact", ContactParameters::mode_name(contact.mode));
      if (speed > 0. && ratio == 1.)
        problem.description.add("Hertz contact duration estimate", hertz);
      if (rank_count() > 1)
        problem.description.add("cells held by each process",
                                cells_held_on_each_rank(
                                  {&bodies[0]->cell_data(),
                                   &bodies[1]->cell_data()}));
      auto system =
        std::make_unique<ContactSystem>(bodies, contact, "colliding balls");
      problem.q0     = system->concatenate(q);
      problem.v0     = system->concatenate(v);
      problem.system = std::move(system);
      return problem;
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_PROBLEM(
  "colliding balls",
  "Two elastic balls (subsection Colliding balls, material in the subsection "
  "Material) meeting with a relative speed and a spin, in contact (subsection "
  "Contact).",
  estep::declare_colliding_balls_parameters,
  estep::create_colliding_balls_problem)
