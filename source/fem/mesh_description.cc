#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/patterns.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <estep/base/exception_text.h>
#include <estep/base/point_entry.h>
#include <estep/fem/ball_mesh.h>
#include <estep/fem/gmsh_check.h>
#include <estep/fem/mesh_description.h>
#include <estep/fem/meshes.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>

namespace estep
{
  namespace
  {
    std::string
    print_point(const std::array<double, 3> &p)
    {
      return dealii::Utilities::to_string(p[0]) + ", " +
             dealii::Utilities::to_string(p[1]) + ", " +
             dealii::Utilities::to_string(p[2]);
    }

    /**
     * The hexahedra a subdividing generator (subdivided_hyper_cube,
     * subdivided_hyper_rectangle) will make, counted from its first argument,
     * the subdivisions, before it runs: deal.II reads them as unsigned
     * integers (-1 becomes 4294967295) and allocates for them before any
     * check of its own. Throws if they are not positive integers; none for
     * other generators.
     */
    std::optional<double>
    subdivided_hexahedra(const MeshDescription &d)
    {
      if (d.generator != "subdivided_hyper_cube" &&
          d.generator != "subdivided_hyper_rectangle")
        return std::nullopt;
      const std::string subdivisions =
        dealii::Utilities::trim(d.arguments.substr(
          0, std::min(d.arguments.find(':'), d.arguments.size())));
      double       hexahedra = 1.;
      unsigned int n_numbers = 0;
      for (const std::string &word :
           dealii::Utilities::split_string_list(subdivisions, ','))
        {
          const bool digits =
            !word.empty() &&
            word.find_first_not_of("0123456789") == std::string::npos;
          // (strtod: a number beyond double range is infinite, no throw.)
          const double n = digits ? std::strtod(word.c_str(), nullptr) : 0.;
          if (!(n >= 1.))
            throw std::runtime_error("Generator arguments: the subdivisions <" +
                                     subdivisions + "> of " + d.generator +
                                     " must be positive integers.");
          hexahedra *= n;
          ++n_numbers;
        }
      return n_numbers == 1 ? std::pow(hexahedra, 3.) : hexahedra;
    }

    void
    throw_if_too_many_cells(const MeshDescription &d, const double hexahedra)
    {
      const double cells =
        24. * hexahedra * std::pow(8., static_cast<double>(d.n_refinements));
      if (cells <= max_generated_mesh_cells)
        return;
      std::ostringstream message;
      message << "Mesh: the deal.II generator '" << d.generator << "' with "
              << d.n_refinements << " refinements would make about " << cells
              << " tetrahedra (24 per hexahedron), more than "
              << max_generated_mesh_cells
              << "; take fewer refinements or a coarser mesh.";
      AssertThrow(false, dealii::ExcMessage(message.str()));
    }

    void
    make_hexahedral(const MeshDescription &d, dealii::Triangulation<3, 3> &hex)
    {
      if (const auto hexahedra = subdivided_hexahedra(d))
        throw_if_too_many_cells(d, *hexahedra);
      try
        {
          dealii::GridGenerator::generate_from_name_and_arguments(hex,
                                                                  d.generator,
                                                                  d.arguments);
        }
      catch (const std::exception &e)
        {
          // deal.II names the arguments' pattern, a tuple of so many parts
          // separated by ':': say first how many the entry gives.
          const std::string what = one_line_message(e);
          std::string       count;
          std::smatch       tuple;
          if (std::regex_search(what,
                                tuple,
                                std::regex("Tuple of <([0-9]+)> elements")))
            if (const std::size_t given =
                  dealii::Utilities::split_string_list(d.arguments, ':').size();
                std::to_string(given) != tuple[1].str())
              count = "it takes " + tuple[1].str() +
                      " arguments separated by ':', and these are " +
                      std::to_string(given) + ". ";
          AssertThrow(false,
                      dealii::ExcMessage("Mesh: the deal.II generator '" +
                                         d.generator + "' with arguments '" +
                                         d.arguments + "' failed: " + count +
                                         what));
        }
      throw_if_too_many_cells(d, hex.n_active_cells());
      hex.refine_global(d.n_refinements);
    }
  } // namespace

