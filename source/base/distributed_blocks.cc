#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <estep/base/distributed_blocks.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>

namespace estep
{
  namespace
  {
    bool distributed = false;

    /** MPI counts in ints: large messages go in pieces of this many bytes. */
    constexpr std::size_t message_piece = std::size_t(1) << 30;

    MPI_Comm
    communicator()
    {
      return MPI_COMM_WORLD;
    }

    void
    check(const int code, const char *call)
    {
      AssertThrow(code == MPI_SUCCESS,
                  dealii::ExcMessage(std::string(call) + " failed."));
    }
  } // namespace



  void
  distribute_blocks_over_mpi_ranks(const bool distribute)
  {
    int initialized = 0;
    MPI_Initialized(&initialized);
    AssertThrow(initialized || !distribute,
                dealii::ExcMessage("distribute_blocks_over_mpi_ranks(): MPI "
                                   "is not running."));
    distributed = distribute;
  }



  unsigned int
  rank_count()
  {
    if (!distributed)
      return 1;
    int size = 1;
    MPI_Comm_size(communicator(), &size);
    return size;
  }



  unsigned int
  this_rank()
  {
    if (!distributed)
      return 0;
    int rank = 0;
    MPI_Comm_rank(communicator(), &rank);
    return rank;
  }



  BlockRange
  rank_blocks(const unsigned int n_blocks,
              const unsigned int rank,
              const unsigned int n_ranks)
  {
    const unsigned long long n = n_blocks, ranks = n_ranks;
    return {static_cast<unsigned int>(n * rank / ranks),
            static_cast<unsigned int>(n * (rank + 1) / ranks)};
  }



  std::vector<unsigned int>
  block_ranks(const unsigned int n_blocks, const unsigned int n_ranks)
  {
    std::vector<unsigned int> ranks(n_blocks);
    for (unsigned int r = 0; r < n_ranks; ++r)
      {
        const BlockRange blocks = rank_blocks(n_blocks, r, n_ranks);
        std::fill(ranks.begin() + blocks.begin, ranks.begin() + blocks.end, r);
      }
    return ranks;
  }



  std::vector<unsigned int>
  cell_ranks(const unsigned int n_cells, const unsigned int n_ranks)
  {
    const std::vector<unsigned int> block_rank =
      block_ranks(n_blocks(n_cells), n_ranks);
    std::vector<unsigned int> rank(n_cells);
    for (unsigned int e = 0; e < n_cells; ++e)
      rank[e] = block_rank[e / block_size];
    return rank;
  }



  BlockRange
  rank_cells(const unsigned int n_cells,
             const unsigned int rank,
             const unsigned int n_ranks)
  {
    const BlockRange blocks = rank_blocks(n_blocks(n_cells), rank, n_ranks);
    return {std::min(blocks.begin * block_size, n_cells),
            std::min(blocks.end * block_size, n_cells)};
  }



  void
  share_block_items(void              *items,
                    const std::size_t  item_bytes,
                    const unsigned int n_blocks)
  {
    const unsigned int ranks = rank_count();
    if (ranks == 1)
      return;
    std::vector<int> counts(ranks), displacements(ranks);
    for (unsigned int r = 0; r < ranks; ++r)
      {
        const BlockRange blocks = rank_blocks(n_blocks, r);
        counts[r]               = (blocks.end - blocks.begin) * item_bytes;
        displacements[r]        = blocks.begin * item_bytes;
      }
    check(MPI_Allgatherv(MPI_IN_PLACE,
                         0,
                         MPI_DATATYPE_NULL,
                         items,
                         counts.data(),
                         displacements.data(),
                         MPI_BYTE,
                         communicator()),
          "MPI_Allgatherv");
  }



  void
  gather_from_all_ranks(const double                    *mine,
                        const std::vector<unsigned int> &counts,
                        double                          *all)
  {
    const unsigned int ranks = rank_count();
    AssertDimension(counts.size(), ranks);
    if (ranks == 1)
      {
        if (mine != all)
          std::copy(mine, mine + counts[0], all);
        return;
      }
    std::vector<int> sizes(counts.begin(), counts.end()), displacements(ranks);
    std::exclusive_scan(sizes.begin(), sizes.end(), displacements.begin(), 0);
    const bool in_place = mine == all + displacements[this_rank()];
    check(MPI_Allgatherv(in_place ? MPI_IN_PLACE : mine,
                         sizes[this_rank()],
                         MPI_DOUBLE,
                         all,
                         sizes.data(),
                         displacements.data(),
                         MPI_DOUBLE,
                         communicator()),
          "MPI_Allgatherv");
  }



  void
  broadcast_from_first_rank(void *bytes, const std::size_t size)
  {
    if (rank_count() == 1)
      return;
    for (std::size_t start = 0; start < size; start += message_piece)
      check(MPI_Bcast(static_cast<char *>(bytes) + start,
                      static_cast<int>(std::min(message_piece, size - start)),
                      MPI_BYTE,
                      0,
                      communicator()),
            "MPI_Bcast");
  }



  void
  send_bytes_from_first_rank(const unsigned int rank,
                             const void        *bytes,
                             const std::size_t  size)
  {
    for (std::size_t start = 0; start < size; start += message_piece)
      check(MPI_Send(static_cast<const char *>(bytes) + start,
                     static_cast<int>(std::min(message_piece, size - start)),
                     MPI_BYTE,
                     static_cast<int>(rank),
                     0,
                     communicator()),
            "MPI_Send");
  }



  void
  receive_bytes_from_first_rank(void *bytes, const std::size_t size)
  {
    for (std::size_t start = 0; start < size; start += message_piece)
      check(MPI_Recv(static_cast<char *>(bytes) + start,
                     static_cast<int>(std::min(message_piece, size - start)),
                     MPI_BYTE,
                     0,
                     0,
                     communicator(),
                     MPI_STATUS_IGNORE),
            "MPI_Recv");
  }



  int
  largest_over_ranks(const int value)
  {
    if (rank_count() == 1)
      return value;
    int largest = value;
    check(MPI_Allreduce(&value, &largest, 1, MPI_INT, MPI_MAX, communicator()),
          "MPI_Allreduce");
    return largest;
  }



  unsigned int
  ranks_on_this_machine()
  {
    if (rank_count() == 1)
      return 1;
    MPI_Comm machine;
    check(MPI_Comm_split_type(
            communicator(), MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine),
          "MPI_Comm_split_type");
    int size = 1;
    MPI_Comm_size(machine, &size);
    MPI_Comm_free(&machine);
    return size;
  }



  void
  end_all_ranks(const int code)
  {
    if (rank_count() > 1)
      MPI_Abort(communicator(), code);
    std::exit(code);
  }
} // namespace estep
