#include <deal.II/grid/tria.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/exception_text.h>
#include <estep/fem/distributed_cell_data.h>

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace estep
{
  std::vector<std::vector<unsigned int>>
  chunks_held_by_ranks(const P1CellData &data, const unsigned int n_ranks)
  {
    Assert(data.held_chunks().size() == data.n_chunks(),
           dealii::ExcInternalError());
    const unsigned int              n_padded = data.n_padded_cells();
    const std::vector<unsigned int> block_rank =
      block_ranks(n_blocks(n_padded), n_ranks);
    std::vector<std::vector<bool>> held(n_ranks,
                                        std::vector<bool>(data.n_chunks()));
    constexpr unsigned int         chunk = P1CellData::gradient_chunk;
    for (unsigned int e = 0; e < n_padded; ++e)
      {
        held[block_rank[e / block_size]][e / chunk] = true;
        for (unsigned int a = 0; a < 4; ++a)
          held[block_rank[data.first_cell[data.point[a][e]] / block_size]]
              [e / chunk] = true;
      }
    std::vector<std::vector<unsigned int>> chunks(n_ranks);
    for (unsigned int r = 0; r < n_ranks; ++r)
      for (unsigned int c = 0; c < data.n_chunks(); ++c)
        if (held[r][c])
          chunks[r].push_back(c);
    return chunks;
  }



  P1CellData
  make_p1_cell_data_on_first_rank(
    const std::function<void(dealii::Triangulation<3, 3> &)> &make_mesh,
    const double                                              density)
  {
    const auto make = [&]() {
      dealii::Triangulation<3, 3> tria;
      make_mesh(tria);
      return make_p1_cell_data(tria, density);
    };
    if (rank_count() == 1)
      return make();

    // What the first rank meets, every rank throws.
    P1CellData         data;
    std::exception_ptr failure;
    std::vector<char>  message;
    if (this_rank() == 0)
      {
        try
          {
            data = make();
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

    // The cells: to each rank the chunks it holds, one rank after the other.
    if (this_rank() == 0)
      {
        const std::vector<std::vector<unsigned int>> held =
          chunks_held_by_ranks(data, rank_count());
        const auto part_of = [&](const auto &v, const unsigned int r) {
          std::decay_t<decltype(v)> part;
          for (const unsigned int c : held[r])
            {
              const BlockRange cells = data.chunk_cells(c);
              part.insert(part.end(),
                          v.begin() + cells.begin,
                          v.begin() + cells.end);
            }
          return part;
        };
        for (unsigned int r = 1; r < held.size(); ++r)
          {
            send_from_first_rank(r, held[r].data(), held[r].size());
            data.for_each_cell_array([&](const auto &v) {
              const auto part = part_of(v, r);
              send_from_first_rank(r, part.data(), part.size());
            });
          }
        data.for_each_cell_array([&](auto &v) { part_of(v, 0).swap(v); });
        data.hold_chunks(held[0]);
      }
    else
      {
        std::vector<unsigned int> chunks;
        receive_from_first_rank(chunks);
        data.for_each_cell_array([](auto &v) { receive_from_first_rank(v); });
        data.hold_chunks(chunks);
      }
    return data;
  }



  std::vector<double>
  cells_held_on_each_rank(const std::vector<const P1CellData *> &bodies)
  {
    double mine = 0.;
    for (const P1CellData *data : bodies)
      mine += data->n_cells_in(data->held_chunks());
    std::vector<double> all(rank_count());
    gather_from_all_ranks(&mine,
                          std::vector<unsigned int>(rank_count(), 1),
                          all.data());
    return all;
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