  void
  MeshDescription::declare_parameters(dealii::ParameterHandler &prm)
  {
    const MeshDescription defaults;
    prm.declare_entry(
      "Type",
      defaults.type,
      dealii::Patterns::Selection("box|ball|deal.II|deal.II 24|gmsh"),
      "How the tetrahedral mesh is made: 'box' (a box divided into n^3 "
      "hexahedra of 24 tetrahedra each), 'ball' (a ball of radius R about the "
      "origin meshed by gmsh), 'deal.II' (a deal.II hexahedral generator "
      "converted with convert_hypercube_to_simplex_mesh), 'deal.II 24' (the "
      "same generator with every hexahedron split into 24 tetrahedra, as in "
      "'box'), or 'gmsh' (a .msh file of tetrahedra).");
    prm.declare_entry(
      "Subdivisions",
      std::to_string(defaults.n_subdivisions),
      dealii::Patterns::Integer(1),
      "box: number of hexahedra per direction (8: the spinning cube's "
      "mesh of 12,288 tetrahedra).");
    prm.declare_entry("Lower corner",
                      print_point(defaults.lower),
                      dealii::Patterns::List(dealii::Patterns::Double(), 3, 3),
                      "box: its lower corner (length).");
    prm.declare_entry("Upper corner",
                      print_point(defaults.upper),
                      dealii::Patterns::List(dealii::Patterns::Double(), 3, 3),
                      "box: its upper corner (length).");
    prm.declare_entry("Radius",
                      std::to_string(defaults.radius),
                      dealii::Patterns::Double(0.),
                      "ball: its radius (length).");
    prm.declare_entry("Mesh size",
                      std::to_string(defaults.mesh_size),
                      dealii::Patterns::Double(0.),
                      "ball: the target edge length relative to the radius "
                      "(0.3: 898 tetrahedra).");
    prm.declare_entry(
      "Generator",
      defaults.generator,
      dealii::Patterns::Anything(),
      "deal.II, deal.II 24: name of the GridGenerator function, e.g. "
      "hyper_cube, hyper_ball, subdivided_hyper_rectangle.");
    prm.declare_entry(
      "Generator arguments",
      defaults.arguments,
      dealii::Patterns::Anything(),
      "deal.II, deal.II 24: arguments of the generator in the format of "
      "GridGenerator::generate_from_name_and_arguments, e.g. "
      "'0, 0, 0 : 1 : false' for hyper_ball (centre : radius : manifolds).");
    prm.declare_entry(
      "Refinements",
      std::to_string(defaults.n_refinements),
      dealii::Patterns::Integer(0, 10),
      "deal.II, deal.II 24: global refinements of the hexahedral mesh before "
      "its conversion to tetrahedra.");
    prm.declare_entry(
      "File name",
      defaults.file_name,
      dealii::Patterns::Anything(),
      "gmsh: the .msh file (gmsh formats 2 or 4) of tetrahedra.");
    prm.declare_entry(
      "Shift",
      print_point(defaults.shift),
      dealii::Patterns::List(dealii::Patterns::Double(), 3, 3),
      "Translation applied to the mesh after it is made (length).");
  }

  void
  MeshDescription::parse_parameters(const dealii::ParameterHandler &prm)
  {
    type           = prm.get("Type");
    n_subdivisions = prm.get_integer("Subdivisions");
    lower          = parse_point(prm.get("Lower corner"), "Mesh/Lower corner");
    upper          = parse_point(prm.get("Upper corner"), "Mesh/Upper corner");
    radius         = prm.get_double("Radius");
    mesh_size      = prm.get_double("Mesh size");
    generator      = prm.get("Generator");
    arguments      = prm.get("Generator arguments");
    n_refinements  = prm.get_integer("Refinements");
    file_name      = prm.get("File name");
    shift          = parse_point(prm.get("Shift"), "Mesh/Shift");
  }

  std::string
  MeshDescription::identity() const
  {
    std::ostringstream text;
    text.precision(17);
    text << type << '|' << n_subdivisions << '|' << radius << '|' << mesh_size
         << '|' << generator << '|' << arguments << '|' << n_refinements << '|'
         << file_name;
    for (const std::array<double, 3> &point : {lower, upper, shift})
      for (const double x : point)
        text << '|' << x;
    return text.str();
  }

