#include <deal.II/base/exceptions.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/ghost_exchange.h>
#include <estep/fem/distributed_cell_data.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/elastic_free_flight.h>

#include "p1_kernels.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace estep
{
  ElasticBody::ElasticBody(const dealii::Triangulation<3, 3> &tria,
                           std::shared_ptr<const Material>    material,
                           const double                       density,
                           const std::string                 &name)
    : ElasticBody(make_p1_cell_data(tria, density), std::move(material), name)
  {}



  ElasticBody::ElasticBody(P1CellData                      cell_data,
                           std::shared_ptr<const Material> material,
                           const std::string              &name)
    : body_name(name)
    , body_material(std::move(material))
    , data(std::move(cell_data))
  {
    AssertThrow(body_material != nullptr,
                dealii::ExcMessage("ElasticBody: no material given."));
    AssertThrow(data.density > 0. && std::isfinite(data.density),
                dealii::ExcMessage(
                  "ElasticBody: the density must be positive (got " +
                  std::to_string(data.density) + ")."));
    // The per-cell arrays must hold at least this rank's cells (all of them
    // on one rank).
    const unsigned int n_padded = data.n_padded_cells();
    const unsigned int n_held   = data.volume.size();
    const BlockRange   mine     = rank_cells(n_padded, this_rank());
    bool               complete = data.n_cells > 0 &&
                    data.chunk_start.size() == data.n_chunks() &&
                    n_held == data.n_held_cells() && data.holds(mine) &&
                    data.reference_position.size() == 3 * data.n_points &&
                    data.lumped_mass.size() == data.n_points &&
                    data.first_cell.size() == data.n_points &&
                    data.boundary_id.size() == data.boundary_triangle.size();
    data.for_each_cell_array(
      [&](const auto &v) { complete = complete && v.size() == n_held; });
    AssertThrow(complete,
                dealii::ExcMessage("ElasticBody: incomplete cell data."));

    inv_mass.reinit(3 * data.n_points);
    for (unsigned int i = 0; i < data.n_points; ++i)
      {
        AssertThrow(data.lumped_mass[i] > 0.,
                    dealii::ExcMessage(
                      "ElasticBody: the mesh has a vertex that belongs to no "
                      "cell (zero mass)."));
        for (unsigned int c = 0; c < 3; ++c)
          inv_mass[3 * i + c] = 1. / data.lumped_mass[i];
      }
    scratch_J.resize(n_held);
    scratch_positions.resize(3 * data.n_points + 1);
  }

  ElasticBody::~ElasticBody() = default;

  std::string
  ElasticBody::name() const
  {
    return body_name;
  }

  unsigned int
  ElasticBody::spatial_dimension() const
  {
    return 3;
  }

  unsigned int
  ElasticBody::n_dofs() const
  {
    return 3 * data.n_points;
  }

  const Vector &
  ElasticBody::inverse_mass() const
  {
    return inv_mass;
  }

  namespace
  {
    /**
     * J_e = det F_e of the cells of @p cells (padding included) into @p J
     * (at data.at(e)) for
     * positions @p x (padded, see load_triples()); returns the sum over them
     * of |Omega_e| (|F_e|^2 - 3).
     */
    ESTEP_LANE_KERNEL double
    jacobians_and_square_sum(const P1CellData &data,
                             const double     *x,
                             const BlockRange  cells,
                             double           *J)
    {
      Lanes square = lanes(0.);
      for (unsigned int e = cells.begin; e < cells.end; e += n_lanes)
        {
          Lanes F[9], C[9];
          internal::deformation_gradient(x, data, e, F);
          internal::cofactor(F, C);
          store_lanes(J + data.at(e), internal::determinant(F, C));
          square += load_lanes(data.volume.data() + data.at(e)) *
                    (internal::contract(F, F) - 3.);
        }
      return sum(square);
    }

    /** The cells assemble_gradient() takes at a time, from the start of a
     * run of whole chunks of P1CellData::gradient_chunk cells. */
    constexpr unsigned int assembly_chunk = 128;
    static_assert(assembly_chunk % P1CellData::gradient_chunk == 0);

    /**
     * The nodal forces |Omega_e| P_e grad N_a of the cells of @p cells, with
     * P = f'(J) cof F + c F, in chunks of cells: F and cof F stay in L1
     * between the determinant pass and the assembly pass, and f'(J) is one
     * batch call of the material per chunk. They are added to @p y (with one
     * writable double after its last point, see add_triples()) in the order
     * (batch of four cells, vertex a, cell of the batch).
     */
    ESTEP_LANE_KERNEL void
    assemble_gradient(const P1CellData &data,
                      const Material   &material,
                      const double     *x,
                      const BlockRange  cells,
                      double           *y)
    {
      constexpr unsigned int chunk = assembly_chunk;
      const double           c     = material.quadratic_modulus();
      Lanes                  F[chunk / n_lanes][9], C[chunk / n_lanes][9];
      double                 J[chunk], df[chunk];
      for (unsigned int begin = cells.begin; begin < cells.end; begin += chunk)
        {
          const unsigned int m = std::min(chunk, cells.end - begin);
          for (unsigned int b = 0; b < m / n_lanes; ++b)
            {
              internal::deformation_gradient(x,
                                             data,
                                             begin + n_lanes * b,
                                             F[b]);
              internal::cofactor(F[b], C[b]);
              store_lanes(J + n_lanes * b, internal::determinant(F[b], C[b]));
            }
          material.volumetric_derivatives(J, df, m);
          for (unsigned int b = 0; b < m / n_lanes; ++b)
            {
              const unsigned int e = begin + n_lanes * b;
              const unsigned int h = data.at(e);
              const Lanes        w = load_lanes(data.volume.data() + h);
              const Lanes dfv = load_lanes(df + n_lanes * b) * w, cv = c * w;
              Lanes       P[9];
              for (unsigned int l = 0; l < 9; ++l)
                P[l] = dfv * C[b][l] + cv * F[b][l];
              // The forces on the four vertices of each cell: f_a = P grad
              // N_a for a = 1, 2, 3, and f_0 = -(f_1 + f_2 + f_3).
              Lanes force[4][3];
              for (unsigned int i = 0; i < 3; ++i)
                force[0][i] = lanes(0.);
              for (unsigned int a = 0; a < 3; ++a)
                {
                  Lanes B[3];
                  for (unsigned int j = 0; j < 3; ++j)
                    B[j] =
                      load_lanes(data.shape_gradient[3 * a + j].data() + h);
                  for (unsigned int i = 0; i < 3; ++i)
                    {
                      force[a + 1][i] = P[3 * i] * B[0] + P[3 * i + 1] * B[1] +
                                        P[3 * i + 2] * B[2];
                      force[0][i] -= force[a + 1][i];
                    }
                }
              // Added cell by cell (the cells of a batch may share
              // vertices).
              for (unsigned int a = 0; a < 4; ++a)
                add_triples(y, data.point[a].data() + h, force[a]);
            }
        }
    }
  } // namespace

  double
  ElasticBody::energy(const Vector &q) const
  {
    AssertDimension(q.size(), n_dofs());
    internal::copy_padded(q.data(),
                          q.size(),
                          scratch_positions.data(),
                          kept_coordinates());
    // Per block: the volumetric energy and the sum of |Omega_e| (|F_e|^2 - 3).
    struct Terms
    {
      double volumetric, square;
      Terms &
      operator+=(const Terms &other)
      {
        volumetric += other.volumetric;
        square += other.square;
        return *this;
      }
    };
    const unsigned int n_padded = data.n_padded_cells();
    const Terms        terms    = sum_over_distributed_blocks<Terms>(
      n_blocks(n_padded), [&](const unsigned int b) {
        const BlockRange cells  = block_range(b, n_padded);
        const double     square = jacobians_and_square_sum(data,
                                                       scratch_positions.data(),
                                                       cells,
                                                       scratch_J.data());
        return Terms{body_material->sum_volumetric_energy(
                       scratch_J.data() + data.at(cells.begin),
                       data.volume.data() + data.at(cells.begin),
                       std::min(cells.end, data.n_cells) - cells.begin),
                     square};
      });
    if (!std::isfinite(terms.volumetric))
      return std::numeric_limits<double>::infinity();
    // W - W_0 = f(J) - f(1) + c/2 (|F|^2 - 3), summed so that the undeformed
    // state gives 0 up to round-off of the cells, not of the totals.
    return terms.volumetric +
           0.5 * body_material->quadratic_modulus() * terms.square -
           body_material->volumetric_energy(1.) * data.total_volume;
  }

  const ElasticBody::GradientParts &
  ElasticBody::current_gradient_parts() const
  {
    if (gradient_parts.threads != thread_count() ||
        gradient_parts.ranks != rank_count())
      {
        gradient_parts = GradientParts(data, thread_count());
        part_forces.assign(gradient_parts.parts.size(),
                           std::vector<double>(n_dofs() + 1));
      }
    return gradient_parts;
  }

  const double *
  ElasticBody::gradient_of_own_points(const Vector &q, Vector &g) const
  {
    AssertDimension(q.size(), n_dofs());
    internal::copy_padded(q.data(),
                          q.size(),
                          scratch_positions.data(),
                          kept_coordinates());
    g.reinit(n_dofs(), true);
    const GradientParts &shared = current_gradient_parts();
    const unsigned int  *points = shared.points.data() + shared.first;
    double              *mine   = g.data() + 3 * shared.first;
    if (!shared.in_order)
      {
        scratch_mine.resize(3 *
                            std::size_t(shared.points_per_rank[this_rank()]));
        mine = scratch_mine.data();
      }
    for_each_block(shared.parts.size(), [&](const unsigned int j) {
      const GradientParts::Part &part   = shared.parts[j];
      double *const              forces = part_forces[j].data();
      std::fill(forces + 3 * part.lowest, forces + 3 * part.highest + 4, 0.);
      for (const BlockRange &cells : part.cells)
        assemble_gradient(
          data, *body_material, scratch_positions.data(), cells, forces);
      for (const unsigned int k : part.positions)
        for (unsigned int i = 0; i < 3; ++i)
          mine[3 * k + i] = forces[3 * points[k] + i];
    });
    return mine;
  }

  void
  ElasticBody::gather_own_points(const double *own, Vector &x) const
  {
    const GradientParts &shared = current_gradient_parts();
    if (shared.in_order)
      {
        gather_from_all_ranks(own, shared.points_per_rank, x.data(), 3);
        return;
      }
    scratch_all.resize(n_dofs());
    gather_from_all_ranks(own, shared.points_per_rank, scratch_all.data(), 3);
    for (unsigned int k = 0; k < data.n_points; ++k)
      for (unsigned int i = 0; i < 3; ++i)
        x[3 * shared.points[k] + i] = scratch_all[3 * k + i];
  }

  void
  ElasticBody::gradient(const Vector &q, Vector &g) const
  {
    gather_own_points(gradient_of_own_points(q, g), g);
  }

  const std::vector<BlockRange> *
  ElasticBody::kept_coordinates() const
  {
    return rank_count() > 1 ? &current_gradient_parts().kept : nullptr;
  }

  const std::vector<char> &
  ElasticBody::coordinates_read() const
  {
    return current_gradient_parts().read;
  }

  const std::vector<dealii::types::global_dof_index> &
  ElasticBody::own_coordinates() const
  {
    return current_gradient_parts().owned;
  }

  void
  ElasticBody::kept_gradient(const Vector &q, Vector &g) const
  {
    const double *const  mine   = gradient_of_own_points(q, g);
    const GradientParts &shared = current_gradient_parts();
    if (shared.ranks == 1)
      return;
    const std::vector<dealii::types::global_dof_index> &owned = shared.owned;
    if (!shared.in_order)
      for (std::size_t j = 0; j < owned.size(); ++j)
        g[owned[j]] = mine[j];
    if (ghost_exchange == nullptr)
      ghost_exchange =
        std::make_unique<GhostExchange>(owned, shared.kept, n_dofs());
    ghost_exchange->send(mine, g.data());
  }

  void
  ElasticBody::complete_state(Vector &x) const
  {
    const GradientParts &shared = current_gradient_parts();
    if (shared.ranks == 1)
      return;
    if (shared.in_order)
      {
        gather_own_points(x.data() + 3 * std::size_t(shared.first), x);
        return;
      }
    scratch_mine.resize(shared.owned.size());
    for (std::size_t j = 0; j < shared.owned.size(); ++j)
      scratch_mine[j] = x[shared.owned[j]];
    gather_own_points(scratch_mine.data(), x);
  }

  ElasticBody::GradientParts::GradientParts(const P1CellData  &data,
                                            const unsigned int threads)
    : threads(threads)
    , ranks(rank_count())
  {
    const unsigned int n_padded = data.n_padded_cells();
    const unsigned int me       = this_rank();
    // The owner of each block of cells: a rank, and in this rank a part.
    const unsigned int              n_cell_blocks = n_blocks(n_padded);
    const std::vector<unsigned int> block_rank    = block_ranks(n_cell_blocks);
    std::vector<unsigned int>       block_part(n_cell_blocks, 0);
    const BlockRange                mine = rank_blocks(n_cell_blocks, me);
    const unsigned int n_parts = std::min(threads, mine.end - mine.begin);
    for (unsigned int b = mine.begin; b < mine.end; ++b)
      block_part[b] = static_cast<unsigned long long>(b - mine.begin) *
                      n_parts / (mine.end - mine.begin);
    // Each point's owner: that of the block of its first cell.
    std::vector<unsigned int> point_rank(data.n_points),
      point_part(data.n_points);
    for (unsigned int p = 0; p < data.n_points; ++p)
      {
        point_rank[p] = block_rank[data.first_cell[p] / block_size];
        point_part[p] = block_part[data.first_cell[p] / block_size];
      }

    // The points in rank order, each rank's in increasing order: a counting
    // sort, one pass over the points whatever the number of ranks.
    points_per_rank.assign(ranks, 0);
    for (unsigned int p = 0; p < data.n_points; ++p)
      ++points_per_rank[point_rank[p]];
    std::vector<unsigned int> next(ranks, 0);
    for (unsigned int r = 1; r < ranks; ++r)
      next[r] = next[r - 1] + points_per_rank[r - 1];
    first = next[me];
    parts.resize(n_parts);
    points.resize(data.n_points);
    for (unsigned int p = 0; p < data.n_points; ++p)
      {
        const unsigned int r = point_rank[p];
        if (r == me)
          parts[point_part[p]].positions.push_back(next[r] - first);
        points[next[r]++] = p;
      }
    in_order = true;
    for (unsigned int k = 0; k < points.size(); ++k)
      in_order = in_order && points[k] == k;

    // The chunks of cells with a vertex among a part's points, in runs of at
    // most block_size cells, and the range of the points they touch. All of
    // them lie among the cells this rank holds (chunks_held_by_ranks()).
    const std::vector<unsigned int> held = data.held_chunks();
    for (unsigned int j = 0; j < n_parts; ++j)
      {
        Part &part  = parts[j];
        part.lowest = data.n_points;
        for (const unsigned int c : held)
          {
            const unsigned int chunk  = data.chunk_cells(c).begin;
            const unsigned int end    = data.chunk_cells(c).end;
            bool               needed = false;
            for (unsigned int e = chunk; e < end && !needed; ++e)
              for (unsigned int a = 0; a < 4; ++a)
                {
                  const unsigned int p = data.point[a][data.at(e)];
                  needed =
                    needed || (point_rank[p] == me && point_part[p] == j);
                }
            if (!needed)
              continue;
            for (unsigned int e = chunk; e < end; ++e)
              for (unsigned int a = 0; a < 4; ++a)
                {
                  const unsigned int p = data.point[a][data.at(e)];
                  part.lowest          = std::min(part.lowest, p);
                  part.highest         = std::max(part.highest, p);
                }
            if (!part.cells.empty() && part.cells.back().end == chunk &&
                part.cells.back().end - part.cells.back().begin < block_size)
              part.cells.back().end = end;
            else
              part.cells.push_back({chunk, end});
          }
      }
    if (ranks > 1)
      {
        // The coordinates this rank keeps: the points of the cells it
        // computes (those of its blocks, and those its points' gradient
        // needs: its own points among them), and its blocks of coordinates.
        const unsigned int n_coordinates = 3 * data.n_points;
        read.assign(n_coordinates, 0);
        const auto keep_points = [&](const BlockRange cells) {
          for (unsigned int e = cells.begin;
               e < std::min(cells.end, data.n_cells);
               ++e)
            for (unsigned int a = 0; a < 4; ++a)
              std::fill_n(read.begin() + 3 * data.point[a][data.at(e)], 3, 1);
        };
        if (mine.begin < mine.end)
          keep_points({block_range(mine.begin, n_padded).begin,
                       block_range(mine.end - 1, n_padded).end});
        for (const Part &part : parts)
          for (const BlockRange &cells : part.cells)
            keep_points(cells);
        kept = kept_coordinate_ranges(read);
        owned.reserve(3 * std::size_t(points_per_rank[me]));
        for (unsigned int k = first; k < first + points_per_rank[me]; ++k)
          for (unsigned int i = 0; i < 3; ++i)
            owned.push_back(3 * points[k] + i);
      }
    // A part whose blocks bring no point of their own (the cells of a short
    // last block may all have their points in earlier cells) has nothing to
    // compute.
    parts.erase(std::remove_if(parts.begin(),
                               parts.end(),
                               [](const Part &part) {
                                 return part.positions.empty();
                               }),
                parts.end());
  }

  std::unique_ptr<FreeFlight>
  ElasticBody::free_flight(const Vector &q, const Vector &v) const
  {
    return make_free_flight(q, v);
  }

  std::unique_ptr<ElasticFreeFlight>
  ElasticBody::make_free_flight(const Vector &q, const Vector &v) const
  {
    return std::make_unique<ElasticFreeFlight>(*this, q, v);
  }

  unsigned int
  ElasticBody::n_cells() const
  {
    return data.n_cells;
  }

  unsigned int
  ElasticBody::n_vertices() const
  {
    return data.n_points;
  }

  double
  ElasticBody::volume() const
  {
    return data.total_volume;
  }

  double
  ElasticBody::mass() const
  {
    double m = 0.;
    for (const double mi : data.lumped_mass)
      m += mi;
    return m;
  }

  double
  ElasticBody::density() const
  {
    return data.density;
  }

  double
  ElasticBody::point_mass(const unsigned int i) const
  {
    AssertIndexRange(i, data.n_points);
    return data.lumped_mass[i];
  }

  Vector
  ElasticBody::reference_configuration() const
  {
    Vector q(n_dofs());
    for (unsigned int k = 0; k < n_dofs(); ++k)
      q[k] = data.reference_position[k];
    return q;
  }

  unsigned int
  ElasticBody::closest_point(const std::array<double, 3> &X) const
  {
    unsigned int best = 0;
    double       d2   = std::numeric_limits<double>::infinity();
    for (unsigned int i = 0; i < data.n_points; ++i)
      {
        double r2 = 0.;
        for (unsigned int c = 0; c < 3; ++c)
          r2 += (data.reference_position[3 * i + c] - X[c]) *
                (data.reference_position[3 * i + c] - X[c]);
        if (r2 < d2)
          {
            d2   = r2;
            best = i;
          }
      }
    return best;
  }

  Vector
  ElasticBody::rigid_velocity(const Vector                &q,
                              const std::array<double, 3> &v0,
                              const std::array<double, 3> &omega,
                              const std::array<double, 3> &centre) const
  {
    AssertDimension(q.size(), n_dofs());
    Vector v(n_dofs());
    for (unsigned int i = 0; i < data.n_points; ++i)
      {
        const double r[3] = {q[3 * i] - centre[0],
                             q[3 * i + 1] - centre[1],
                             q[3 * i + 2] - centre[2]};
        v[3 * i]          = v0[0] + omega[1] * r[2] - omega[2] * r[1];
        v[3 * i + 1]      = v0[1] + omega[2] * r[0] - omega[0] * r[2];
        v[3 * i + 2]      = v0[2] + omega[0] * r[1] - omega[1] * r[0];
      }
    return v;
  }

  const Material &
  ElasticBody::material() const
  {
    return *body_material;
  }

  const P1CellData &
  ElasticBody::cell_data() const
  {
    return data;
  }

  const P1CellData &
  ElasticBody::every_cell_data() const
  {
    if (rank_count() == 1)
      return data;
    if (gathered_cells == nullptr)
      gathered_cells = std::make_unique<P1CellData>(gather_every_cell(data));
    return *gathered_cells;
  }

  const P1CellData &
  ElasticBody::data_of(const BlockRange cells) const
  {
    Assert(cells.begin <= cells.end && cells.end <= data.n_cells,
           dealii::ExcInternalError());
    if (data.holds(cells))
      return data;
    AssertThrow(gathered_cells != nullptr,
                dealii::ExcMessage("ElasticBody: cells this rank does not "
                                   "hold, before every_cell_data()."));
    return *gathered_cells;
  }

} // namespace estep



