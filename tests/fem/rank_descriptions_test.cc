// The descriptions of the ranks' parts of a mesh are deal.II's own, field for
// field: those that create_description_from_triangulation() makes of the mesh
// partitioned by subdomain ids, for each rank of several partitions of a ball
// of gmsh (along its Hilbert curve, as the runs partition it, and in
// interleaved runs, whose ranks' cells lie all over the ball).

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/mesh_description.h>
#include <estep/fem/meshes.h>
#include <estep/fem/rank_descriptions.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace
{
  using Description = dealii::TriangulationDescription::Description<3, 3>;

  /** @p d with the manifold ids of the lines and faces a hexahedron has and
   * a tetrahedron has not set flat: deal.II leaves them uninitialized. */
  Description
  tetrahedral_entries_only(Description d)
  {
    for (auto &info : d.cell_infos[0])
      {
        std::fill(info.manifold_line_ids.begin() + 6,
                  info.manifold_line_ids.end(),
                  dealii::numbers::flat_manifold_id);
        std::fill(info.manifold_quad_ids.begin() + 4,
                  info.manifold_quad_ids.end(),
                  dealii::numbers::flat_manifold_id);
      }
    return d;
  }

  /** Each rank's description against deal.II's, for the partition
   * @p cell_rank of @p mesh among @p n_ranks ranks. */
  void
  expect_deal_ii_descriptions(dealii::Triangulation<3, 3>     &mesh,
                              const std::vector<unsigned int> &cell_rank,
                              const unsigned int               n_ranks,
                              const std::string               &what)
  {
    for (const auto &cell : mesh.active_cell_iterators())
      cell->set_subdomain_id(cell_rank[cell->index()]);
    const estep::RankDescriptions descriptions(mesh, cell_rank, n_ranks);
    unsigned int                  taken = 0;
    for (unsigned int r = 0; r < n_ranks; ++r)
      {
        const Description ours =
          tetrahedral_entries_only(descriptions.describe(r));
        const Description theirs = tetrahedral_entries_only(
          dealii::TriangulationDescription::Utilities::
            create_description_from_triangulation(
              mesh,
              MPI_COMM_WORLD,
              dealii::TriangulationDescription::Settings::default_setting,
              r));
        EXPECT_EQ(ours.coarse_cell_index_to_coarse_cell_id,
                  theirs.coarse_cell_index_to_coarse_cell_id)
          << what << ", rank " << r;
        EXPECT_EQ(ours.coarse_cell_vertices.size(),
                  theirs.coarse_cell_vertices.size())
          << what << ", rank " << r;
        EXPECT_TRUE(ours == theirs) << what << ", rank " << r;
        EXPECT_EQ(descriptions.cells_of(r),
                  ours.coarse_cell_index_to_coarse_cell_id);
        taken += descriptions.cells_of(r).size();
      }
    // A ghost layer on each side of every boundary between ranks.
    if (n_ranks > 1)
      {
        EXPECT_GT(taken, mesh.n_active_cells()) << what;
      }
  }

  TEST(RankDescriptions, DealIIsOwnForEachRank)
  {
    estep::MeshDescription d;
    d.type      = "ball";
    d.mesh_size = 0.15;
    dealii::Triangulation<3> mesh;
    estep::make_mesh(d, mesh);
    const unsigned int n_cells = mesh.n_active_cells();
    ASSERT_GT(estep::n_blocks(n_cells), 3u);
    for (const unsigned int n_ranks : {1u, 2u, 3u, 5u})
      {
        // As the runs share the cells: runs of whole blocks.
        std::vector<unsigned int> cell_rank =
          estep::cell_ranks(n_cells, n_ranks);
        expect_deal_ii_descriptions(mesh,
                                    cell_rank,
                                    n_ranks,
                                    std::to_string(n_ranks) + " ranks");
        // Interleaved runs of 100 cells: a rank's cells all over the ball.
        for (unsigned int e = 0; e < n_cells; ++e)
          cell_rank[e] = (e / 100) % n_ranks;
        expect_deal_ii_descriptions(mesh,
                                    cell_rank,
                                    n_ranks,
                                    std::to_string(n_ranks) +
                                      " ranks, interleaved");
      }
  }

  TEST(RankDescriptions, ARankOutOfRangeIsAnError)
  {
    dealii::Triangulation<3> mesh;
    estep::make_mesh(estep::MeshDescription{}, mesh);
    std::vector<unsigned int> cell_rank(mesh.n_active_cells(), 0);
    cell_rank.back() = 2;
    EXPECT_THROW(estep::RankDescriptions(mesh, cell_rank, 2), std::exception);
  }
} // namespace
