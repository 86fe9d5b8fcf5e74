#ifndef estep_fem_mesh_description_h
#define estep_fem_mesh_description_h

#include <estep/base/parameter_subsections.h>

#include <array>
#include <string>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
  class ParameterHandler;
} // namespace dealii

namespace estep
{
  /**
   * A tetrahedral mesh described by a type name and parameters, as read from a
   * parameter file. make_mesh() builds it. The types:
   *
   * - "box": a box of hexahedra split into tetrahedra
   * (make_seed_cube_mesh()): the box
   * [lower, upper] divided into n_subdivisions^3 hexahedra, 24 tetrahedra each
   * (n_subdivisions = 8 on the unit cube: 12,288 cells, 2,969 vertices). Uses
   * n_subdivisions, lower, upper.
   * - "deal.II": a deal.II hexahedral generator,
   * GridGenerator::generate_from_name_and_arguments (generator, arguments),
   * refined n_refinements times, then converted with
   *   GridGenerator::convert_hypercube_to_simplex_mesh (curved manifolds are
   * not kept: the conversion sees the refined vertices).
   * - "deal.II 24": the same generator and refinements, split with
   *   split_hexahedra_into_24_tetrahedra() (as "box").
   * - "ball": a ball of the given radius about the origin, meshed by gmsh
   *   with the given mesh size relative to the radius (make_ball_mesh()).
   * - "gmsh": a gmsh .msh file (formats 2 and 4 that deal.II's GridIn::read_msh
   * reads), of tetrahedra; uses file_name.
   *
   * For every type the mesh is then translated by @p shift. The result is
   * checked with check_tetrahedral_mesh().
   */
  struct MeshDescription
  {
    /** "box", "ball", "deal.II", "deal.II 24" or "gmsh". */
    std::string type = "box";

    /** box: hexahedra per direction (>= 1). */
    unsigned int n_subdivisions = 8;

    /** box: its lower corner. */
    std::array<double, 3> lower = {{0., 0., 0.}};

    /** box: its upper corner. */
    std::array<double, 3> upper = {{1., 1., 1.}};

    /** ball: its radius. */
    double radius = 1.;

    /** ball: the target edge length relative to the radius. */
    double mesh_size = 0.3;

    /** deal.II types: name of the GridGenerator function (e.g. "hyper_ball").
     */
    std::string generator = "hyper_cube";

    /**
     * deal.II types: its arguments in deal.II's
     * generate_from_name_and_arguments format, e.g. "0, 0, 0 : 1 : false" for
     * hyper_ball (centre : radius : attach manifolds) or "0 : 1 : false" for
     * hyper_cube.
     */
    std::string arguments = "0 : 1 : false";

    /** deal.II types: global refinements of the hexahedral mesh before
     * conversion. */
    unsigned int n_refinements = 0;

    /** gmsh: the .msh file. */
    std::string file_name;

    /** Translation applied to the mesh at the end. */
    std::array<double, 3> shift = {{0., 0., 0.}};

    /** Declare the entries (in the current subsection of @p prm), with
     * documentation. */
    static void
    declare_parameters(dealii::ParameterHandler &prm);

    /** Read the entries declared by declare_parameters(). */
    void
    parse_parameters(const dealii::ParameterHandler &prm);

    /** Every entry above as text, to the last bit: equal exactly for
     * descriptions of the same mesh (an entry added above must join it). */
    std::string
    identity() const;

    /** Each entry that only some types read, with those types (for
     * entries_unread_by_type()). */
    static TypeReaders
    type_readers();
  };

  /**
   * Build the mesh described by @p description into the empty @p tria. Throws
   * dealii::ExcMessage with one clear message for an unknown type, bad
   * arguments, a missing or unreadable file (a gmsh file is first checked
   * with check_gmsh_file()), and non-tetrahedral, inverted or degenerate
   * cells (numbered as the mesher or the file numbers them). A mesh other
   * than a box then goes through order_cells_compactly().
   */
  void
  make_mesh(const MeshDescription       &description,
            dealii::Triangulation<3, 3> &tria);

  /**
   * make_mesh() for the mesh read from the subsection @p section/Mesh of an
   * input file: its errors are one std::runtime_error naming that entry
   * ("Elastic body/Mesh: ...").
   */
  void
  make_mesh(const MeshDescription       &description,
            dealii::Triangulation<3, 3> &tria,
            const std::string           &section);
} // namespace estep

#endif
