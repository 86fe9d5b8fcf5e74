#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/grid/tria.h>

#include <estep/contact/predicates.h>
#include <estep/fem/meshes.h>
#include <estep/fem/p1_cell_data.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

namespace estep
{
  namespace
  {
    /** The boundary faces of @p tria into @p data, in point numbers through
     * @p point_of_vertex, each oriented by its cell's fourth vertex. */
    void
    add_boundary_faces(const dealii::Triangulation<3, 3> &tria,
                       const std::vector<unsigned int>   &point_of_vertex,
                       P1CellData                        &data)
    {
      const auto point = [&](const unsigned int vertex) {
        const dealii::Point<3> &p = tria.get_vertices()[vertex];
        return contact::Point3{{p[0], p[1], p[2]}};
      };
      for (const auto &cell : tria.active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          {
            const auto face = cell->face(f);
            if (!face->at_boundary())
              continue;
            std::array<unsigned int, 3> t = {{face->vertex_index(0),
                                              face->vertex_index(1),
                                              face->vertex_index(2)}};
            for (const unsigned int v : cell->vertex_indices())
              {
                const unsigned int i = cell->vertex_index(v);
                if (i == t[0] || i == t[1] || i == t[2])
                  continue;
                // The cell's vertex off the face must lie below it.
                if (contact::orient3d(
                      point(t[0]), point(t[1]), point(t[2]), point(i)) > 0)
                  std::swap(t[1], t[2]);
                break;
              }
            for (auto &i : t)
              i = point_of_vertex[i];
            data.boundary_triangle.push_back(t);
            data.boundary_id.push_back(face->boundary_id());
          }
    }
  } // namespace



