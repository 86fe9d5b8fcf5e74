#include <deal.II/base/mpi_noncontiguous_partitioner.templates.h>

#include <estep/base/ghost_exchange.h>

namespace estep
{
  GhostExchange::GhostExchange(
    const std::vector<dealii::types::global_dof_index> &owned,
    const std::vector<dealii::types::global_dof_index> &ghosts)
    : n_owned(owned.size())
    , n_coordinates(ghosts.size())
    , partitioner(
        std::make_unique<dealii::Utilities::MPI::NoncontiguousPartitioner>(
          owned,
          ghosts,
          MPI_COMM_WORLD))
  {}

  GhostExchange::~GhostExchange() = default;

  void
  GhostExchange::send(const double *own, double *x) const
  {
    partitioner->export_to_ghosted_array(
      dealii::ArrayView<const double>(own, n_owned),
      dealii::ArrayView<double>(x, n_coordinates));
  }
} // namespace estep
