// The cells each MPI rank holds: its blocks and exactly the later cells its
// points' gradient needs, whole chunks of them (checked by brute force on the
// seed cube, for 1, 2, 3, 5, 12 and 13 ranks); on one process, every cell's
// data is the data itself.

#include <deal.II/grid/tria.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/mesh_description.h>
#include <estep/fem/p1_cell_data.h>

#include <gtest/gtest.h>

#include "test_bodies.h"

#include <algorithm>
#include <array>
#include <iostream>
#include <vector>

namespace
{
  using estep::block_size;
  using estep::BlockRange;

  /** What each of @p n_ranks ranks must hold, by brute force: the chunks of
   * its blocks, and the chunk of every cell that touches a point whose first
   * cell (recomputed here) lies in its blocks. */
  std::vector<std::vector<unsigned int>>
  chunks_needed(const estep::P1CellData &data, const unsigned int n_ranks)
  {
    const unsigned int        n_padded = data.n_padded_cells();
    const unsigned int        n_blocks = estep::n_blocks(n_padded);
    constexpr unsigned int    chunk    = estep::P1CellData::gradient_chunk;
    std::vector<unsigned int> first_cell(data.n_points, n_padded);
    for (unsigned int e = 0; e < n_padded; ++e)
      for (unsigned int a = 0; a < 4; ++a)
        first_cell[data.point[a][e]] =
          std::min(first_cell[data.point[a][e]], e);
    EXPECT_EQ(data.first_cell, first_cell);
    std::vector<unsigned int> block_rank(n_blocks);
    for (unsigned int r = 0; r < n_ranks; ++r)
      {
        const BlockRange blocks = estep::rank_blocks(n_blocks, r, n_ranks);
        for (unsigned int b = blocks.begin; b < blocks.end; ++b)
          block_rank[b] = r;
      }
    std::vector<std::vector<unsigned int>> needed(n_ranks);
    const auto need = [&](const unsigned int r, const unsigned int c) {
      if (std::find(needed[r].begin(), needed[r].end(), c) == needed[r].end())
        needed[r].push_back(c);
    };
    for (unsigned int e = 0; e < n_padded; ++e)
      {
        need(block_rank[e / block_size], e / chunk);
        for (unsigned int a = 0; a < 4; ++a)
          need(block_rank[first_cell[data.point[a][e]] / block_size],
               e / chunk);
      }
    for (auto &chunks : needed)
      std::sort(chunks.begin(), chunks.end());
    return needed;
  }

  TEST(ChunksHeldByRanks, ItsBlocksAndExactlyTheChunksItsPointsNeed)
  {
    const estep::P1CellData &data     = estep_test::seed_cube().cell_data();
    const unsigned int       n_padded = data.n_padded_cells();
    const unsigned int       n_blocks = estep::n_blocks(n_padded);
    ASSERT_EQ(n_blocks, 12u);
    EXPECT_EQ(data.held_chunks().size(), data.n_chunks());
    for (const unsigned int n_ranks : {1u, 2u, 3u, 5u, 12u, 13u})
      {
        const std::vector<std::vector<unsigned int>> held =
          estep::chunks_held_by_ranks(data, n_ranks);
        EXPECT_EQ(held, chunks_needed(data, n_ranks)) << n_ranks << " ranks";
        unsigned int total = 0, empty = 0;
        for (unsigned int r = 0; r < held.size(); ++r)
          {
            total += data.n_cells_in(held[r]);
            empty += held[r].empty();
          }
        EXPECT_EQ(empty, n_ranks > n_blocks ? n_ranks - n_blocks : 0u);
        if (n_ranks == 1)
          {
            EXPECT_EQ(total, n_padded);
          }
        if (n_ranks == 2)
          {
            // The box is numbered layer by layer: each rank holds its half
            // and the first rank one layer of hexahedra more (1,536 cells).
            EXPECT_EQ(data.n_cells_in(held[0]), n_padded / 2 + n_padded / 8);
            EXPECT_EQ(data.n_cells_in(held[1]), n_padded / 2);
          }
      }
  }