  void
  set_cell_geometry(P1CellData                                 &data,
                    const unsigned int                          h,
                    const std::array<std::array<double, 3>, 4> &x)
  {
    dealii::Tensor<2, 3> Dm;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int i = 0; i < 3; ++i)
        Dm[i][a] = x[a + 1][i] - x[0][i];
    data.volume[h]               = dealii::determinant(Dm) / 6.;
    const dealii::Tensor<2, 3> B = dealii::invert(Dm);
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int j = 0; j < 3; ++j)
        data.shape_gradient[3 * a + j][h] = B[a][j];
  }



  P1CellData
  make_p1_cell_data(const dealii::Triangulation<3, 3> &tria,
                    const double                       density)
  {
    AssertThrow(density > 0. && std::isfinite(density),
                dealii::ExcMessage(
                  "ElasticBody: the density must be positive (got " +
                  std::to_string(density) + ")."));
    check_tetrahedral_mesh(tria);
    const dealii::FESystem<3> fe(dealii::FE_SimplexP<3>(1), 3);
    dealii::DoFHandler<3, 3>  dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
      AssertThrow(fe.system_to_component_index(k).first == k % 3 &&
                    fe.system_to_component_index(k).second == k / 3,
                  dealii::ExcInternalError());

    P1CellData data;
    data.density                = density;
    data.n_cells                = tria.n_active_cells();
    data.n_points               = dof_handler.n_dofs() / 3;
    const unsigned int n_padded = data.n_padded_cells();
    for (auto &v : data.point)
      v.resize(n_padded);
    for (auto &v : data.shape_gradient)
      v.resize(n_padded);
    data.volume.resize(n_padded);
    data.reference_position.assign(3 * data.n_points, 0.);
    data.lumped_mass.assign(data.n_points, 0.);
    data.first_cell.assign(data.n_points, data.n_cells);
    std::vector<unsigned int> point_of_vertex(
      tria.n_vertices(), std::numeric_limits<unsigned int>::max());

    // Geometry: points, B = D_m^-1, volume.
    std::vector<dealii::types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const unsigned int e = cell->active_cell_index();
        cell->get_dof_indices(dofs);
        for (unsigned int a = 0; a < 4; ++a)
          {
            const unsigned int p = dofs[3 * a] / 3;
            for (unsigned int c = 0; c < 3; ++c)
              {
                AssertThrow(dofs[3 * a + c] == 3 * p + c,
                            dealii::ExcInternalError());
                data.reference_position[3 * p + c] = cell->vertex(a)[c];
              }
            data.point[a][e]                       = p;
            point_of_vertex[cell->vertex_index(a)] = p;
            data.first_cell[p] = std::min(data.first_cell[p], e);
          }
        std::array<std::array<double, 3>, 4> x;
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int i = 0; i < 3; ++i)
            x[a][i] = cell->vertex(a)[i];
        set_cell_geometry(data, e, x);
        data.total_volume += data.volume[e];
        // The lumped mass: rho |Omega_e| / 4 from each cell of a point, the
        // row sums of the consistent mass of the scalar P1 element.
        for (unsigned int a = 0; a < 4; ++a)
          data.lumped_mass[data.point[a][e]] += 0.25 * density * data.volume[e];
      }
    // The padding of the last batch of four cells: copies of the last cell
    // with volume 0.
    for (unsigned int e = data.n_cells; e < n_padded; ++e)
      {
        for (auto &v : data.point)
          v[e] = v[data.n_cells - 1];
        for (auto &v : data.shape_gradient)
          v[e] = v[data.n_cells - 1];
        data.volume[e] = 0.;
      }

    // deal.II's FEValues checks the geometry above: volume, the lumped
    // mass's row sums and the gradients. Its values are not taken: they
    // differ in the last bits with the number of threads (on one thread it
    // reuses the Jacobian of a cell for the next if that is its translate, on
    // more it does not), and the masses would make the trajectory depend on
    // it.
    const dealii::FE_SimplexP<3>   scalar_fe(1);
    const dealii::MappingFE<3>     mapping(scalar_fe);
    const dealii::QGaussSimplex<3> quadrature(2);
    dealii::FEValues<3>            fe_values(mapping,
                                  scalar_fe,
                                  quadrature,
                                  dealii::update_values |
                                    dealii::update_gradients |
                                    dealii::update_JxW_values);
    for (const auto &cell : tria.active_cell_iterators())
      {
        const unsigned int e = cell->active_cell_index();
        fe_values.reinit(cell);
        double volume = 0.;
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          volume += fe_values.JxW(q);
        const double tolerance = 1e-10;
        AssertThrow(std::abs(volume - data.volume[e]) <=
                      tolerance * data.volume[e],
                    dealii::ExcMessage(
                      "ElasticBody: the volume of cell " + std::to_string(e) +
                      " from FEValues disagrees with the geometry."));
        for (unsigned int a = 0; a < 4; ++a)
          {
            double row_sum = 0.;
            for (unsigned int q = 0; q < quadrature.size(); ++q)
              for (unsigned int b = 0; b < 4; ++b)
                row_sum += density * fe_values.shape_value(a, q) *
                           fe_values.shape_value(b, q) * fe_values.JxW(q);
            AssertThrow(std::abs(row_sum - 0.25 * density * data.volume[e]) <=
                          tolerance * density * data.volume[e],
                        dealii::ExcMessage(
                          "ElasticBody: lumped mass check failed on cell " +
                          std::to_string(e) + "."));
            if (a > 0)
              for (unsigned int j = 0; j < 3; ++j)
                {
                  const double B_aj = data.shape_gradient[3 * (a - 1) + j][e];
                  AssertThrow(std::abs(fe_values.shape_grad(a, 0)[j] - B_aj) <=
                                tolerance * (1. + std::abs(B_aj)) *
                                  std::cbrt(1. / data.volume[e]),
                              dealii::ExcMessage(
                                "ElasticBody: shape gradient check failed "
                                "on cell " +
                                std::to_string(e) + "."));
                }
          }
      }

    add_boundary_faces(tria, point_of_vertex, data);
    data.hold_every_chunk();
    return data;
  }



  void
  P1CellData::hold_chunks(const std::vector<unsigned int> &chunks)
  {
    chunk_start.assign(n_chunks(), not_held);
    unsigned int position = 0;
    for (std::size_t i = 0; i < chunks.size(); ++i)
      {
        const unsigned int c = chunks[i];
        AssertIndexRange(c, n_chunks());
        Assert(i == 0 || c > chunks[i - 1],
               dealii::ExcMessage("hold_chunks: the chunks must increase."));
        chunk_start[c]         = position;
        const BlockRange cells = chunk_cells(c);
        position += cells.end - cells.begin;
      }
  }

  void
  P1CellData::hold_every_chunk()
  {
    std::vector<unsigned int> every_chunk(n_chunks());
    std::iota(every_chunk.begin(), every_chunk.end(), 0u);
    hold_chunks(every_chunk);
  }

  std::vector<unsigned int>
  P1CellData::held_chunks() const
  {
    std::vector<unsigned int> chunks;
    for (unsigned int c = 0; c < chunk_start.size(); ++c)
      if (chunk_start[c] != not_held)
        chunks.push_back(c);
    return chunks;
  }

  unsigned int
  P1CellData::n_held_cells() const
  {
    unsigned int n = 0;
    for (const unsigned int c : held_chunks())
      n += chunk_cells(c).end - chunk_cells(c).begin;
    return n;
  }

  unsigned int
  P1CellData::n_cells_in(const std::vector<unsigned int> &chunks) const
  {
    unsigned int n = 0;
    for (const unsigned int c : chunks)
      n += std::min(chunk_cells(c).end, n_cells) -
           std::min(chunk_cells(c).begin, n_cells);
    return n;
  }

  bool
  P1CellData::holds(const BlockRange cells) const
  {
    if (cells.begin >= cells.end)
      return true;
    if (cells.end > n_padded_cells() || chunk_start.size() != n_chunks())
      return false;
    const unsigned int first = cells.begin / gradient_chunk;
    const unsigned int last  = (cells.end - 1) / gradient_chunk;
    for (unsigned int c = first; c <= last; ++c)
      if (chunk_start[c] == not_held ||
          chunk_start[c] != chunk_start[first] + (c - first) * gradient_chunk)
        return false;
    return true;
  }
} // namespace estep
