#ifndef estep_base_ghost_exchange_h
#define estep_base_ghost_exchange_h

#include <deal.II/base/types.h>

#include <estep/base/parallel_blocks.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace dealii::Utilities::MPI
{
  class NoncontiguousPartitioner;
} // namespace dealii::Utilities::MPI

namespace estep
{
  /**
   * The values of a state shared among the MPI ranks (see
   * MechanicalSystem::kept_coordinates()) sent from the rank that computes
   * each coordinate to the ranks that keep it too: deal.II's
   * Utilities::MPI::NoncontiguousPartitioner over MPI_COMM_WORLD, whose
   * messages go to the ranks that share coordinates alone.
   */
  class GhostExchange
  {
  public:
    /**
     * @p owned: the coordinates this rank computes, in the order of the
     * values send() takes. @p kept: the coordinates it keeps current
     * (MechanicalSystem::kept_coordinates()); those below @p n_exchanged
     * that it does not own are its ghosts, each computed by one other rank.
     * Collective.
     */
    GhostExchange(const std::vector<dealii::types::global_dof_index> &owned,
                  const std::vector<BlockRange>                      &kept,
                  const unsigned int n_exchanged);

    ~GhostExchange();

    /** Write into @p x (the whole state) at the ghosts the values of the
     * ranks that compute them, each rank giving @p own, the values of its
     * owned coordinates. Collective. */
    void
    send(const double *own, double *x) const;

  private:
    std::size_t n_owned, n_coordinates;
    std::unique_ptr<dealii::Utilities::MPI::NoncontiguousPartitioner>
      partitioner;
  };
} // namespace estep

#endif
