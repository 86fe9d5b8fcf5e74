#ifndef estep_fem_distributed_cell_data_h
#define estep_fem_distributed_cell_data_h

#include <estep/base/parallel_blocks.h>
#include <estep/fem/p1_cell_data.h>

#include <functional>
#include <vector>

/**
 * @file
 * The P1CellData of a body in a run on several MPI ranks
 * (distributed_blocks.h): the first rank alone builds the serial mesh and
 * its per-point arrays, which every rank receives whole with the boundary;
 * each rank takes its cells from a
 * dealii::parallel::fullydistributed::Triangulation of its own cells and
 * their ghost layer, built from deal.II's description of the serial mesh.
 */

namespace estep
{
  /**
   * The chunks of cells (P1CellData::gradient_chunk) each of @p n_ranks ranks
   * holds, in increasing order, from @p data holding every cell: rank r holds
   * the chunks of its blocks (rank_blocks()) and every chunk with a cell that
   * touches a point whose first cell lies in its blocks (ElasticBody's
   * gradient computes these points' forces from all their cells, chunk by
   * chunk). None for a rank without blocks.
   */
  std::vector<std::vector<unsigned int>>
  chunks_held_by_ranks(const P1CellData &data, const unsigned int n_ranks);

  /**
   * The same for any partition of the blocks among @p n_ranks ranks:
   * @p block_rank holds the rank of each block of cells.
   */
  std::vector<std::vector<unsigned int>>
  chunks_held_by_ranks(const P1CellData                &data,
                       const std::vector<unsigned int> &block_rank,
                       const unsigned int               n_ranks);

  /**
   * make_p1_cell_data() of the mesh that @p make_mesh builds, of which every
   * rank holds its part. Only the first rank builds the mesh and the arrays;
   * it sends each rank the per-point arrays and the boundary, and deal.II's
   * description (TriangulationDescription) of the rank's cells, those of its
   * blocks, and their ghost layer, from the mesh partitioned by blocks
   * (block_ranks()), with the point of each of the description's vertices.
   * Each rank
   * builds a dealii::parallel::fullydistributed::Triangulation from it and
   * computes the per-cell arrays of the chunks chunks_held_by_ranks() gives
   * it from that mesh's cells; the cells of those chunks beyond the ghost
   * layer, which only the gradient reads for points of other ranks, are
   * inert stand-ins of volume 0. So no other rank ever holds a deal.II mesh
   * of the whole body or every cell's data, and the arrays hold the same bits
   * as make_p1_cell_data()'s. What the first rank throws, every rank throws,
   * with the same message. On one rank, simply make_p1_cell_data().
   * Collective.
   */
  P1CellData
  make_p1_cell_data_on_first_rank(
    const std::function<void(dealii::Triangulation<3, 3> &)> &make_mesh,
    const double                                              density);

  /**
   * The cells (the padding aside) whose data each rank holds, summed over
   * @p bodies, in rank order: its own and the chunks its gradient needs
   * (chunks_held_by_ranks()). Collective.
   */
  std::vector<double>
  cells_held_on_each_rank(const std::vector<const P1CellData *> &bodies);

  /**
   * The P1CellData of every cell, on every rank, from the ranks' parts
   * @p data (each sends the cells of its blocks). A copy of @p data if it
   * holds every cell. Collective when it does not.
   */
  P1CellData
  gather_every_cell(const P1CellData &data);
} // namespace estep

#endif
