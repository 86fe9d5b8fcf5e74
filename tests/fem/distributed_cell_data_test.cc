// The cells each MPI rank holds: its blocks and exactly the later cells its
// points' gradient needs, whole chunks of them (checked by brute force on the
// seed cube, for 1, 2, 3, 5, 12 and 13 ranks); on one process, every cell's
// data is the data itself.

#include <estep/base/distributed_blocks.h>
#include <estep/fem/distributed_cell_data.h>

#include <gtest/gtest.h>

#include "test_bodies.h"

#include <algorithm>

namespace
{
  using estep::block_size;
  using estep::BlockRange;

  TEST(CellsHeldByRanks, ItsBlocksAndExactlyTheChunksItsPointsNeed)
  {
    const estep::P1CellData &data     = estep_test::seed_cube().cell_data();
    const unsigned int       n_padded = data.n_padded_cells();
    const unsigned int       n_blocks = estep::n_blocks(n_padded);
    ASSERT_EQ(n_blocks, 12u);
    constexpr unsigned int chunk = estep::P1CellData::gradient_chunk;
    // Each point's first cell, by brute force.
    std::vector<unsigned int> first_cell(data.n_points, n_padded);
    for (unsigned int e = 0; e < n_padded; ++e)
      for (unsigned int a = 0; a < 4; ++a)
        first_cell[data.point[a][e]] =
          std::min(first_cell[data.point[a][e]], e);
    EXPECT_EQ(data.first_cell, first_cell);
    for (const unsigned int n_ranks : {1u, 2u, 3u, 5u, 12u, 13u})
      {
        const std::vector<BlockRange> held =
          estep::cells_held_by_ranks(data, n_ranks);
        ASSERT_EQ(held.size(), n_ranks);
        // What each rank must hold, by brute force: its blocks, and the chunk
        // of every cell that touches one of its points.
        std::vector<BlockRange>   needed(n_ranks);
        std::vector<unsigned int> block_rank(n_blocks);
        for (unsigned int r = 0; r < n_ranks; ++r)
          {
            const BlockRange blocks = estep::rank_blocks(n_blocks, r, n_ranks);
            for (unsigned int b = blocks.begin; b < blocks.end; ++b)
              block_rank[b] = r;
            needed[r] = {std::min(blocks.begin * block_size, n_padded),
                         std::min(blocks.end * block_size, n_padded)};
          }
        for (unsigned int e = 0; e < n_padded; ++e)
          for (unsigned int a = 0; a < 4; ++a)
            {
              const unsigned int r =
                block_rank[first_cell[data.point[a][e]] / block_size];
              EXPECT_LE(needed[r].begin, e);
              needed[r].end =
                std::max(needed[r].end,
                         std::min((e / chunk + 1) * chunk, n_padded));
            }
        unsigned int total = 0, empty = 0;
        for (unsigned int r = 0; r < n_ranks; ++r)
          {
            EXPECT_EQ(held[r].begin, needed[r].begin)
              << n_ranks << " ranks, rank " << r;
            EXPECT_EQ(held[r].end, needed[r].end)
              << n_ranks << " ranks, rank " << r;
            total += held[r].end - held[r].begin;
            empty += held[r].begin == held[r].end;
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
            EXPECT_EQ(held[0].end - held[0].begin, n_padded / 2 + n_padded / 8);
            EXPECT_EQ(held[1].end - held[1].begin, n_padded / 2);
          }
      }
  }

  TEST(GatherEveryCell, OnOneProcessTheDataItself)
  {
    const estep::P1CellData &data  = estep_test::seed_cube().cell_data();
    const estep::P1CellData  every = estep::gather_every_cell(data);
    EXPECT_EQ(every.held_begin, 0u);
    EXPECT_EQ(every.volume, data.volume);
    for (unsigned int a = 0; a < 4; ++a)
      EXPECT_EQ(every.point[a], data.point[a]);
    EXPECT_EQ(&estep_test::seed_cube().every_cell_data(), &data);
  }
} // namespace
