// What it costs the first process to describe every process's part of a
// body's mesh at the start of an MPI run: deal.II's
// TriangulationDescription::Utilities::create_description_from_triangulation()
// once per process, each call a sweep of the whole mesh (O(P N) in all),
// against RankDescriptions, one sweep and then each process's part alone
// (O(N)). For the centred cube of 98,304 and 786,432 cells shared among P
// processes in runs of whole blocks, as the runs share it, this prints the
// seconds of each for all P processes, their ratio, and whether the two gave
// the same cells and vertices for every process; and the seconds of the
// other per-process part of the first process's setup, the chunks of cells
// each process holds (chunks_held_by_ranks(), one pass over the cells). It
// runs as one process: the descriptions are made for processes that need not
// exist.
//
// Usage: build/benchmarks/benchmark_fem_rank_descriptions
//        [largest subdivision, default 32] [P ..., default 2 8 32]
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/meshes.h>
#include <estep/fem/p1_cell_data.h>
#include <estep/fem/rank_descriptions.h>

#include "seconds_since.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

using benchmark_timing::seconds_since;

int
main(int argc, char **argv)
{
  const unsigned int        largest = argc > 1 ? std::atoi(argv[1]) : 32;
  std::vector<unsigned int> processes;
  for (int i = 2; i < argc; ++i)
    processes.push_back(std::atoi(argv[i]));
  if (processes.empty())
    processes = {2, 8, 32};

  std::printf("describing every process's part of the centred cube on the "
              "first process: deal.II's sweep per process against one "
              "sweep (RankDescriptions)\n");
  std::printf("%9s %6s %14s %14s %8s %10s %6s %10s\n",
              "cells",
              "P",
              "deal.II: s",
              "one sweep: s",
              "ratio",
              "cells/own",
              "same",
              "chunks: s");
  for (unsigned int n = 16; n <= largest; n *= 2)
    {
      dealii::Triangulation<3> mesh;
      estep::make_seed_cube_mesh(mesh, n);
      const unsigned int      n_cells = mesh.n_active_cells();
      const estep::P1CellData data    = estep::make_p1_cell_data(mesh, 0.1);
      for (const unsigned int p : processes)
        {
          const std::vector<unsigned int> cell_rank =
            estep::cell_ranks(n_cells, p);
          for (const auto &cell : mesh.active_cell_iterators())
            cell->set_subdomain_id(cell_rank[cell->index()]);

          // Each kept only for the comparison of cells and vertices.
          std::vector<std::vector<dealii::types::coarse_cell_id>> theirs_cells(
            p);
          std::vector<std::size_t> theirs_vertices(p);
          auto                     start = std::chrono::steady_clock::now();
          for (unsigned int r = 0; r < p; ++r)
            {
              const auto d = dealii::TriangulationDescription::Utilities::
                create_description_from_triangulation(
                  mesh,
                  MPI_COMM_WORLD,
                  dealii::TriangulationDescription::Settings::default_setting,
                  r);
              theirs_cells[r]    = d.coarse_cell_index_to_coarse_cell_id;
              theirs_vertices[r] = d.coarse_cell_vertices.size();
            }
          const double theirs = seconds_since(start);

          bool        same  = true;
          std::size_t taken = 0;
          start             = std::chrono::steady_clock::now();
          const estep::RankDescriptions descriptions(mesh, cell_rank, p);
          for (unsigned int r = 0; r < p; ++r)
            {
              const auto d = descriptions.describe(r);
              same         = same &&
                     d.coarse_cell_index_to_coarse_cell_id == theirs_cells[r] &&
                     d.coarse_cell_vertices.size() == theirs_vertices[r];
              taken += d.coarse_cells.size();
            }
          const double ours = seconds_since(start);

          start = std::chrono::steady_clock::now();
          const std::vector<std::vector<unsigned int>> held =
            estep::chunks_held_by_ranks(data, p);
          const double chunks = seconds_since(start);
          std::printf("%9u %6u %14.3f %14.3f %8.1f %10.3f %6s %10.3f\n",
                      n_cells,
                      p,
                      theirs,
                      ours,
                      theirs / ours,
                      double(taken) / n_cells,
                      same ? "yes" : "NO",
                      chunks);
          std::fflush(stdout);
        }
    }
  return 0;
}
