// Two partitions of a body's blocks of cells among MPI ranks, compared by
// what each rank must hold: estep's, contiguous runs of whole blocks in the
// cell order (block_ranks()), against METIS on the graph of blocks that
// share a point (deal.II's SparsityTools::partition, weighted by the cells of
// each block), which also keeps every block whole. For the 98,304-cell cube
// (layer by layer) and the 152,424-cell ball of gmsh along the Hilbert curve
// (order_cells_compactly()), on 2 and 4 ranks: the cells all ranks hold
// together (their own and the chunks their gradient needs,
// chunks_held_by_ranks()) relative to the cells, the most any rank holds
// relative to its own, and the largest share of cells relative to the mean.
// Serial: the ranks are counted, not started.
//
// Usage: build/benchmarks/benchmark_fem_partitions
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/ball_mesh.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/meshes.h>
#include <estep/fem/p1_cell_data.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace
{
  using estep::block_size;

  /** METIS's partition of the blocks of @p data into @p n_ranks parts. */
  std::vector<unsigned int>
  metis_block_ranks(const estep::P1CellData &data, const unsigned int n_ranks)
  {
    const unsigned int n_blocks = estep::n_blocks(data.n_padded_cells());
    dealii::DynamicSparsityPattern         graph(n_blocks, n_blocks);
    std::vector<std::vector<unsigned int>> blocks_of_point(data.n_points);
    for (unsigned int e = 0; e < data.n_cells; ++e)
      for (unsigned int a = 0; a < 4; ++a)
        blocks_of_point[data.point[a][data.at(e)]].push_back(e / block_size);
    for (const std::vector<unsigned int> &blocks : blocks_of_point)
      for (const unsigned int i : blocks)
        for (const unsigned int j : blocks)
          if (i != j)
            graph.add(i, j);
    dealii::SparsityPattern pattern;
    pattern.copy_from(graph);
    std::vector<unsigned int> cells(n_blocks), rank(n_blocks);
    for (unsigned int b = 0; b < n_blocks; ++b)
      cells[b] = std::min((b + 1) * block_size, data.n_cells) - b * block_size;
    dealii::SparsityTools::partition(
      pattern, cells, n_ranks, rank, dealii::SparsityTools::Partitioner::metis);
    return rank;
  }

  /** One row of the table: what the ranks hold under @p block_rank. */
  void
  print_row(const char                      *body,
            const char                      *partition,
            const estep::P1CellData         &data,
            const std::vector<unsigned int> &block_rank,
            const unsigned int               n_ranks)
  {
    const std::vector<std::vector<unsigned int>> held =
      estep::chunks_held_by_ranks(data, block_rank, n_ranks);
    std::vector<double> own(n_ranks, 0.);
    for (unsigned int e = 0; e < data.n_cells; ++e)
      own[block_rank[e / block_size]] += 1.;
    double all = 0., most_held = 0., most_own = 0.;
    for (unsigned int r = 0; r < n_ranks; ++r)
      {
        const double n = data.n_cells_in(held[r]);
        all += n;
        most_held = std::max(most_held, n / own[r]);
        most_own  = std::max(most_own, own[r]);
      }
    std::printf("| %s | %u | %s | %.3f | %.3f | %.3f |\n",
                body,
                n_ranks,
                partition,
                all / data.n_cells,
                most_held,
                most_own * n_ranks / data.n_cells);
  }

  void
  compare(const char *body, const dealii::Triangulation<3> &tria)
  {
    const estep::P1CellData data     = estep::make_p1_cell_data(tria, 1.);
    const unsigned int      n_blocks = estep::n_blocks(data.n_padded_cells());
    for (const unsigned int n_ranks : {2u, 4u})
      {
        print_row(body,
                  "runs in cell order",
                  data,
                  estep::block_ranks(n_blocks, n_ranks),
                  n_ranks);
        print_row(
          body, "METIS", data, metis_block_ranks(data, n_ranks), n_ranks);
      }
  }
} // namespace

int
main()
{
  std::printf("| body | ranks | partition of the blocks | cells held by all / "
              "cells | most held / own | largest share / mean |\n"
              "|---|---:|---|---:|---:|---:|\n");
  {
    dealii::Triangulation<3> cube;
    estep::make_seed_cube_mesh(cube, 16);
    compare("cube, 98,304 cells", cube);
  }
  {
    dealii::Triangulation<3> ball;
    estep::make_ball_mesh(ball, 0.05);
    estep::order_cells_compactly(ball);
    compare("ball of gmsh, 152,424 cells", ball);
  }
}
