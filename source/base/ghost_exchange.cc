#include <deal.II/base/mpi_noncontiguous_partitioner.templates.h>

#include <estep/base/ghost_exchange.h>

#include <algorithm>

namespace estep
{
  GhostExchange::GhostExchange(
    const std::vector<dealii::types::global_dof_index> &owned,
    const std::vector<BlockRange>                      &kept,
    const unsigned int                                  n_exchanged)
    : n_owned(owned.size())
    , n_coordinates(n_exchanged)
  {
    // deal.II's ghost array: each ghost at its own index, the rest invalid.
    std::vector<char> is_owned(n_exchanged, 0);
    for (const auto i : owned)
      is_owned[i] = 1;
    std::vector<dealii::types::global_dof_index> ghosts(
      n_exchanged, dealii::numbers::invalid_dof_index);
    for (const BlockRange range : kept)
      for (unsigned int i = range.begin; i < std::min(range.end, n_exchanged);
           ++i)
        if (!is_owned[i])
          ghosts[i] = i;
    partitioner =
      std::make_unique<dealii::Utilities::MPI::NoncontiguousPartitioner>(
        owned, ghosts, MPI_COMM_WORLD);
  }

  GhostExchange::~GhostExchange() = default;

  void
  GhostExchange::send(const double *own, double *x) const
  {
    partitioner->export_to_ghosted_array(
      dealii::ArrayView<const double>(own, n_owned),
      dealii::ArrayView<double>(x, n_coordinates));
  }
} // namespace estep