namespace estep
{
  void
  ElasticBody::cell_fields(const Vector        &q,
                           const BlockRange     cells,
                           std::vector<double> &J,
                           std::vector<double> &energy_density) const
  {
    AssertDimension(q.size(), n_dofs());
    const P1CellData &cell_data = data_of(cells);
    J.resize(cells.end - cells.begin);
    energy_density.resize(cells.end - cells.begin);
    const double c  = body_material->quadratic_modulus();
    const double f1 = body_material->volumetric_energy(1.);
    for (unsigned int e = cells.begin; e < cells.end; ++e)
      {
        double F[9], C[9];
        internal::deformation_gradient(q.data(), cell_data, e, F);
        internal::cofactor(F, C);
        const double Je    = internal::determinant(F, C);
        J[e - cells.begin] = Je;
        energy_density[e - cells.begin] =
          Je > 0. ? body_material->volumetric_energy(Je) - f1 +
                      0.5 * c * (internal::contract(F, F) - 3.) :
                    std::numeric_limits<double>::infinity();
      }
  }

  void
  ElasticBody::cell_stresses(const Vector        &q,
                             const BlockRange     cells,
                             std::vector<double> &cauchy,
                             std::vector<double> &von_mises) const
  {
    AssertDimension(q.size(), n_dofs());
    const P1CellData &cell_data = data_of(cells);
    cauchy.resize(9 * std::size_t(cells.end - cells.begin));
    von_mises.resize(cells.end - cells.begin);
    const double c = body_material->quadratic_modulus();
    for (unsigned int e = cells.begin; e < cells.end; ++e)
      {
        double F[9], C[9];
        internal::deformation_gradient(q.data(), cell_data, e, F);
        internal::cofactor(F, C);
        const double J     = internal::determinant(F, C);
        const double df    = body_material->volumetric_derivative(J);
        double      *sigma = &cauchy[9 * std::size_t(e - cells.begin)];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              double FFt = 0.;
              for (unsigned int k = 0; k < 3; ++k)
                FFt += F[3 * i + k] * F[3 * j + k];
              sigma[3 * i + j] = (i == j ? df : 0.) + c / J * FFt;
            }
        const double mean = (sigma[0] + sigma[4] + sigma[8]) / 3.;
        double       ss   = 0.;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              const double s = sigma[3 * i + j] - (i == j ? mean : 0.);
              ss += s * s;
            }
        von_mises[e - cells.begin] = std::sqrt(1.5 * ss);
      }
  }



  unsigned long long
  elastic_cells(const MechanicalSystem &system)
  {
    const auto        *bodies = dynamic_cast<const ElasticBodies *>(&system);
    unsigned long long cells  = 0;
    for (unsigned int b = 0; bodies != nullptr && b < bodies->n_bodies(); ++b)
      cells += bodies->body(b).n_cells();
    return cells;
  }



  void
  ElasticBodies::obstacle_surface(std::vector<double>       &points,
                                  std::vector<unsigned int> &triangles) const
  {
    points.clear();
    triangles.clear();
  }



  unsigned int
  ElasticBody::n_bodies() const
  {
    return 1;
  }



  const ElasticBody &
  ElasticBody::body(const unsigned int b) const
  {
    AssertIndexRange(b, 1);
    (void)b;
    return *this;
  }



  void
  ElasticBody::body_state(const Vector      &q,
                          const Vector      &v,
                          const unsigned int b,
                          Vector            &q_b,
                          Vector            &v_b) const
  {
    AssertIndexRange(b, 1);
    (void)b;
    q_b = q;
    v_b = v;
  }



  void
  ElasticBody::track_point(const std::string           &name,
                           const std::array<double, 3> &X)
  {
    tracked_points.emplace_back(name, closest_point(X));
  }

  std::pair<std::array<double, 3>, std::array<double, 3>>
  ElasticBody::reference_bounding_box() const
  {
    std::array<double, 3> lower, upper;
    lower.fill(std::numeric_limits<double>::infinity());
    upper.fill(-std::numeric_limits<double>::infinity());
    for (unsigned int i = 0; i < data.n_points; ++i)
      for (unsigned int c = 0; c < 3; ++c)
        {
          lower[c] = std::min(lower[c], data.reference_position[3 * i + c]);
          upper[c] = std::max(upper[c], data.reference_position[3 * i + c]);
        }
    return {lower, upper};
  }

  std::vector<std::string>
  ElasticBody::observable_names() const
  {
    std::vector<std::string> names;
    for (const auto &[name, point] : tracked_points)
      for (const char *axis : {"_x", "_y", "_z"})
        names.push_back(name + axis);
    return names;
  }

  std::vector<double>
  ElasticBody::observables(const Vector &q, const Vector &) const
  {
    std::vector<double> values;
    for (const auto &[name, point] : tracked_points)
      for (unsigned int c = 0; c < 3; ++c)
        values.push_back(q[3 * point + c]);
    return values;
  }
} // namespace estep