  TypeReaders
  MeshDescription::type_readers()
  {
    const std::vector<std::string> generated = {"deal.II", "deal.II 24"};
    return {{"Subdivisions", {"box"}},
            {"Lower corner", {"box"}},
            {"Upper corner", {"box"}},
            {"Radius", {"ball"}},
            {"Mesh size", {"ball"}},
            {"Generator", generated},
            {"Generator arguments", generated},
            {"Refinements", generated},
            {"File name", {"gmsh"}}};
  }

  void
  make_mesh(const MeshDescription &d, dealii::Triangulation<3, 3> &tria)
  {
    if (d.type == "box")
      {
        const double cells = 24. * std::pow(double(d.n_subdivisions), 3);
        if (!(cells <= max_generated_mesh_cells))
          {
            std::ostringstream message;
            message << "Mesh: a box of " << d.n_subdivisions
                    << " subdivisions would make " << cells
                    << " tetrahedra (24 n^3), more than "
                    << max_generated_mesh_cells
                    << "; Subdivisions must be at most "
                    << static_cast<unsigned int>(
                         std::cbrt(max_generated_mesh_cells / 24.))
                    << ".";
            AssertThrow(false, dealii::ExcMessage(message.str()));
          }
        make_seed_cube_mesh(tria, d.n_subdivisions, d.lower, d.upper);
      }
    else if (d.type == "ball")
      {
        AssertThrow(d.radius > 0. && d.mesh_size > 0.,
                    dealii::ExcMessage(
                      "Mesh: a ball needs a positive radius and mesh size."));
        try
          {
            make_ball_mesh(tria, d.mesh_size, d.radius);
          }
        catch (const std::exception &e)
          {
            AssertThrow(false,
                        dealii::ExcMessage("Mesh: " + one_line_message(e)));
          }
      }
    else if (d.type == "deal.II" || d.type == "deal.II 24")
      {
        dealii::Triangulation<3, 3> hex;
        make_hexahedral(d, hex);
        if (d.type == "deal.II")
          dealii::GridGenerator::convert_hypercube_to_simplex_mesh(hex, tria);
        else
          {
            // split works on the coarsest level: flatten the refined mesh
            // first.
            dealii::Triangulation<3, 3> flat;
            dealii::GridGenerator::flatten_triangulation(hex, flat);
            split_hexahedra_into_24_tetrahedra(flat, tria);
          }
      }
    else if (d.type == "gmsh")
      {
        AssertThrow(!d.file_name.empty(),
                    dealii::ExcMessage("Mesh: type 'gmsh' needs a file name."));
        AssertThrow(!std::filesystem::is_directory(d.file_name),
                    dealii::ExcMessage("Mesh: the gmsh file '" + d.file_name +
                                       "' is a directory, not a file."));
        std::ifstream file(d.file_name);
        AssertThrow(file.good(),
                    dealii::ExcMessage("Mesh: cannot open the gmsh file '" +
                                       d.file_name +
                                       "' (missing or unreadable)."));
        dealii::GridIn<3, 3> grid_in(tria);
        try
          {
            check_gmsh_file(d.file_name, 3);
            grid_in.read_msh(file);
          }
        catch (const std::exception &e)
          {
            AssertThrow(false,
                        dealii::ExcMessage(
                          "Mesh: cannot read the gmsh file '" + d.file_name +
                          "' as a .msh mesh: " + one_line_message(e)));
          }
      }
    else
      AssertThrow(false,
                  dealii::ExcMessage(
                    "Mesh: unknown type '" + d.type +
                    "' (known: box, ball, deal.II, deal.II 24, gmsh)."));

    if (d.shift[0] != 0. || d.shift[1] != 0. || d.shift[2] != 0.)
      dealii::GridTools::shift(
        dealii::Tensor<1, 3>({d.shift[0], d.shift[1], d.shift[2]}), tria);
    check_tetrahedral_mesh(tria);
    // The box is made layer by layer, the other meshes in their mesher's
    // order, which need not be compact.
    if (d.type != "box")
      order_cells_compactly(tria);
  }


  void
  make_mesh(const MeshDescription       &description,
            dealii::Triangulation<3, 3> &tria,
            const std::string           &section)
  {
    try
      {
        make_mesh(description, tria);
      }
    catch (const std::exception &e)
      {
        std::string message = one_line_message(e);
        if (message.rfind("Mesh: ", 0) == 0)
          message.erase(0, 6);
        throw std::runtime_error(section + "/Mesh: " + message);
      }
  }
} // namespace estep