  /** The cells that the ranks of 2 and of 4 hold on the mesh that @p d
   * describes, in all, relative to its cells; each rank holding less than
   * twice its own. */
  std::array<double, 2>
  held_cells_in_all(const estep::MeshDescription &d)
  {
    dealii::Triangulation<3> tria;
    estep::make_mesh(d, tria);
    const estep::P1CellData data     = estep::make_p1_cell_data(tria, 1.);
    const unsigned int      n_padded = data.n_padded_cells();
    EXPECT_GT(estep::n_blocks(n_padded), 12u);
    std::array<double, 2> in_all{};
    for (const unsigned int k : {0u, 1u})
      {
        const unsigned int                           n_ranks = 2 * (k + 1);
        const std::vector<std::vector<unsigned int>> held =
          estep::chunks_held_by_ranks(data, n_ranks);
        EXPECT_EQ(held, chunks_needed(data, n_ranks)) << n_ranks << " ranks";
        for (unsigned int r = 0; r < n_ranks; ++r)
          {
            const BlockRange own = estep::rank_cells(n_padded, r, n_ranks);
            EXPECT_LT(data.n_cells_in(held[r]), 2 * (own.end - own.begin))
              << n_ranks << " ranks, rank " << r;
            in_all[k] += data.n_cells_in(held[r]);
          }
        in_all[k] /= n_padded;
      }
    std::cout << d.type << ": the ranks of 2 hold " << in_all[0]
              << " times the cells in all, those of 4 " << in_all[1]
              << std::endl;
    return in_all;
  }

  // gmsh numbers a ball's cells in no compact order: before make_mesh() put
  // them in the order of a Hilbert curve, the first of 2 ranks held (and
  // computed the gradient of) nearly every cell of a ball of gmsh. Along the
  // curve, each rank holds its cells and a layer of the others' (1.11 and
  // 1.25 times the cells in all for 2 and 4 ranks).
  TEST(ChunksHeldByRanks, ABallOfGmshInCompactRuns)
  {
    estep::MeshDescription d;
    d.type      = "ball";
    d.mesh_size = 0.08;
    for (const double in_all : held_cells_in_all(d))
      EXPECT_LT(in_all, 1.3);
  }

  // A bar ten times as long as it is thick (15,360 cells): the curve runs
  // through the cube that holds the bar, so that a rank's cells are a length
  // of it: 1.05 and 1.16 times the cells in all for 2 and 4 ranks. They were
  // 1.08 and 1.27 when ranks held chunks of 128 cells, not 8; with chunks of
  // 128, and each axis scaled to its own extent, the runs cut across the bar
  // (1.24 and 1.63), and in the generator's order (1.28 and 1.85).
  TEST(ChunksHeldByRanks, ABarInLengths)
  {
    estep::MeshDescription d;
    d.type      = "deal.II 24";
    d.generator = "subdivided_hyper_rectangle";
    d.arguments = "40, 4, 4 : 0, 0, 0 : 1, 0.1, 0.1 : false";
    const std::array<double, 2> in_all = held_cells_in_all(d);
    EXPECT_LT(in_all[0], 1.07);
    EXPECT_LT(in_all[1], 1.2);
  }

  TEST(GatherEveryCell, OnOneProcessTheDataItself)
  {
    const estep::P1CellData &data  = estep_test::seed_cube().cell_data();
    const estep::P1CellData  every = estep::gather_every_cell(data);
    EXPECT_EQ(every.chunk_start, data.chunk_start);
    EXPECT_EQ(every.volume, data.volume);
    for (unsigned int a = 0; a < 4; ++a)
      EXPECT_EQ(every.point[a], data.point[a]);
    EXPECT_EQ(&estep_test::seed_cube().every_cell_data(), &data);
  }
} // namespace
