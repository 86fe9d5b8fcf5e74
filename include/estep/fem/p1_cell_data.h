#ifndef estep_fem_p1_cell_data_h
#define estep_fem_p1_cell_data_h

#include <estep/base/parallel_blocks.h>

#include <array>
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
   * entry per cell): the body keeps no deal.II mesh.
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
   * The cells are padded to a whole number of batches of four
   * (n_padded_cells(); see Lanes): the padding repeats the last cell with
   * volume 0, so that it adds nothing to sums over cells. The per-cell arrays
   * hold whole chunks of gradient_chunk of these cells (the last one cut to
   * n_padded_cells()), in the order of the cells, entry at(e) for cell e: all
   * of them, but on each of several MPI ranks only those it computes
   * (distributed_cell_data.h).
   */
  struct P1CellData
  {
    /** The per-cell arrays hold cells, and the parts of ElasticBody's
     * gradient on several threads and processes compute them, in chunks of
     * this many (a multiple of 4): the widest vector of the material's batch
     * call, 8 doubles, whose vector and scalar parts round differently. A run
     * of whole chunks puts every cell at the place modulo 8 that it has in
     * the serial loop's batch calls (see Material::volumetric_derivatives()).
     */
    static constexpr unsigned int gradient_chunk = 8;

    /** Number of cells (tetrahedra). */
    unsigned int n_cells = 0;

    /** n_cells rounded up to a multiple of 4. */
    unsigned int
    n_padded_cells() const
    {
      return (n_cells + 3) / 4 * 4;
    }

    /** The number of chunks of gradient_chunk cells of the padded cells. */
    unsigned int
    n_chunks() const
    {
      return n_blocks(n_padded_cells(), gradient_chunk);
    }

    /** The cells of chunk @p c. */
    BlockRange
    chunk_cells(const unsigned int c) const
    {
      return block_range(c, n_padded_cells(), gradient_chunk);
    }

    /** chunk_start[c]: where the first cell of chunk c is in the per-cell
     * arrays, or not_held. */
    std::vector<unsigned int> chunk_start;

    /** The chunk_start of a chunk the per-cell arrays do not hold. */
    static constexpr unsigned int not_held = ~0u;

    /** Let the per-cell arrays hold the chunks @p chunks (increasing), one
     * after the other, and no others: sets chunk_start. */
    void
    hold_chunks(const std::vector<unsigned int> &chunks);

    /** hold_chunks() of every chunk. */
    void
    hold_every_chunk();

    /** The chunks the per-cell arrays hold, in increasing order. */
    std::vector<unsigned int>
    held_chunks() const;

    /** The number of entries of the per-cell arrays: the cells of the held
     * chunks, padding included. */
    unsigned int
    n_held_cells() const;

    /** The number of cells (the padding aside) in the chunks @p chunks. */
    unsigned int
    n_cells_in(const std::vector<unsigned int> &chunks) const;

    /** Whether the per-cell arrays hold the cells @p cells, one after the
     * other (whole chunks or parts of them). */
    bool
    holds(const BlockRange cells) const;

    /** Where cell @p e is in the per-cell arrays (of a held chunk). */
    unsigned int
    at(const unsigned int e) const
    {
      return chunk_start[e / gradient_chunk] + e % gradient_chunk;
    }

    /** Number of points (vertices). */
    unsigned int n_points = 0;

    /** point[a][at(e)]: point index of vertex a of cell e. */
    std::array<std::vector<unsigned int>, 4> point;

    /** shape_gradient[3 a + j][at(e)] = B_aj = dN_{a+1}/dX_j on cell e (units
     * 1/length). */
    std::array<std::vector<double>, 9> shape_gradient;

    /** Reference volume of each cell (positive), at at(e). */
    std::vector<double> volume;

    /** The volume of the body: the sum of all cells' volumes, in cell order.
     */
    double total_volume = 0.;

    /** Reference positions, point-major: X[3 i + c]. */
    std::vector<double> reference_position;

    /** The mass density the lumped masses are of (mass per unit reference
     * volume). */
    double density = 0.;

    /** Lumped mass of each point (row sums of the consistent mass matrix). */
    std::vector<double> lumped_mass;

    /** The first cell of each point: the lowest-numbered cell it is a vertex
     * of. On several threads or ranks the one that computes this cell
     * computes the point's gradient. */
    std::vector<unsigned int> first_cell;

    /** The boundary faces as triples of points, oriented so that (x_1 - x_0)
     * x (x_2 - x_0) points out of the body, in the order of the cells and
     * their faces. */
    std::vector<std::array<unsigned int, 3>> boundary_triangle;

    /** The boundary id of each of them. */
    std::vector<unsigned int> boundary_id;

    /** Apply @p f to each per-cell array (those indexed by at(e)). */
    template <typename F>
    void
    for_each_cell_array(const F &f)
    {
      for (auto &v : point)
        f(v);
      for (auto &v : shape_gradient)
        f(v);
      f(volume);
    }

    /** The same, read only. */
    template <typename F>
    void
    for_each_cell_array(const F &f) const
    {
      for (const auto &v : point)
        f(v);
      for (const auto &v : shape_gradient)
        f(v);
      f(volume);
    }
  };



  /**
   * The geometry of a cell with vertices @p x (reference positions, in
   * deal.II's vertex order) into entry @p h of the per-cell arrays of
   * @p data: shape_gradient from B = D_m^{-1} and volume det D_m / 6 (the
   * points are the caller's). The one formula for every way the arrays are
   * made, so that they hold the same bits.
   */
  void
  set_cell_geometry(P1CellData                                 &data,
                    const unsigned int                          h,
                    const std::array<std::array<double, 3>, 4> &x);

  /**
   * The P1CellData of the tetrahedral mesh @p tria, of mass density
   * @p density: the geometry from the vertices, the lumped mass from deal.II
   * (FE_SimplexP, QGaussSimplex, MappingFE), checked against the geometry.
   * Throws dealii::ExcMessage if @p density is not positive or the mesh has
   * non-tetrahedral, inverted or degenerate cells.
   */
  P1CellData
  make_p1_cell_data(const dealii::Triangulation<3, 3> &tria,
                    const double                       density);
} // namespace estep

#endif
