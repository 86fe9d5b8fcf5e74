#ifndef estep_fem_p1_cell_data_h
#define estep_fem_p1_cell_data_h

#include <array>
#include <functional>
#include <vector>

namespace dealii
{
  template <int dim, int spacedim>
  class Triangulation;
} // namespace dealii

namespace estep
{
  /**
   * What ElasticBody needs about a mesh of linear (P1) tetrahedra, computed
   * once from deal.II and stored as plain arrays (structure of arrays, one
   * entry per cell): the body keeps no deal.II mesh, and in a run on several
   * MPI ranks only the first builds one and sends the others these arrays.
   *
   * Points are the mesh vertices, numbered as the DoFHandler of
   * FESystem<3>(FE_SimplexP<3>(1), 3) numbers its vertex degrees of freedom:
   * component c of point i is degree of freedom 3 i + c, so a coordinate vector
   * of the body is also a deal.II finite-element vector (positions,
   * point-major).
   *
   * For cell e with points p_0..p_3 (in deal.II's vertex order) and reference
   * positions X_0..X_3, let D_m = [X_1 - X_0 | X_2 - X_0 | X_3 - X_0] and B =
   * D_m^{-1}. Row a of B is the reference gradient dN_{a+1}/dX of the shape
   * function of vertex a + 1, and dN_0/dX = -sum of the rows. The deformation
   * gradient of positions x is F = [x_1 - x_0 | x_2 - x_0 | x_3 - x_0] B.
   *
   * The per-cell arrays are padded to a whole number of batches of four cells
   * (n_padded_cells() entries; see Lanes): the padding repeats the last cell
   * with volume 0, so that it adds nothing to sums over cells.
   */
  struct P1CellData
  {
    /** Number of cells (tetrahedra). */
    unsigned int n_cells = 0;

    /** The length of the per-cell arrays: n_cells rounded up to a multiple
     * of 4. */
    unsigned int
    n_padded_cells() const
    {
      return (n_cells + 3) / 4 * 4;
    }

    /** Number of points (vertices). */
    unsigned int n_points = 0;

    /** point[a][e]: point index of vertex a of cell e. */
    std::array<std::vector<unsigned int>, 4> point;

    /** shape_gradient[3 a + j][e] = B_aj = dN_{a+1}/dX_j on cell e (units
     * 1/length). */
    std::array<std::vector<double>, 9> shape_gradient;

    /** Reference volume of each cell (positive). */
    std::vector<double> volume;

    /** Reference positions, point-major: X[3 i + c]. */
    std::vector<double> reference_position;

    /** Lumped mass of each point (row sums of the consistent mass matrix). */
    std::vector<double> lumped_mass;

    /** The boundary faces as triples of points, oriented so that (x_1 - x_0)
     * x (x_2 - x_0) points out of the body, in the order of the cells and
     * their faces. */
    std::vector<std::array<unsigned int, 3>> boundary_triangle;

    /** The boundary id of each of them. */
    std::vector<unsigned int> boundary_id;
  };



  /**
   * The P1CellData of the tetrahedral mesh @p tria, of mass density
   * @p density: the geometry from the vertices, the lumped mass from deal.II
   * (FE_SimplexP, QGaussSimplex, MappingFE), checked against the geometry.
   * Throws dealii::ExcMessage if the mesh has non-tetrahedral, inverted or
   * degenerate cells, or a vertex in no cell.
   */
  P1CellData
  make_p1_cell_data(const dealii::Triangulation<3, 3> &tria,
                    const double                       density);



  /**
   * make_p1_cell_data() of the mesh that @p make_mesh builds, on every rank
   * of a run on several MPI ranks (distributed_blocks.h) while only the first
   * builds the mesh, the others receiving the arrays: so no other rank ever
   * holds a deal.II mesh of the whole body. What the first rank throws,
   * every rank throws, with the same message. Collective.
   */
  P1CellData
  make_p1_cell_data_on_first_rank(
    const std::function<void(dealii::Triangulation<3, 3> &)> &make_mesh,
    const double                                              density);
} // namespace estep

#endif
