#include <deal.II/grid/cell_id.h>
#include <deal.II/grid/tria_accessor.h>
#include <deal.II/grid/tria_iterator.h>

#include <estep/fem/rank_descriptions.h>

#include <algorithm>
#include <string>
#include <utility>

namespace estep
{
  RankDescriptions::RankDescriptions(const dealii::Triangulation<3, 3> &mesh,
                                     std::vector<unsigned int> cell_rank,
                                     const unsigned int        n_ranks)
    : mesh(mesh)
    , cell_rank(std::move(cell_rank))
    , cells_of_rank(n_ranks)
  {
    AssertThrow(mesh.n_levels() == 1 &&
                  this->cell_rank.size() == mesh.n_active_cells(),
                dealii::ExcMessage("RankDescriptions: a mesh of one level "
                                   "and a rank for each of its cells"));
    // The ranks that own a cell at each vertex.
    std::vector<std::vector<unsigned int>> vertex_ranks(mesh.n_vertices());
    for (const auto &cell : mesh.active_cell_iterators())
      {
        const unsigned int r = this->cell_rank[cell->index()];
        AssertThrow(r < n_ranks,
                    dealii::ExcMessage("RankDescriptions: cell " +
                                       std::to_string(cell->index()) +
                                       " is given rank " + std::to_string(r) +
                                       " of " + std::to_string(n_ranks)));
        for (const unsigned int v : cell->vertex_indices())
          {
            std::vector<unsigned int> &ranks =
              vertex_ranks[cell->vertex_index(v)];
            if (std::find(ranks.begin(), ranks.end(), r) == ranks.end())
              ranks.push_back(r);
          }
      }
    // A cell matters to the ranks that own a cell at one of its vertices.
    std::vector<unsigned int> ranks;
    for (const auto &cell : mesh.active_cell_iterators())
      {
        ranks.clear();
        for (const unsigned int v : cell->vertex_indices())
          for (const unsigned int r : vertex_ranks[cell->vertex_index(v)])
            ranks.push_back(r);
        std::sort(ranks.begin(), ranks.end());
        ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
        for (const unsigned int r : ranks)
          cells_of_rank[r].push_back(cell->index());
      }
  }



  const std::vector<unsigned int> &
  RankDescriptions::cells_of(const unsigned int rank) const
  {
    AssertIndexRange(rank, cells_of_rank.size());
    return cells_of_rank[rank];
  }



  dealii::TriangulationDescription::Description<3, 3>
  RankDescriptions::describe(const unsigned int rank) const
  {
    namespace TD                             = dealii::TriangulationDescription;
    const std::vector<unsigned int> &cells   = cells_of(rank);
    const auto                       cell_at = [&](const unsigned int e) {
      return dealii::Triangulation<3, 3>::active_cell_iterator(&mesh, 0, e);
    };

    TD::Description<3, 3> description;
    description.comm      = MPI_COMM_WORLD;
    description.settings  = TD::Settings::default_setting;
    description.smoothing = mesh.get_mesh_smoothing();

    // The vertices of the part, in increasing order of their index in the
    // mesh, numbered from 0.
    std::vector<unsigned int> vertices;
    for (const unsigned int e : cells)
      {
        const auto cell = cell_at(e);
        for (const unsigned int v : cell->vertex_indices())
          vertices.push_back(cell->vertex_index(v));
      }
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()),
                   vertices.end());
    description.coarse_cell_vertices.reserve(vertices.size());
    for (const unsigned int i : vertices)
      description.coarse_cell_vertices.push_back(mesh.get_vertices()[i]);

    description.coarse_cells.reserve(cells.size());
    description.coarse_cell_index_to_coarse_cell_id.reserve(cells.size());
    description.cell_infos.resize(1);
    description.cell_infos[0].reserve(cells.size());
    for (const unsigned int e : cells)
      {
        const auto          cell = cell_at(e);
        dealii::CellData<3> coarse(cell->n_vertices());
        coarse.material_id = cell->material_id();
        coarse.manifold_id = cell->manifold_id();
        for (const unsigned int v : cell->vertex_indices())
          coarse.vertices[v] = std::lower_bound(vertices.begin(),
                                                vertices.end(),
                                                cell->vertex_index(v)) -
                               vertices.begin();
        description.coarse_cells.push_back(std::move(coarse));
        description.coarse_cell_index_to_coarse_cell_id.push_back(e);

        TD::CellData<3> info;
        info.id                 = dealii::CellId(e, 0, nullptr).to_binary<3>();
        info.subdomain_id       = cell_rank[e];
        info.level_subdomain_id = cell->level_subdomain_id();
        info.manifold_id        = cell->manifold_id();
        info.manifold_line_ids.fill(dealii::numbers::flat_manifold_id);
        info.manifold_quad_ids.fill(dealii::numbers::flat_manifold_id);
        for (const unsigned int l : cell->line_indices())
          info.manifold_line_ids[l] = cell->line(l)->manifold_id();
        for (const unsigned int f : cell->face_indices())
          {
            info.manifold_quad_ids[f] = cell->face(f)->manifold_id();
            if (const auto id = cell->face(f)->boundary_id();
                id != dealii::numbers::internal_face_boundary_id)
              info.boundary_ids.emplace_back(f, id);
          }
        description.cell_infos[0].push_back(std::move(info));
      }
    return description;
  }
} // namespace estep
