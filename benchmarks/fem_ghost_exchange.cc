// What the exchange of point values between MPI processes costs now, and
// what it would cost with a distributed state. Now every process holds the
// whole state, so after each gradient every process receives every point's
// gradient (gather_from_all_ranks(), one MPI_Allgatherv, as ElasticBody does).
// With a distributed state a process would keep only the points its cells
// read: its own (those whose first cell lies in its blocks) and, as ghosts,
// the other points of the chunks of cells it holds (chunks_held_by_ranks()),
// and receive only the ghosts' values from their owners: deal.II's
// LinearAlgebra::distributed::Vector::update_ghost_values() over a
// Utilities::MPI::Partitioner of these index sets. For the centred cube at
// 12,288 / 98,304 / 786,432 cells, this prints per process the points it
// owns and its ghosts, the doubles each exchange brings it, the time of
// each (the fastest of three rounds of repeated calls), their ratio, and
// whether the ghosts received their owners' values.
//
// Usage: mpirun -np P build/benchmarks/benchmark_fem_ghost_exchange
//        [largest subdivision, default 32] [calls per round, default 200]
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/meshes.h>
#include <estep/fem/p1_cell_data.h>

#include "fastest_of_rounds.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

namespace
{
  /** The value point coordinate @p i holds in this benchmark. */
  double
  value_of(const dealii::types::global_dof_index i)
  {
    return 0.5 * static_cast<double>(i) + 1.;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  estep::distribute_blocks_over_mpi_ranks();
  const unsigned int ranks   = estep::rank_count();
  const unsigned int me      = estep::this_rank();
  const unsigned int largest = argc > 1 ? std::atoi(argv[1]) : 32;
  const unsigned int calls   = argc > 2 ? std::atoi(argv[2]) : 200;
  if (me == 0)
    {
      std::printf("the gradient's exchange on %u MPI processes, centred "
                  "cube: the gather of every point (now) against deal.II's "
                  "ghost update of a distributed state\n",
                  ranks);
      std::printf("%9s %8s %5s %8s %8s %14s %14s %12s %12s %7s %9s\n",
                  "cells",
                  "points",
                  "rank",
                  "owned",
                  "ghosts",
                  "gather: recv",
                  "ghosts: recv",
                  "gather: us",
                  "ghosts: us",
                  "ratio",
                  "correct");
    }
  for (unsigned int n = 8; n <= largest; n *= 2)
    {
      dealii::Triangulation<3> tria;
      estep::make_seed_cube_mesh(tria, n);
      const estep::P1CellData data = estep::make_p1_cell_data(tria, 0.1);
      tria.clear();

      // Own points: those whose first cell is in this rank's cells. The
      // points are numbered in the order of their first cells, so each
      // rank's are one range, in rank order.
      const std::vector<unsigned int> cell_rank =
        estep::cell_ranks(data.n_cells);
      std::vector<unsigned int> points_per_rank(ranks, 0);
      for (unsigned int p = 0; p < data.n_points; ++p)
        ++points_per_rank[cell_rank[data.first_cell[p]]];
      unsigned int first_own = 0;
      for (unsigned int r = 0; r < me; ++r)
        first_own += points_per_rank[r];
      const unsigned int n_own = points_per_rank[me];
      for (unsigned int p = first_own; p < first_own + n_own; ++p)
        if (cell_rank[data.first_cell[p]] != me)
          {
            std::fprintf(stderr, "the own points are not one range\n");
            return 1;
          }

      // Ghosts: the other points of the chunks this rank holds.
      const std::vector<unsigned int> held =
        estep::chunks_held_by_ranks(data, ranks)[me];
      std::vector<bool> read(data.n_points, false);
      for (const unsigned int c : held)
        {
          const estep::BlockRange cells = data.chunk_cells(c);
          for (unsigned int e = cells.begin;
               e < std::min(cells.end, data.n_cells);
               ++e)
            for (unsigned int a = 0; a < 4; ++a)
              read[data.point[a][data.at(e)]] = true;
        }
      dealii::IndexSet owned(3 * data.n_points), ghosts(3 * data.n_points);
      owned.add_range(3 * first_own, 3 * (first_own + n_own));
      unsigned int n_ghosts = 0;
      for (unsigned int p = 0; p < data.n_points; ++p)
        if (read[p] && (p < first_own || p >= first_own + n_own))
          {
            ghosts.add_range(3 * p, 3 * p + 3);
            ++n_ghosts;
          }
      const auto partitioner =
        std::make_shared<dealii::Utilities::MPI::Partitioner>(owned,
                                                              ghosts,
                                                              MPI_COMM_WORLD);
      dealii::LinearAlgebra::distributed::Vector<double> state(partitioner);
      for (const auto i : owned)
        state[i] = value_of(i);

      // Now: each rank's own values to every rank.
      std::vector<unsigned int> doubles_per_rank(ranks);
      for (unsigned int r = 0; r < ranks; ++r)
        doubles_per_rank[r] = 3 * points_per_rank[r];
      std::vector<double> mine(3 * n_own), all(3 * data.n_points);
      for (unsigned int k = 0; k < mine.size(); ++k)
        mine[k] = value_of(3 * first_own + k);
      const double gather       = benchmark_mpi::seconds_per_call(calls, [&]() {
        estep::gather_from_all_ranks(mine.data(), doubles_per_rank, all.data());
      });
      const double ghost_update = benchmark_mpi::seconds_per_call(calls, [&]() {
        state.zero_out_ghost_values();
        state.update_ghost_values();
      });

      bool correct = true;
      for (const auto i : ghosts)
        correct = correct && state[i] == value_of(i);
      for (unsigned int i = 0; i < all.size(); ++i)
        correct = correct && all[i] == value_of(i);
      correct = dealii::Utilities::MPI::min(correct ? 1 : 0, MPI_COMM_WORLD);

      // One line per rank, in rank order.
      const std::vector<unsigned int> owned_of =
        dealii::Utilities::MPI::gather(MPI_COMM_WORLD, n_own);
      const std::vector<unsigned int> ghosts_of =
        dealii::Utilities::MPI::gather(MPI_COMM_WORLD, n_ghosts);
      if (me == 0)
        for (unsigned int r = 0; r < ranks; ++r)
          std::printf("%9u %8u %5u %8u %8u %14u %14u %12.1f %12.1f %7.1f %9s\n",
                      data.n_cells,
                      data.n_points,
                      r,
                      owned_of[r],
                      ghosts_of[r],
                      3 * (data.n_points - owned_of[r]),
                      3 * ghosts_of[r],
                      1e6 * gather,
                      1e6 * ghost_update,
                      gather / ghost_update,
                      correct ? "yes" : "NO");
    }
  return 0;
}
