#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/tria.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/exception_text.h>
#include <estep/base/parameter_subsections.h>
#include <estep/base/point_entry.h>
#include <estep/composite/contact_parameters.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/mesh_description.h>
#include <estep/fem/tangent_stiffness.h>
#include <estep/materials/material_registry.h>
#include <estep/problems/parsed_vector_field.h>
#include <estep/problems/problem.h>

#include <iostream>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    void
    declare_elastic_body_parameters(dealii::ParameterHandler &prm)
    {
      using dealii::Patterns::Anything;
      using dealii::Patterns::Double;
      using dealii::Patterns::List;
      using dealii::Patterns::Selection;
      const double max = Double::max_double_value;
      const List   point(Double(-max, max), 3, 3, ",");

      declare_material_subsection(prm); // this problem reads it
      ContactParameters::declare_parameters(prm);
      prm.enter_subsection("Elastic body");
      {
        prm.enter_subsection("Mesh");
        MeshDescription::declare_parameters(prm);
        prm.leave_subsection();

        prm.enter_subsection("Initial velocity");
        {
          prm.declare_entry(
            "Type",
            "rigid motion",
            Selection("rigid motion|function"),
            "rigid motion: v = V + omega x (X - c); function: the "
            "parsed function below of the reference coordinates x, y, z.");
          prm.declare_entry("Translational velocity",
                            "0, 0, 0",
                            point,
                            "V of the rigid motion.");
          prm.declare_entry(
            "Angular velocity",
            "0, 0, 1",
            point,
            "omega of the rigid motion (the spinning cube: 1 about z).");
          prm.declare_entry("Rotation centre",
                            "0.5, 0.5, 0.5",
                            point,
                            "c of the rigid motion.");
          prm.declare_entry(
            "Function expression",
            "0; 0; 0",
            Anything(),
            "The three velocity components as functions of x, y, z (and "
            "the constants below), separated by ';' (deal.II's "
            "FunctionParser syntax).");
          prm.declare_entry(
            "Function constants",
            "",
            Anything(),
            "Constants of the function expression, e.g. 'w=2, a=0.1'.");
        }
        prm.leave_subsection();

        prm.declare_entry(
          "Tracked point",
          "0.5, 1.0, 1.0",
          point,
          "Reference coordinates of a point whose current position the "
          "history records (the nearest mesh vertex): columns "
          "tracked_x, tracked_y, tracked_z.");
      }
      prm.leave_subsection();
    }



    Problem
    create_elastic_body_problem(dealii::ParameterHandler &prm)
    {
      // Any contact setting, also one that contact itself would refuse, is
      // one this problem would ignore.
      bool contact_set = true;
      try
        {
          ContactParameters contact;
          contact.parse_parameters(prm);
          contact_set = !contact.is_default();
        }
      catch (const std::exception &)
        {}
      if (contact_set)
        throw std::runtime_error(
          "Contact: the elastic body problem has no contact; for bodies in "
          "contact or obstacles, set Problem/System = scene.");

      prm.enter_subsection("Elastic body");

      MeshDescription mesh;
      prm.enter_subsection("Mesh");
      mesh.parse_parameters(prm);
      prm.leave_subsection();

      prm.leave_subsection();
      prm.enter_subsection("Material");
      const MaterialChoice material =
        parse_material_parameters(prm, "Material");
      prm.leave_subsection();
      prm.enter_subsection("Elastic body");

      auto body = std::make_unique<ElasticBodyWithHessian>(
        make_p1_cell_data_on_first_rank(
          [&](dealii::Triangulation<3> &tria) {
            make_mesh(mesh, tria, "Elastic body");
          },
          material.density),
        material.material,
        "elastic body");
      Problem                     problem;
      const std::array<double, 3> tracked =
        parse_point(prm.get("Tracked point"), "Elastic body/Tracked point");
      body->track_point("tracked", tracked);
      if (const std::string warning =
            tracked_point_warning(*body, "Elastic body/Tracked point", tracked);
          !warning.empty())
        problem.warnings.push_back(warning);
      problem.q0 = body->reference_configuration();

      prm.enter_subsection("Initial velocity");
      if (prm.get("Type") == "rigid motion")
        problem.v0 = body->rigid_velocity(
          problem.q0,
          parse_point(prm.get("Translational velocity"),
                      "Elastic body/Initial velocity/Translational velocity"),
          parse_point(prm.get("Angular velocity"),
                      "Elastic body/Initial velocity/Angular velocity"),
          parse_point(prm.get("Rotation centre"),
                      "Elastic body/Initial velocity/Rotation centre"));
      else
        problem.v0 = evaluate_vector_field(
          "Elastic body/Initial velocity/Function expression",
          prm.get("Function expression"),
          "x,y,z",
          prm.get("Function constants"),
          problem.q0);
      prm.leave_subsection();
      prm.leave_subsection();

      problem.description.add("cells", body->n_cells())
        .add("vertices", body->n_vertices())
        .add("volume", body->volume())
        .add("mass", body->mass())
        .add("mesh", mesh.type)
        .add("material", material.material->name())
        .add("density", material.density);
      if (rank_count() > 1)
        problem.description.add("cells held by each process",
                                cells_held_on_each_rank({&body->cell_data()}));
      problem.system = std::move(body);
      // Entries that the chosen mesh type and velocity type do not read.
      const std::vector<std::string> unread = entries_unread_by_type(
        prm,
        {{"Elastic body/Mesh", MeshDescription::type_readers()},
         {"Elastic body/Initial velocity", initial_velocity_type_readers()}});
      problem.warnings.insert(problem.warnings.end(),
                              unread.begin(),
                              unread.end());
      return problem;
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_PROBLEM(
  "elastic body",
  "One elastic body (subsection Elastic body): a mesh, a material (subsection "
  "Material), an initial velocity and a tracked point.",
  estep::declare_elastic_body_parameters,
  estep::create_elastic_body_problem)
