#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <estep/base/checksum.h>
#include <estep/base/distributed_blocks.h>
#include <estep/base/exception_text.h>
#include <estep/base/parameter_subsections.h>
#include <estep/base/point_entry.h>
#include <estep/composite/contact_parameters.h>
#include <estep/composite/contact_system.h>
#include <estep/composite/gravity.h>
#include <estep/composite/half_space_obstacles.h>
#include <estep/composite/scene.h>
#include <estep/composite/static_surface.h>
#include <estep/composite/supported_system.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/mesh_description.h>
#include <estep/fem/meshes.h>
#include <estep/fem/tangent_stiffness.h>
#include <estep/materials/material_registry.h>
#include <estep/problems/parsed_vector_field.h>
#include <estep/problems/problem.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    using Point3 = std::array<double, 3>;

    /** "p_x, p_y, p_z, n_x, n_y, n_z; ..." as half-spaces (unit normals). */
    std::vector<HalfSpace>
    parse_half_spaces(const std::string &text)
    {
      std::vector<HalfSpace> planes;
      for (const std::string &item :
           dealii::Utilities::split_string_list(text, ';'))
        {
          const auto parts = dealii::Utilities::split_string_list(item, ',');
          std::vector<double> x;
          try
            {
              for (const std::string &part : parts)
                x.push_back(dealii::Utilities::string_to_double(part));
            }
          catch (...)
            {
              x.clear();
            }
          if (x.size() != 6 ||
              !std::all_of(x.begin(), x.end(), [](const double value) {
                return std::isfinite(value);
              }))
            throw std::runtime_error(
              "Scene/Obstacles/Half-spaces: <" + item +
              "> is not six finite numbers p_x, p_y, p_z, n_x, n_y, n_z" +
              (x.size() > 6 && x.size() % 6 == 0 ?
                 " (half-spaces are separated by ';')." :
                 "."));
          // std::hypot: the norm of a normal of large components does not
          // overflow.
          const double norm = std::hypot(x[3], x[4], x[5]);
          if (!(norm > 0.))
            throw std::runtime_error("Scene/Obstacles/Half-spaces: <" + item +
                                     "> has a zero normal.");
          HalfSpace plane;
          plane.point  = {{x[0], x[1], x[2]}};
          plane.normal = {{x[3] / norm, x[4] / norm, x[5] / norm}};
          planes.push_back(plane);
        }
      return planes;
    }

    /**
     * A square of the plane of @p plane, for output: centred at the
     * projection of the centre of the box around the points of @p q, twice
     * as wide as that box (at least 1). @p corners receives its four corners.
     */
    void
    draw_half_space(const HalfSpace     &plane,
                    const Vector        &q,
                    std::vector<double> &corners)
    {
      Point3 lower = {{q[0], q[1], q[2]}}, upper = lower;
      for (unsigned int i = 0; 3 * i < q.size(); ++i)
        for (unsigned int c = 0; c < 3; ++c)
          {
            lower[c] = std::min(lower[c], q[3 * i + c]);
            upper[c] = std::max(upper[c], q[3 * i + c]);
          }
      const Point3 &n = plane.normal;
      Point3        centre;
      double        size = 0.5, height = 0.;
      for (unsigned int c = 0; c < 3; ++c)
        {
          centre[c] = 0.5 * (lower[c] + upper[c]);
          size      = std::max(size, upper[c] - lower[c]);
          height += (centre[c] - plane.point[c]) * n[c];
        }
      // Two unit vectors of the plane.
      const Point3 a =
        std::abs(n[0]) < 0.9 ? Point3{{1., 0., 0.}} : Point3{{0., 1., 0.}};
      Point3       t1 = {{a[1] * n[2] - a[2] * n[1],
                          a[2] * n[0] - a[0] * n[2],
                          a[0] * n[1] - a[1] * n[0]}};
      const double norm =
        std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
      for (double &x : t1)
        x /= norm;
      const Point3 t2 = {{n[1] * t1[2] - n[2] * t1[1],
                          n[2] * t1[0] - n[0] * t1[2],
                          n[0] * t1[1] - n[1] * t1[0]}};
      for (const auto &[s1, s2] :
           {std::pair{-1., -1.}, {1., -1.}, {1., 1.}, {-1., 1.}})
        for (unsigned int c = 0; c < 3; ++c)
          corners.push_back(centre[c] - height * n[c] +
                            size * (s1 * t1[c] + s2 * t2[c]));
    }

    std::string
    body_section(const unsigned int b)
    {
      return "Body " + std::to_string(b + 1);
    }

    /** Declare a vector field given by a function (FunctionParser). */
    void
    declare_function_entries(dealii::ParameterHandler &prm,
                             const std::string        &what)
    {
      prm.declare_entry("Function expression",
                        "0; 0; 0",
                        dealii::Patterns::Anything(),
                        "The three components of the " + what +
                          ", separated by ';', as functions of the variables "
                          "(deal.II's FunctionParser syntax).");
      prm.declare_entry("Variable names",
                        "x,y,z",
                        dealii::Patterns::Anything(),
                        "The names of the reference coordinates (after the "
                        "placement) in the function expression.");
      prm.declare_entry("Function constants",
                        "",
                        dealii::Patterns::Anything(),
                        "Constants of the function expression, e.g. 'w=2, "
                        "a=0.1'.");
    }

    Vector
    evaluate_function_entries(dealii::ParameterHandler &prm,
                              const std::string        &section,
                              const Vector             &points)
    {
      return evaluate_vector_field(section + "/Function expression",
                                   prm.get("Function expression"),
                                   prm.get("Variable names"),
                                   prm.get("Function constants"),
                                   points);
    }

    void
    declare_body_parameters(dealii::ParameterHandler &prm)
    {
      const double max = dealii::Patterns::Double::max_double_value;
      const dealii::Patterns::List point(dealii::Patterns::Double(-max, max),
                                         3,
                                         3,
                                         ",");
      prm.enter_subsection("Mesh");
      MeshDescription::declare_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("Placement");
      {
        prm.declare_entry("Scale",
                          "1",
                          dealii::Patterns::Double(0., max),
                          "Factor the mesh is scaled by about the origin, "
                          "first.");
        prm.declare_entry("Rotation axis",
                          "0, 0, 1",
                          point,
                          "Axis of the rotation about the origin that "
                          "follows.");
        prm.declare_entry("Rotation angle",
                          "0",
                          dealii::Patterns::Double(-max, max),
                          "Angle of that rotation, in degrees.");
        prm.declare_entry("Shift",
                          "0, 0, 0",
                          point,
                          "Translation applied last (length).");
      }
      prm.leave_subsection();
      prm.enter_subsection("Material");
      declare_material_parameters(prm);
      prm.leave_subsection();
      prm.enter_subsection("Initial velocity");
      {
        prm.declare_entry("Type",
                          "rigid motion",
                          dealii::Patterns::Selection("rigid motion|function"),
                          "rigid motion: v = V + omega x (X - c); function: "
                          "the function below of the placed reference "
                          "coordinates.");
        prm.declare_entry("Translational velocity",
                          "0, 0, 0",
                          point,
                          "V of the rigid motion.");
        prm.declare_entry("Angular velocity",
                          "0, 0, 0",
                          point,
                          "omega of the rigid motion.");
        prm.declare_entry("Rotation centre",
                          "0, 0, 0",
                          point,
                          "c of the rigid motion (placed coordinates).");
        declare_function_entries(prm, "velocity");
      }
      prm.leave_subsection();
      prm.enter_subsection("Initial displacement");
      declare_function_entries(prm, "displacement from the placed mesh");
      prm.leave_subsection();
      prm.declare_entry(
        "Tracked point",
        "",
        dealii::Patterns::Anything(),
        "Placed reference coordinates 'x, y, z' of a point whose current "
        "position the history records (the nearest vertex): columns "
        "body<k>_x, body<k>_y, body<k>_z; empty for none.");
      prm.enter_subsection("Supports");
      {
        prm.declare_entry(
          "Boundary ids",
          "",
          dealii::Patterns::List(dealii::Patterns::Integer(0, 255)),
          "The vertices of the boundary faces with these ids (gmsh physical "
          "tags; deal.II generators' boundary ids) are held fixed.");
        prm.declare_entry(
          "Region",
          "",
          dealii::Patterns::Anything(),
          "An expression of the placed reference coordinates x, y, z (e.g. "
          "'x < 1e-3'): the vertices where it is nonzero are held fixed.");
      }
      prm.leave_subsection();
    }

    void
    declare_scene_parameters(dealii::ParameterHandler &prm)
    {
      const double max = dealii::Patterns::Double::max_double_value;
      prm.enter_subsection("Scene");
      // Declared again after a first reading of the input (see
      // read_parameters in the application): the number it read sizes the
      // body subsections. Read it before declaring resets it.
      unsigned int n_bodies = 1;
      try
        {
          n_bodies = prm.get_integer("Number of bodies");
        }
      catch (...)
        {}
      prm.declare_entry("Number of bodies",
                        "1",
                        dealii::Patterns::Integer(1, 100000),
                        "How many bodies the scene has: each reads its "
                        "subsection Body 1, Body 2, ...");
      prm.declare_entry(
        "Gravity",
        "0, 0, 0",
        dealii::Patterns::List(dealii::Patterns::Double(-max, max), 3, 3, ","),
        "The uniform acceleration of gravity (a potential "
        "-m g.x in V).");
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          prm.enter_subsection(body_section(b));
          declare_body_parameters(prm);
          prm.leave_subsection();
        }
      prm.enter_subsection("Obstacles");
      prm.declare_entry(
        "Half-spaces",
        "",
        dealii::Patterns::Anything(),
        "Rigid half-spaces, separated by ';', each as six numbers 'p_x, p_y, "
        "p_z, n_x, n_y, n_z': a point p of its plane and the normal n "
        "pointing out of the obstacle (towards the bodies).");
      prm.declare_entry(
        "Surface files",
        "",
        dealii::Patterns::Anything(),
        "Rigid obstacles given as triangle surfaces, a comma-separated list "
        "of files: STL (.stl, ASCII or binary) or gmsh surface meshes of "
        "triangles "
        "(.msh), read as they are (no placement; paths relative to the "
        "working directory). The bodies touch them from either side.");
      prm.leave_subsection();
      prm.leave_subsection();
      ContactParameters::declare_parameters(prm);
    }

    /** One body of the scene as its subsection describes it. */
    struct SceneBody
    {
      std::shared_ptr<const ElasticBody> body;
      Vector                             q0, v0;
      std::vector<unsigned int>          fixed_points;
      /** Warnings about its input: a tracked point far from it
       * (tracked_point_warning()), an initial velocity its supports drop. */
      std::vector<std::string> warnings;
    };

    /** The points of @p body at the vertices of its boundary faces with one
     * of @p ids. */
    std::vector<unsigned int>
    points_on_boundary(const ElasticBody            &body,
                       const std::set<unsigned int> &ids)
    {
      const P1CellData      &data = body.cell_data();
      std::set<unsigned int> points;
      for (unsigned int f = 0; f < data.boundary_triangle.size(); ++f)
        if (ids.count(data.boundary_id[f]) > 0)
          points.insert(data.boundary_triangle[f].begin(),
                        data.boundary_triangle[f].end());
      return {points.begin(), points.end()};
    }

    /**
     * The meshes of a scene's bodies, made once for bodies whose Mesh
     * subsections are the same (a scene of many equal balls, each placed
     * elsewhere): the first of them makes it, the others copy it, and the
     * copy is kept only until the last of them.
     */
    class SceneMeshes
    {
    public:
      /** @p descriptions: each body's, in body order. */
      explicit SceneMeshes(const std::vector<MeshDescription> &descriptions)
        : descriptions(descriptions)
      {
        for (unsigned int b = 0; b < descriptions.size(); ++b)
          last_body[descriptions[b].identity()] = b;
      }

      /** Body @p b's mesh into the empty @p tria (errors as make_mesh()'s
       * for @p section). */
      void
      make(const unsigned int        b,
           dealii::Triangulation<3> &tria,
           const std::string        &section)
      {
        const std::string identity = descriptions[b].identity();
        const auto        made     = kept.find(identity);
        if (made != kept.end())
          tria.copy_triangulation(made->second);
        else
          make_mesh(descriptions[b], tria, section);
        if (last_body.at(identity) == b)
          kept.erase(identity);
        else if (made == kept.end())
          kept[identity].copy_triangulation(tria);
      }

    private:
      const std::vector<MeshDescription>              descriptions;
      std::map<std::string, unsigned int>             last_body;
      std::map<std::string, dealii::Triangulation<3>> kept;
    };

    SceneBody
    create_body(dealii::ParameterHandler &prm,
                const unsigned int        b,
                SceneMeshes              &meshes)
    {
      const std::string section = "Scene/" + body_section(b);
      SceneBody         result;
      prm.enter_subsection("Placement");
      const double scale = prm.get_double("Scale");
      const Point3 axis  = parse_point(prm.get("Rotation axis"),
                                      section + "/Placement/Rotation axis");
      const double angle = prm.get_double("Rotation angle");
      const Point3 shift =
        parse_point(prm.get("Shift"), section + "/Placement/Shift");
      prm.leave_subsection();
      if (!(scale > 0.))
        throw std::runtime_error(section +
                                 "/Placement/Scale: must be positive.");
      const dealii::Tensor<1, 3> rotation_axis({axis[0], axis[1], axis[2]});
      if (angle != 0. && !(rotation_axis.norm() > 0.))
        throw std::runtime_error(section +
                                 "/Placement/Rotation axis: must not be "
                                 "zero.");

      prm.enter_subsection("Material");
      const MaterialChoice material =
        parse_material_parameters(prm, section + "/Material");
      prm.leave_subsection();
      const auto make_placed_mesh = [&](dealii::Triangulation<3> &tria) {
        meshes.make(b, tria, section);
        if (scale != 1.)
          dealii::GridTools::scale(scale, tria);
        if (angle != 0.)
          dealii::GridTools::rotate(rotation_axis / rotation_axis.norm(),
                                    angle * M_PI / 180.,
                                    tria);
        dealii::GridTools::shift(
          dealii::Tensor<1, 3>({shift[0], shift[1], shift[2]}), tria);
        // A placement may spoil cells the mesh had right (a shift of 1e30
        // leaves a body of 0.1 flat in double precision).
        if (scale != 1. || angle != 0. || shift[0] != 0. || shift[1] != 0. ||
            shift[2] != 0.)
          try
            {
              check_tetrahedral_mesh(tria);
            }
          catch (const std::exception &error)
            {
              throw std::runtime_error(
                section +
                "/Placement: the placed mesh: " + one_line_message(error));
            }
      };
      auto body = std::make_shared<ElasticBodyWithHessian>(
        make_p1_cell_data_on_first_rank(make_placed_mesh, material.density),
        material.material,
        "body " + std::to_string(b + 1));
      const Vector X = body->reference_configuration();
      if (const std::string tracked = prm.get("Tracked point");
          !tracked.empty())
        {
          const std::array<double, 3> point =
            parse_point(tracked, section + "/Tracked point");
          body->track_point("body" + std::to_string(b + 1), point);
          if (std::string warning =
                tracked_point_warning(*body, section + "/Tracked point", point);
              !warning.empty())
            result.warnings.push_back(std::move(warning));
        }

      prm.enter_subsection("Initial displacement");
      result.q0 = X;
      result.q0 +=
        evaluate_function_entries(prm, section + "/Initial displacement", X);
      prm.leave_subsection();

      prm.enter_subsection("Initial velocity");
      if (prm.get("Type") == "rigid motion")
        result.v0 = body->rigid_velocity(
          X,
          parse_point(prm.get("Translational velocity"),
                      section + "/Initial velocity/Translational velocity"),
          parse_point(prm.get("Angular velocity"),
                      section + "/Initial velocity/Angular velocity"),
          parse_point(prm.get("Rotation centre"),
                      section + "/Initial velocity/Rotation centre"));
      else
        result.v0 =
          evaluate_function_entries(prm, section + "/Initial velocity", X);
      prm.leave_subsection();

      prm.enter_subsection("Supports");
      std::set<unsigned int> ids;
      for (const std::string &id :
           dealii::Utilities::split_string_list(prm.get("Boundary ids"), ','))
        ids.insert(dealii::Utilities::string_to_int(id));
      std::set<unsigned int> fixed;
      for (const unsigned int id : ids)
        {
          const auto points = points_on_boundary(*body, {id});
          if (points.empty())
            throw std::runtime_error(section +
                                     "/Supports/Boundary ids: no boundary "
                                     "face of the body has the id " +
                                     std::to_string(id) + ".");
          fixed.insert(points.begin(), points.end());
        }
      const std::string region = prm.get("Region");
      prm.leave_subsection();
      if (!region.empty())
        {
          const Vector inside = evaluate_vector_field(
            section + "/Supports/Region", region, "x,y,z", "", X, 1);
          std::size_t n_selected = 0;
          for (unsigned int i = 0; i < inside.size(); ++i)
            if (inside[i] != 0.)
              {
                fixed.insert(i);
                ++n_selected;
              }
          if (n_selected == 0)
            throw std::runtime_error(section + "/Supports/Region: <" + region +
                                     "> selects no vertex of the body.");
        }
      if (!fixed.empty() && fixed.size() == body->n_vertices())
        throw std::runtime_error(section +
                                 "/Supports: every vertex of the body is "
                                 "fixed; it has nothing left to move.");
      result.fixed_points.assign(fixed.begin(), fixed.end());
      // A supported vertex does not move: its initial velocity is dropped,
      // with a warning if it had one.
      const double kinetic_energy_before = kinetic_energy(*body, result.v0);
      for (const unsigned int i : result.fixed_points)
        for (unsigned int c = 0; c < 3; ++c)
          result.v0[3 * i + c] = 0.;
      if (const double dropped =
            kinetic_energy_before - kinetic_energy(*body, result.v0);
          dropped > 0.)
        {
          std::ostringstream message;
          message << section << "/Supports: the " << fixed.size()
                  << " vertices they fix start at rest, whatever " << section
                  << "/Initial velocity gives them: of its kinetic "
                  << "energy " << kinetic_energy_before << ", " << dropped
                  << " is dropped.";
          result.warnings.push_back(message.str());
        }
      result.body = body;
      return result;
    }

    /**
     * Throws if a body of the scene after the first has every entry at its
     * default: its subsection is missing from the input (Number of bodies
     * larger than the bodies given), and the default body would join the
     * scene unseen. (The first may be the default body: a scene printed by
     * --print-parameters is a valid input.)
     */
    void
    check_every_body_is_given(const dealii::ParameterHandler &prm,
                              const unsigned int              n_bodies)
    {
      dealii::ParameterHandler defaults;
      defaults.enter_subsection("Scene");
      defaults.enter_subsection(body_section(0));
      declare_body_parameters(defaults);
      defaults.leave_subsection();
      defaults.leave_subsection();
      const std::vector<std::string> default_body =
        printed_subsections(defaults, "Scene")[body_section(0)];
      auto sections = printed_subsections(prm, "Scene");
      for (unsigned int b = 1; b < n_bodies; ++b)
        if (sections[body_section(b)] == default_body)
          throw std::runtime_error(
            "Scene/" + body_section(b) +
            ": not given (every entry at its default); Number of bodies = " +
            std::to_string(n_bodies) + " asks for the subsections Body 1 to " +
            body_section(n_bodies - 1) + ".");
    }

    Problem
    create_scene_problem(dealii::ParameterHandler &prm)
    {
      prm.enter_subsection("Scene");
      const unsigned int n_bodies = prm.get_integer("Number of bodies");
      check_every_body_is_given(prm, n_bodies);
      const Point3 gravity = parse_point(prm.get("Gravity"), "Scene/Gravity");
      std::vector<MeshDescription> descriptions(n_bodies);
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          prm.enter_subsection(body_section(b));
          prm.enter_subsection("Mesh");
          descriptions[b].parse_parameters(prm);
          prm.leave_subsection();
          prm.leave_subsection();
        }
      SceneMeshes            meshes(descriptions);
      std::vector<SceneBody> bodies;
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          prm.enter_subsection(body_section(b));
          bodies.push_back(create_body(prm, b, meshes));
          prm.leave_subsection();
        }
      prm.enter_subsection("Obstacles");
      const std::string              half_spaces = prm.get("Half-spaces");
      const std::vector<std::string> surface_files =
        dealii::Utilities::split_string_list(prm.get("Surface files"), ',');
      prm.leave_subsection();
      prm.leave_subsection();
      ContactParameters contact;
      contact.parse_parameters(prm);

      const std::vector<HalfSpace> planes = parse_half_spaces(half_spaces);
      std::vector<StaticSurface>   surfaces;
      unsigned int                 n_surface_triangles = 0;
      for (const std::string &file : surface_files)
        {
          try
            {
              surfaces.push_back(read_static_surface(file));
            }
          catch (const std::exception &e)
            {
              throw std::runtime_error("Scene/Obstacles/Surface files: " +
                                       std::string(e.what()));
            }
          n_surface_triangles += surfaces.back().triangles.size();
        }
      const bool has_obstacles = !planes.empty() || !surfaces.empty();

      std::vector<std::shared_ptr<const ElasticBody>> body_list;
      std::vector<Vector>                             q, v;
      for (const SceneBody &b : bodies)
        {
          body_list.push_back(b.body);
          q.push_back(b.q0);
          v.push_back(b.v0);
        }
      const bool contact_on = contact.mode != ContactParameters::Mode::none;
      if (contact_on && n_bodies == 1 && !contact.self_contact &&
          !has_obstacles)
        throw std::runtime_error(
          "Contact/Mode: a scene of one body without obstacles has nothing "
          "to contact; set Mode = none (or Self contact = true).");
      if (!contact_on && has_obstacles)
        throw std::runtime_error(
          "Scene/Obstacles: the obstacles need a contact model; set "
          "Contact/Mode = impenetrability or penalty.");

      // The bodies' own system: the body alone, or the bodies in contact.
      std::shared_ptr<const MechanicalSystem> system;
      std::shared_ptr<const ElasticBodies>    bodies_system;
      std::shared_ptr<const ContactSystem>    contact_system;
      std::vector<unsigned int>               offsets(n_bodies, 0);
      Vector                                  q0, v0;
      if (n_bodies == 1 && !contact_on)
        {
          system        = body_list[0];
          bodies_system = body_list[0];
          q0            = q[0];
          v0            = v[0];
        }
      else
        {
          contact_system = std::make_shared<ContactSystem>(body_list,
                                                           surfaces,
                                                           contact,
                                                           "scene");
          system         = contact_system;
          bodies_system  = contact_system;
          q0             = contact_system->concatenate(q);
          v0             = contact_system->concatenate_velocities(v);
          for (unsigned int b = 0; b < n_bodies; ++b)
            offsets[b] = contact_system->point_offset(b);
          // Bodies whose boundaries cross overlap, and so does a body inside
          // another. Boundaries that touch cannot start impenetrable
          // contact: its pairs at a distance of exactly zero have no side
          // (two cubes placed flush stalled at t = 0, or passed into each
          // other).
          const auto name = [&](const unsigned int b) {
            return b >= n_bodies ?
                     "obstacle " + contact_system->surface(b - n_bodies).name :
                     body_section(b);
          };
          const auto meetings = contact_system->meeting_bodies(q0);
          for (const auto &[b1, b2, crossing] : meetings)
            if (crossing)
              throw std::runtime_error(
                b2 >= n_bodies ?
                  "Scene: " + name(b1) + " intersects " + name(b2) +
                    " at t = 0 (their triangles cross); move the body or "
                    "the surface." :
                b1 == b2 ? "Scene/" + name(b1) +
                             ": its boundary intersects itself at t = 0." :
                           "Scene: " + name(b1) + " and " + name(b2) +
                             " overlap at t = 0 (their boundaries cross); "
                             "move them apart.");
          if (const auto nested = contact_system->nested_bodies(q0))
            throw std::runtime_error("Scene: " + name(nested->first) +
                                     " lies inside " + name(nested->second) +
                                     " at t = 0; move them apart.");
          if (!meetings.empty() &&
              contact.mode == ContactParameters::Mode::impenetrability)
            {
              const ContactSystem::Meeting &touch = meetings.front();
              throw std::runtime_error(
                "Scene: " + name(touch.first) + " touches " +
                (touch.first == touch.second ? "itself" : name(touch.second)) +
                " at t = 0 (faces flush, or a vertex or an edge on a face); "
                "impenetrable contact needs a gap at the start, however "
                "small (1e-9 of their size will do).");
            }
        }

      // Decorations: obstacles, gravity, supports.
      std::shared_ptr<const HalfSpaceObstacles> obstacles;
      std::shared_ptr<const SupportedSystem>    supported;
      if (!planes.empty())
        {
          double longest_edge = 0.;
          for (unsigned int b = 0; b < n_bodies; ++b)
            longest_edge =
              std::max(longest_edge, contact_system->penetration_limit(b, b));
          obstacles = std::make_shared<HalfSpaceObstacles>(
            system,
            planes,
            boundary_points(*contact_system),
            contact.mode == ContactParameters::Mode::penalty ?
              HalfSpaceObstacles::Mode::penalty :
              HalfSpaceObstacles::Mode::impenetrability,
            contact.penalty_parameter,
            longest_edge);
          if (const auto first = obstacles->first_point_deeper_than(q0, 0.))
            throw std::runtime_error(
              "Scene/Obstacles: " +
              std::to_string(obstacles->n_points_behind(q0)) +
              " boundary vertices of the bodies lie inside an obstacle at t = "
              "0, among them vertices of " +
              body_section(contact_system->body_of_point(first->point)) +
              " behind half-space " + std::to_string(first->half_space + 1) +
              " of Scene/Obstacles/Half-spaces; move the bodies or the "
              "obstacles.");
          system = obstacles;
        }
      // The surfaces' points carry no weight: their mass is a placeholder.
      if (gravity[0] != 0. || gravity[1] != 0. || gravity[2] != 0.)
        system = std::make_shared<Gravity>(system,
                                           gravity,
                                           contact_system ?
                                             contact_system->surface_points() :
                                             std::vector<unsigned int>());
      std::vector<unsigned int> fixed;
      for (unsigned int b = 0; b < n_bodies; ++b)
        for (const unsigned int i : bodies[b].fixed_points)
          fixed.push_back(offsets[b] + i);
      // The surfaces' points never move.
      if (contact_system)
        for (const unsigned int i : contact_system->surface_points())
          fixed.push_back(i);
      Scene::StateMap to_bodies =
        [](const Vector &q, const Vector &v, Vector &qb, Vector &vb) {
          qb = q;
          vb = v;
        };
      Problem problem;
      // The whole configuration (with the vertices supports hold and the
      // obstacles' points) and the boundary triangles.
      problem.geometry_checksum =
        checksum(q0.data(), q0.size() * sizeof(double));
      if (contact_system)
        {
          const auto &triangles = contact_system->boundary_triangles();
          problem.geometry_checksum =
            checksum(triangles.data(),
                     triangles.size() * sizeof(triangles[0]),
                     problem.geometry_checksum);
        }
      if (!fixed.empty())
        {
          supported  = std::make_shared<SupportedSystem>(system, fixed, q0);
          problem.q0 = supported->restrict(q0);
          problem.v0 = supported->restrict(v0);
          to_bodies  = [supported](const Vector &q,
                                  const Vector &v,
                                  Vector       &qb,
                                  Vector       &vb) {
            qb = supported->expand(q);
            vb = supported->expand_velocity(v);
          };
          system = supported;
        }
      else
        {
          problem.q0 = q0;
          problem.v0 = v0;
        }

      const auto n_supported_vertices = static_cast<unsigned int>(
        fixed.size() -
        (contact_system ? contact_system->surface_points().size() : 0));
      unsigned int n_cells = 0;
      for (const auto &b : body_list)
        n_cells += b->n_cells();
      problem.description.add("bodies", n_bodies)
        .add("cells", n_cells)
        .add("fixed vertices", n_supported_vertices)
        .add("gravity", std::vector<double>(gravity.begin(), gravity.end()))
        .add("obstacles", static_cast<unsigned int>(planes.size()))
        .add("surface obstacles", static_cast<unsigned int>(surfaces.size()))
        .add("surface obstacle triangles", n_surface_triangles)
        .add("contact", ContactParameters::mode_name(contact.mode));
      if (rank_count() > 1)
        {
          std::vector<const P1CellData *> cells;
          for (const auto &b : body_list)
            cells.push_back(&b->cell_data());
          problem.description.add("cells held by each process",
                                  cells_held_on_each_rank(cells));
        }
      auto scene = std::make_unique<Scene>(system,
                                           bodies_system,
                                           std::move(to_bodies),
                                           "scene",
                                           n_supported_vertices > 0);
      if (obstacles)
        scene->set_obstacle_count([obstacles, supported](const Vector &q) {
          return obstacles->n_points_behind(supported ? supported->expand(q) :
                                                        q);
        });
      for (const HalfSpace &plane : planes)
        {
          std::vector<double> corners;
          draw_half_space(plane, q0, corners);
          scene->add_obstacle_surface(corners, {0, 1, 2, 0, 2, 3});
        }
      for (const StaticSurface &surface : surfaces)
        {
          std::vector<unsigned int> triangles;
          for (const auto &t : surface.triangles)
            triangles.insert(triangles.end(), t.begin(), t.end());
          scene->add_obstacle_surface(surface.points, triangles);
        }
      problem.system = std::move(scene);
      // Entries that the chosen mesh and velocity types do not read.
      std::vector<TypedSubsection> typed;
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          const std::string section = "Scene/" + body_section(b);
          typed.push_back({section + "/Mesh", MeshDescription::type_readers()});
          typed.push_back(
            {section + "/Initial velocity", initial_velocity_type_readers()});
        }
      if (!surfaces.empty() && contact.mode == ContactParameters::Mode::penalty)
        problem.warnings.push_back(
          "Scene/Obstacles/Surface files with Contact/Mode = penalty: the penalty "
          "between triangle pairs is not a penetration depth (a body can pass "
          "through a thin surface), and surface triangles much larger than "
          "the bodies' faces can stall the search at the first contact "
          "(doc/scenes.md); Mode = impenetrability treats surfaces exactly.");
      for (const SceneBody &b : bodies)
        problem.warnings.insert(problem.warnings.end(),
                                b.warnings.begin(),
                                b.warnings.end());
      const std::vector<std::string> unread =
        entries_unread_by_type(prm, typed);
      problem.warnings.insert(problem.warnings.end(),
                              unread.begin(),
                              unread.end());
      return problem;
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_PROBLEM(
  "scene",
  "Any number of elastic bodies (subsection Scene: Body 1, Body 2, ...), "
  "each with its mesh, placement, material, initial state and supports, "
  "under gravity, in contact with each other and with rigid obstacles "
  "(subsection Contact).",
  estep::declare_scene_parameters,
  estep::create_scene_problem)
