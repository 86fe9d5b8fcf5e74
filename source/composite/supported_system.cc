#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/ghost_exchange.h>
#include <estep/composite/supported_system.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace estep
{
  namespace
  {
    constexpr unsigned int invalid = std::numeric_limits<unsigned int>::max();
  } // namespace



  SupportedSystem::SupportedSystem(std::shared_ptr<const MechanicalSystem> base,
                                   std::vector<unsigned int> fixed_points,
                                   const Vector             &configuration)
    : SystemDecorator(std::move(base))
    , dim(base_system->spatial_dimension())
    , fixed_point_list(std::move(fixed_points))
  {
    const unsigned int n_base_dofs = base_system->n_dofs();
    if (dim == 0 || n_base_dofs % dim != 0)
      throw std::invalid_argument(
        "SupportedSystem: the base system <" + base_system->name() + "> has " +
        std::to_string(n_base_dofs) +
        " coordinates, not a whole number of points of dimension " +
        std::to_string(dim) + ".");
    const unsigned int n_points = n_base_dofs / dim;
    if (configuration.size() != n_base_dofs)
      throw std::invalid_argument(
        "SupportedSystem: the configuration holding the fixed points has " +
        std::to_string(configuration.size()) +
        " entries, but the base system <" + base_system->name() + "> has " +
        std::to_string(n_base_dofs) + " coordinates.");

    std::sort(fixed_point_list.begin(), fixed_point_list.end());
    fixed_point_list.erase(std::unique(fixed_point_list.begin(),
                                       fixed_point_list.end()),
                           fixed_point_list.end());
    if (!fixed_point_list.empty() && fixed_point_list.back() >= n_points)
      throw std::invalid_argument("SupportedSystem: fixed point " +
                                  std::to_string(fixed_point_list.back()) +
                                  " is out of range: the base system <" +
                                  base_system->name() + "> has " +
                                  std::to_string(n_points) + " points (0 to " +
                                  std::to_string(n_points - 1) + ").");
    if (fixed_point_list.size() == n_points)
      throw std::invalid_argument(
        "SupportedSystem: all " + std::to_string(n_points) +
        " points of the base system <" + base_system->name() +
        "> are fixed; at least one point must be left free.");

    // The free points and their coordinates, in increasing order.
    free_point_list.reserve(n_points - fixed_point_list.size());
    auto next_fixed = fixed_point_list.begin();
    for (unsigned int i = 0; i < n_points; ++i)
      if (next_fixed != fixed_point_list.end() && *next_fixed == i)
        ++next_fixed;
      else
        free_point_list.push_back(i);
    free_dofs.reserve(dim * free_point_list.size());
    reduced_dofs.assign(n_base_dofs, invalid);
    for (const unsigned int i : free_point_list)
      for (unsigned int c = 0; c < dim; ++c)
        {
          reduced_dofs[dim * i + c] = free_dofs.size();
          free_dofs.push_back(dim * i + c);
        }

    gather(base_system->inverse_mass(), inv_mass);
    full_configuration = configuration;
    scratch_q          = full_configuration;
    scratch_v.reinit(n_base_dofs);
    flight_q = full_configuration;
    flight_v.reinit(n_base_dofs);
  }



  struct SupportedSystem::SharedState
  {
    unsigned int            ranks = 0;
    std::vector<BlockRange> kept;
    /** The free coordinates of this rank's blocks of the base's coordinates,
     * which the base keeps: their gradient goes to the ranks that receive
     * it. */
    std::vector<dealii::types::global_dof_index> sent;
    /** The free coordinates of this rank's blocks that the base does not
     * keep here. */
    std::vector<BlockRange>        received;
    std::vector<double>            sent_gradient;
    std::unique_ptr<GhostExchange> exchange;
  };



  SupportedSystem::~SupportedSystem() = default;



  SupportedSystem::SharedState *
  SupportedSystem::current_shared_state() const
  {
    const std::vector<BlockRange> *base_kept = base_system->kept_coordinates();
    if (base_kept == nullptr)
      return nullptr;
    if (shared_state && shared_state->ranks == rank_count())
      return shared_state.get();
    shared_state         = std::make_unique<SharedState>();
    SharedState &shared  = *shared_state;
    shared.ranks         = rank_count();
    const unsigned int n = n_dofs();
    std::vector<char>  read(n, 0);
    for (const BlockRange range : *base_kept)
      for (unsigned int i = range.begin; i < range.end; ++i)
        if (reduced_dofs[i] != invalid)
          read[reduced_dofs[i]] = 1;
    // This rank's blocks of the free coordinates (rank_cells(): the items of
    // its blocks), and of the base's.
    const BlockRange  own = rank_cells(n, this_rank());
    std::vector<char> received(n, 0);
    for (unsigned int k = own.begin; k < own.end; ++k)
      received[k] = !read[k];
    shared.received = flagged_ranges(received);
    shared.kept     = kept_coordinate_ranges(std::move(read));
    // The base keeps its own blocks of coordinates (MechanicalSystem::
    // kept_coordinates()), so the rank whose blocks hold a coordinate has
    // its gradient.
    const BlockRange base_own = rank_cells(base_system->n_dofs(), this_rank());
    for (unsigned int i = base_own.begin; i < base_own.end; ++i)
      if (reduced_dofs[i] != invalid)
        shared.sent.push_back(reduced_dofs[i]);
    shared.sent_gradient.resize(shared.sent.size());
    return &shared;
  }



  const std::vector<BlockRange> *
  SupportedSystem::kept_coordinates() const
  {
    const SharedState *shared = current_shared_state();
    return shared ? &shared->kept : nullptr;
  }



  void
  SupportedSystem::kept_gradient(const Vector &q, Vector &g) const
  {
    SharedState *shared = current_shared_state();
    if (shared == nullptr)
      {
        gradient(q, g);
        return;
      }
    scatter_kept(q, scratch_q);
    base_system->kept_gradient(scratch_q, scratch_g);
    if (g.size() != n_dofs())
      g.reinit(n_dofs());
    for (const BlockRange range : shared->kept)
      for (unsigned int k = range.begin; k < range.end; ++k)
        g[k] = scratch_g[free_dofs[k]];
    for (std::size_t j = 0; j < shared->sent.size(); ++j)
      shared->sent_gradient[j] = g[shared->sent[j]];
    if (shared->exchange == nullptr)
      shared->exchange = std::make_unique<GhostExchange>(shared->sent,
                                                         shared->received,
                                                         n_dofs());
    shared->exchange->send(shared->sent_gradient.data(), g.data());
  }



  void
  SupportedSystem::complete_state(Vector &x) const
  {
    if (current_shared_state() == nullptr)
      return;
    scatter(x, scratch_q);
    base_system->complete_state(scratch_q);
    gather(scratch_q, x);
  }



  unsigned int
  SupportedSystem::n_dofs() const
  {
    return free_dofs.size();
  }



  const Vector &
  SupportedSystem::inverse_mass() const
  {
    return inv_mass;
  }



  double
  SupportedSystem::energy(const Vector &q) const
  {
    scatter_kept(q, scratch_q);
    return base_system->energy(scratch_q);
  }



  void
  SupportedSystem::gradient(const Vector &q, Vector &g) const
  {
    scatter(q, scratch_q);
    base_system->gradient(scratch_q, scratch_g);
    gather(scratch_g, g);
  }



  std::unique_ptr<FreeFlight>
  SupportedSystem::free_flight(const Vector &q, const Vector &v) const
  {
    scatter_kept(q, flight_q);
    scatter_kept(v, flight_v); // zero on the fixed points, always
    return base_system->free_flight(flight_q, flight_v);
  }



  std::optional<ConstraintEvent>
  SupportedSystem::first_constraint_event(const Vector &q,
                                          const Vector &v,
                                          const double  s_max) const
  {
    scatter(q, scratch_q);
    scatter(v, scratch_v);
    std::optional<ConstraintEvent> event =
      base_system->first_constraint_event(scratch_q, scratch_v, s_max);
    if (event)
      event->normal = restrict(event->normal);
    return event;
  }



  std::vector<SparseNormal>
  SupportedSystem::touching_constraints(const Vector &q) const
  {
    scatter(q, scratch_q);
    std::vector<SparseNormal> normals;
    for (const SparseNormal &normal :
         base_system->touching_constraints(scratch_q))
      {
        SparseNormal free_part;
        for (const auto &[dof, value] : normal)
          if (reduced_dofs[dof] != invalid && value != 0.)
            free_part.emplace_back(reduced_dofs[dof], value);
        if (!free_part.empty())
          normals.push_back(std::move(free_part));
      }
    return normals;
  }



  const dealii::SparsityPattern &
  SupportedSystem::hessian_sparsity() const
  {
    build_hessian_structure();
    return *sparsity;
  }



  void
  SupportedSystem::hessian(const Vector                 &q,
                           dealii::SparseMatrix<double> &H) const
  {
    build_hessian_structure();
    if (H.m() != n_dofs() || H.n() != n_dofs())
      throw std::invalid_argument(
        "SupportedSystem::hessian: the matrix is " + std::to_string(H.m()) +
        " x " + std::to_string(H.n()) + ", not " + std::to_string(n_dofs()) +
        " square (initialise it with hessian_sparsity()).");
    scatter(q, scratch_q);
    base_system->hessian(scratch_q, *full_hessian);

    // Row by row, the entries of the block come in the order of the base's
    // row with the fixed columns left out: both patterns store the diagonal
    // first and then the columns in increasing order, and the renumbering of
    // the free coordinates keeps their order.
    const dealii::SparseMatrix<double> &full = *full_hessian;
    for (unsigned int r = 0; r < free_dofs.size(); ++r)
      {
        auto       entry = H.begin(r);
        const auto end   = H.end(r);
        for (auto full_entry = full.begin(free_dofs[r]);
             full_entry != full.end(free_dofs[r]);
             ++full_entry)
          {
            const unsigned int column = reduced_dofs[full_entry->column()];
            if (column == invalid)
              continue;
            if (entry == end || entry->column() != column)
              throw std::logic_error(
                "SupportedSystem::hessian: the matrix was not initialised "
                "with hessian_sparsity() (row " +
                std::to_string(r) + ").");
            entry->value() = full_entry->value();
            ++entry;
          }
        if (entry != end)
          throw std::logic_error(
            "SupportedSystem::hessian: the matrix was not initialised with "
            "hessian_sparsity() (row " +
            std::to_string(r) + ").");
      }
  }



  std::vector<double>
  SupportedSystem::observables(const Vector &q, const Vector &v) const
  {
    scatter(q, scratch_q);
    scatter(v, scratch_v);
    return base_system->observables(scratch_q, scratch_v);
  }



  std::string
  SupportedSystem::penetration(const Vector &q) const
  {
    scatter_kept(q, scratch_q);
    return base_system->penetration(scratch_q);
  }



  Vector
  SupportedSystem::expand(const Vector &q_free) const
  {
    Vector full(full_configuration);
    scatter(q_free, full);
    return full;
  }



  Vector
  SupportedSystem::expand_velocity(const Vector &v_free) const
  {
    Vector full(base_system->n_dofs());
    scatter(v_free, full);
    return full;
  }



  Vector SupportedSystem::restrict(const Vector &full) const
  {
    Vector part;
    gather(full, part);
    return part;
  }



  unsigned int
  SupportedSystem::n_fixed_points() const
  {
    return fixed_point_list.size();
  }



  const std::vector<unsigned int> &
  SupportedSystem::fixed_points() const
  {
    return fixed_point_list;
  }



  const std::vector<unsigned int> &
  SupportedSystem::free_points() const
  {
    return free_point_list;
  }



  void
  SupportedSystem::scatter(const Vector &q_free, Vector &full) const
  {
    if (q_free.size() != free_dofs.size())
      throw std::invalid_argument("SupportedSystem: a vector of " +
                                  std::to_string(q_free.size()) +
                                  " entries where the free coordinates are " +
                                  std::to_string(free_dofs.size()) + ".");
    AssertDimension(full.size(), reduced_dofs.size());
    for (unsigned int k = 0; k < free_dofs.size(); ++k)
      full[free_dofs[k]] = q_free[k];
  }



  void
  SupportedSystem::scatter_kept(const Vector &q_free, Vector &full) const
  {
    const SharedState *shared = current_shared_state();
    if (shared == nullptr)
      {
        scatter(q_free, full);
        return;
      }
    AssertDimension(q_free.size(), free_dofs.size());
    AssertDimension(full.size(), reduced_dofs.size());
    for (const BlockRange range : shared->kept)
      for (unsigned int k = range.begin; k < range.end; ++k)
        full[free_dofs[k]] = q_free[k];
  }



  void
  SupportedSystem::gather(const Vector &full, Vector &part) const
  {
    if (full.size() != reduced_dofs.size())
      throw std::invalid_argument(
        "SupportedSystem: a vector of " + std::to_string(full.size()) +
        " entries where the base system has " +
        std::to_string(reduced_dofs.size()) + " coordinates.");
    if (part.size() != free_dofs.size())
      part.reinit(free_dofs.size(), true);
    for (unsigned int k = 0; k < free_dofs.size(); ++k)
      part[k] = full[free_dofs[k]];
  }



  void
  SupportedSystem::build_hessian_structure() const
  {
    if (sparsity)
      return;
    // Throws std::logic_error if the base has no Hessian.
    const dealii::SparsityPattern &full = base_system->hessian_sparsity();
    dealii::DynamicSparsityPattern dsp(free_dofs.size(), free_dofs.size());
    for (unsigned int r = 0; r < free_dofs.size(); ++r)
      for (auto entry = full.begin(free_dofs[r]);
           entry != full.end(free_dofs[r]);
           ++entry)
        {
          const unsigned int column = reduced_dofs[entry->column()];
          if (column != invalid)
            dsp.add(r, column);
        }
    auto pattern = std::make_unique<dealii::SparsityPattern>();
    pattern->copy_from(dsp);
    full_hessian = std::make_unique<dealii::SparseMatrix<double>>(full);
    sparsity     = std::move(pattern);
  }
} // namespace estep
