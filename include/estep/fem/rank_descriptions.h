#ifndef estep_fem_rank_descriptions_h
#define estep_fem_rank_descriptions_h

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <vector>

/**
 * @file
 * deal.II's descriptions of the parts of a serial mesh that MPI ranks take,
 * for every rank, in time proportional to the mesh.
 */

namespace estep
{
  /**
   * The TriangulationDescription::Description of each rank's part of a
   * serial mesh: the cells the rank owns and its ghost layer, the cells that
   * share a vertex with them. Each is the description that deal.II's
   * TriangulationDescription::Utilities::create_description_from_triangulation()
   * makes for that rank of the mesh partitioned by subdomain ids, field for
   * field (unit/fem_rank_descriptions compares them), and a
   * parallel::fullydistributed::Triangulation takes it alike.
   *
   * deal.II's function sweeps the whole mesh for the one rank it describes,
   * so the process that holds the mesh spends O(P N) on P ranks of a mesh of
   * N cells. Here one sweep sorts the cells among the ranks they matter to;
   * after it, a rank's description costs in proportion to its own part:
   * O(N) for all ranks together.
   *
   * For meshes of one level without periodic (coinciding) vertices, as the
   * meshes of bodies are: the cells are the coarse cells, each with the
   * coarse cell id of its index.
   */
  class RankDescriptions
  {
  public:
    /**
     * Sort the cells of @p mesh among @p n_ranks ranks, of which
     * @p cell_rank gives the one that owns each cell, by the cell's index.
     * @p mesh must outlive this object.
     */
    RankDescriptions(const dealii::Triangulation<3, 3> &mesh,
                     std::vector<unsigned int>          cell_rank,
                     const unsigned int                 n_ranks);

    /** The cells rank @p rank takes, in increasing order: its own and its
     * ghost layer. */
    const std::vector<unsigned int> &
    cells_of(const unsigned int rank) const;

    /** The description of the part of rank @p rank, for the communicator
     * MPI_COMM_WORLD. */
    dealii::TriangulationDescription::Description<3, 3>
    describe(const unsigned int rank) const;

  private:
    const dealii::Triangulation<3, 3>     &mesh;
    const std::vector<unsigned int>        cell_rank;
    std::vector<std::vector<unsigned int>> cells_of_rank;
  };
} // namespace estep

#endif
