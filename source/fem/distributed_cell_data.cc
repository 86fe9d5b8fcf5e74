#include <deal.II/base/utilities.h>
#include <deal.II/distributed/fully_distributed_tria.h>
#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/exception_text.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/rank_descriptions.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace estep
{
  namespace
  {
    /**
     * The point of @p data at each vertex of @p description, a description
     * of cells of @p data whose coarse cell ids are their numbers.
     */
    std::vector<unsigned int>
    points_of_vertices(
      const dealii::TriangulationDescription::Description<3, 3> &description,
      const P1CellData                                          &data)
    {
      constexpr unsigned int    unset = -1;
      std::vector<unsigned int> points(description.coarse_cell_vertices.size(),
                                       unset);
      for (std::size_t i = 0; i < description.coarse_cells.size(); ++i)
        {
          const unsigned int e =
            description.coarse_cell_index_to_coarse_cell_id[i];
          for (unsigned int a = 0; a < 4; ++a)
            points[description.coarse_cells[i].vertices[a]] =
              data.point[a][data.at(e)];
        }
      AssertThrow(std::find(points.begin(), points.end(), unset) ==
                    points.end(),
                  dealii::ExcInternalError());
      return points;
    }

    /**
     * The per-cell arrays of @p data for the chunks @p chunks, from the cells
     * of the distributed mesh @p tria (coarse cell id: the cell's number;
     * @p point_of_vertex: the point of each vertex). The held cells that
     * @p tria does not have (beyond the layer of cells around this rank's)
     * are only ever read by the gradient, for points of other ranks, and
     * become inert stand-ins: copies of a cell that it has, with volume 0,
     * whose forces are zeros (the sums they are added to start at +0 and so
     * never are -0: adding a zero changes no bit). The padding after the last
     * cell copies it, as in make_p1_cell_data(). Throws if a cell this rank
     * computes, or one of the cells of a point whose gradient it computes, is
     * missing.
     */
    void
    take_held_cells(const dealii::Triangulation<3, 3> &tria,
                    const std::vector<unsigned int>   &point_of_vertex,
                    const std::vector<unsigned int>   &chunks,
                    P1CellData                        &data)
    {
      data.hold_chunks(chunks);
      const unsigned int n_held = data.n_held_cells();
      data.for_each_cell_array([&](auto &v) { v.assign(n_held, {}); });
      std::vector<bool> present(n_held, false);
      // The mass of the cells of each point on this rank, to check that
      // those of the points it computes are all here.
      std::vector<double> mass(data.n_points, 0.);
      for (const auto &cell : tria.active_cell_iterators())
        {
          if (cell->is_artificial())
            continue;
          const unsigned int e = cell->id().get_coarse_cell_id();
          AssertThrow(e < data.n_cells, dealii::ExcInternalError());
          if (data.chunk_start[e / P1CellData::gradient_chunk] ==
              P1CellData::not_held)
            continue;
          const unsigned int                   h = data.at(e);
          std::array<std::array<double, 3>, 4> x;
          for (unsigned int a = 0; a < 4; ++a)
            {
              const unsigned int p = point_of_vertex[cell->vertex_index(a)];
              data.point[a][h]     = p;
              for (unsigned int i = 0; i < 3; ++i)
                {
                  x[a][i] = cell->vertex(a)[i];
                  AssertThrow(x[a][i] == data.reference_position[3 * p + i],
                              dealii::ExcMessage(
                                "The distributed mesh's vertices do not "
                                "match the points of the body."));
                }
            }
          set_cell_geometry(data, h, x);
          present[h] = true;
          for (unsigned int a = 0; a < 4; ++a)
            mass[data.point[a][h]] += data.density * data.volume[h] / 4.;
        }

      // The stand-ins, each a copy of the present cell before it (or, for
      // the first ones, after it). A rank holds chunks only for its own
      // cells and points, so some cell is present if any is held.
      unsigned int source =
        std::find(present.begin(), present.end(), true) - present.begin();
      AssertThrow(n_held == 0 || source < n_held, dealii::ExcInternalError());
      for (unsigned int h = 0; h < n_held; ++h)
        if (present[h])
          source = h;
        else
          {
            data.for_each_cell_array([&](auto &v) { v[h] = v[source]; });
            data.volume[h] = 0.;
          }

      const BlockRange mine = rank_cells(data.n_padded_cells(), this_rank());
      for (unsigned int e = mine.begin; e < std::min(mine.end, data.n_cells);
           ++e)
        AssertThrow(present[data.at(e)],
                    dealii::ExcMessage("The distributed mesh lacks cell " +
                                       std::to_string(e) + " of this rank."));
      for (unsigned int p = 0; p < data.n_points; ++p)
        if (data.first_cell[p] >= mine.begin && data.first_cell[p] < mine.end)
          AssertThrow(std::abs(mass[p] - data.lumped_mass[p]) <=
                        1e-8 * data.lumped_mass[p],
                      dealii::ExcMessage(
                        "The distributed mesh lacks cells of point " +
                        std::to_string(p) +
                        ", whose gradient this rank computes."));
    }
  } // namespace



  std::vector<std::vector<unsigned int>>
  chunks_held_by_ranks(const P1CellData &data, const unsigned int n_ranks)
  {
    return chunks_held_by_ranks(
      data, block_ranks(n_blocks(data.n_padded_cells()), n_ranks), n_ranks);
  }



  std::vector<std::vector<unsigned int>>
  chunks_held_by_ranks(const P1CellData                &data,
                       const std::vector<unsigned int> &block_rank,
                       const unsigned int               n_ranks)
  {
    Assert(data.held_chunks().size() == data.n_chunks(),
           dealii::ExcInternalError());
    const unsigned int n_padded = data.n_padded_cells();
    AssertDimension(block_rank.size(), n_blocks(n_padded));
    // The cells come in increasing order, and with them their chunks: each
    // rank's list stays sorted when a chunk is added only if it is not its
    // last one. One pass over the cells, whatever the number of ranks.
    std::vector<std::vector<unsigned int>> chunks(n_ranks);
    const auto hold = [&](const unsigned int r, const unsigned int c) {
      if (chunks[r].empty() || chunks[r].back() != c)
        chunks[r].push_back(c);
    };
    constexpr unsigned int chunk = P1CellData::gradient_chunk;
    for (unsigned int e = 0; e < n_padded; ++e)
      {
        hold(block_rank[e / block_size], e / chunk);
        for (unsigned int a = 0; a < 4; ++a)
          hold(block_rank[data.first_cell[data.point[a][e]] / block_size],
               e / chunk);
      }
    return chunks;
  }



  P1CellData
  make_p1_cell_data_on_first_rank(
    const std::function<void(dealii::Triangulation<3, 3> &)> &make_mesh,
    const double                                              density)
  {
    dealii::Triangulation<3, 3> mesh;
    if (rank_count() == 1)
      {
        make_mesh(mesh);
        return make_p1_cell_data(mesh, density);
      }

    // What the first rank meets, every rank throws.
    P1CellData         data;
    std::exception_ptr failure;
    std::vector<char>  message;
    if (this_rank() == 0)
      {
        try
          {
            make_mesh(mesh);
            data = make_p1_cell_data(mesh, density);
          }
        catch (const std::exception &e)
          {
            failure                = std::current_exception();
            const std::string text = one_line_message(e);
            message.assign(text.begin(), text.end());
          }
        catch (...)
          {
            failure = std::current_exception();
          }
      }
    int failed = failure != nullptr;
    broadcast_from_first_rank(&failed, sizeof(failed));
    broadcast_from_first_rank(message);
    if (failure)
      std::rethrow_exception(failure);
    if (failed)
      throw std::runtime_error(message.empty() ?
                                 "the first process could not make the mesh" :
                                 std::string(message.begin(), message.end()));

    // The whole body's numbers, the points and the boundary: to every rank.
    unsigned int sizes[2] = {data.n_cells, data.n_points};
    broadcast_from_first_rank(sizes, sizeof(sizes));
    data.n_cells  = sizes[0];
    data.n_points = sizes[1];
    broadcast_from_first_rank(&data.total_volume, sizeof(data.total_volume));
    broadcast_from_first_rank(&data.density, sizeof(data.density));
    broadcast_from_first_rank(data.reference_position);
    broadcast_from_first_rank(data.lumped_mass);
    broadcast_from_first_rank(data.first_cell);
    broadcast_from_first_rank(data.boundary_triangle);
    broadcast_from_first_rank(data.boundary_id);

    // The cells: each rank's from a parallel::fullydistributed::Triangulation
    // of its cells and their ghost layer, which deal.II builds from the
    // description the first rank makes of its serial mesh for it.
    std::vector<unsigned int>                           chunks, point_of_vertex;
    dealii::TriangulationDescription::Description<3, 3> description;
    if (this_rank() == 0)
      {
        const std::vector<std::vector<unsigned int>> held =
          chunks_held_by_ranks(data, rank_count());
        // The mesh has one level (refinements are made on hexahedra, before
        // they are cut into tetrahedra), so that coarse cell e is cell e.
        const RankDescriptions descriptions(mesh,
                                            cell_ranks(data.n_cells),
                                            rank_count());
        for (unsigned int r = 1; r < rank_count(); ++r)
          {
            const auto description = descriptions.describe(r);
            const std::vector<unsigned int> points =
              points_of_vertices(description, data);
            const std::vector<char> bytes =
              dealii::Utilities::pack(description, false);
            send_from_first_rank(r, held[r].data(), held[r].size());
            send_from_first_rank(r, bytes.data(), bytes.size());
            send_from_first_rank(r, points.data(), points.size());
          }
        chunks          = held[0];
        description     = descriptions.describe(0);
        point_of_vertex = points_of_vertices(description, data);
        mesh.clear();
      }
    else
      {
        std::vector<char> bytes;
        receive_from_first_rank(chunks);
        receive_from_first_rank(bytes);
        receive_from_first_rank(point_of_vertex);
        description = dealii::Utilities::unpack<
          dealii::TriangulationDescription::Description<3, 3>>(bytes, false);
      }
    description.comm = MPI_COMM_WORLD;
    dealii::parallel::fullydistributed::Triangulation<3, 3> tria(
      MPI_COMM_WORLD);
    tria.create_triangulation(description);
    // What one rank meets, every rank throws.
    std::string problem;
    try
      {
        take_held_cells(tria, point_of_vertex, chunks, data);
      }
    catch (const std::exception &e)
      {
        problem = one_line_message(e);
      }
    if (largest_over_ranks(!problem.empty()))
      throw std::runtime_error(problem.empty() ?
                                 "another process could not take its cells "
                                 "from the distributed mesh" :
                                 problem);
    return data;
  }



  std::vector<double>
  cells_held_on_each_rank(const std::vector<const P1CellData *> &bodies)
  {
    double mine = 0.;
    for (const P1CellData *data : bodies)
      mine += data->n_cells_in(data->held_chunks());
    return values_of_every_rank(mine);
  }



  P1CellData
  gather_every_cell(const P1CellData &data)
  {
    if (rank_count() == 1)
      return data;
    const unsigned int n_padded = data.n_padded_cells();
    const BlockRange   mine     = rank_cells(n_padded, this_rank());
    Assert(data.holds(mine), dealii::ExcInternalError());
    // Each rank's cells, in whole blocks of block_size cells (the last one
    // cut to n_padded after the exchange).
    P1CellData every = data;
    every.for_each_cell_array([&](auto &whole) {
      using T = typename std::decay_t<decltype(whole)>::value_type;
      const std::vector<T> held = std::move(whole);
      whole.assign(std::size_t(n_blocks(n_padded)) * block_size, T());
      if (mine.begin < mine.end)
        std::copy(held.begin() + data.at(mine.begin),
                  held.begin() + data.at(mine.begin) + (mine.end - mine.begin),
                  whole.begin() + mine.begin);
      share_block_items(whole.data(),
                        block_size * sizeof(T),
                        n_blocks(n_padded));
      whole.resize(n_padded);
    });
    every.hold_every_chunk();
    return every;
  }
} // namespace estep
