#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <estep/base/distributed_blocks.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

namespace estep
{
  namespace
  {
    bool distributed = false;

    /** A duplicate of MPI_COMM_WORLD for every_rank_arrives_within() alone. */
    MPI_Comm error_communicator = MPI_COMM_NULL;

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

    /** The MPI type of items of @p bytes bytes, so that a message's counts
     * (ints) count items, not bytes: freed when it goes out of scope. */
    class ItemType
    {
    public:
      explicit ItemType(const std::size_t bytes)
      {
        AssertThrow(bytes <= std::size_t(std::numeric_limits<int>::max()),
                    dealii::ExcMessage("An item of " + std::to_string(bytes) +
                                       " bytes is too large for MPI."));
        check(MPI_Type_contiguous(static_cast<int>(bytes), MPI_BYTE, &type),
              "MPI_Type_contiguous");
        check(MPI_Type_commit(&type), "MPI_Type_commit");
      }
      ~ItemType()
      {
        MPI_Type_free(&type);
      }
      ItemType(const ItemType &) = delete;
      ItemType              &
      operator=(const ItemType &) = delete;
      MPI_Datatype type;
    };

    /** @p counts as MPI's ints, and their exclusive sums, which must fit an
     * int too (the messages' offsets). */
    std::pair<std::vector<int>, std::vector<int>>
    counts_and_displacements(const std::vector<unsigned int> &counts)
    {
      std::vector<int> sizes(counts.size()), displacements(counts.size());
      long long        total = 0;
      for (std::size_t r = 0; r < counts.size(); ++r)
        {
          displacements[r] = static_cast<int>(total);
          sizes[r]         = static_cast<int>(counts[r]);
          total += counts[r];
          AssertThrow(total <= std::numeric_limits<int>::max(),
                      dealii::ExcMessage(
                        "A gather between the processes of more than 2^31 "
                        "items: too large for MPI's counts."));
        }
      return {sizes, displacements};
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
    if (distribute && error_communicator == MPI_COMM_NULL)
      check(MPI_Comm_dup(communicator(), &error_communicator), "MPI_Comm_dup");
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



  std::vector<BlockRange>
  kept_coordinate_ranges(std::vector<char> read)
  {
    const unsigned int n      = read.size();
    const BlockRange   blocks = rank_blocks(n_blocks(n), this_rank());
    if (blocks.begin < blocks.end)
      std::fill(read.begin() + block_range(blocks.begin, n).begin,
                read.begin() + block_range(blocks.end - 1, n).end,
                1);
    return flagged_ranges(read);
  }



  std::vector<BlockRange>
  flagged_ranges(const std::vector<char> &flags)
  {
    std::vector<BlockRange> ranges;
    for (unsigned int i = 0; i < flags.size(); ++i)
      if (flags[i])
        {
          if (!ranges.empty() && ranges.back().end == i && i % block_size != 0)
            ++ranges.back().end;
          else
            ranges.push_back({i, i + 1});
        }
    return ranges;
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
    std::vector<unsigned int> blocks_per_rank(ranks);
    for (unsigned int r = 0; r < ranks; ++r)
      {
        const BlockRange blocks = rank_blocks(n_blocks, r);
        blocks_per_rank[r]      = blocks.end - blocks.begin;
      }
    const auto [counts, displacements] =
      counts_and_displacements(blocks_per_rank);
    const ItemType item(item_bytes);
    check(MPI_Allgatherv(MPI_IN_PLACE,
                         0,
                         MPI_DATATYPE_NULL,
                         items,
                         counts.data(),
                         displacements.data(),
                         item.type,
                         communicator()),
          "MPI_Allgatherv");
  }



  void
  gather_from_all_ranks(const double                    *mine,
                        const std::vector<unsigned int> &counts,
                        double                          *all,
                        const unsigned int               doubles_per_item)
  {
    const unsigned int ranks = rank_count();
    AssertDimension(counts.size(), ranks);
    if (ranks == 1)
      {
        if (mine != all)
          std::copy(mine,
                    mine + std::size_t(counts[0]) * doubles_per_item,
                    all);
        return;
      }
    const auto [sizes, displacements] = counts_and_displacements(counts);
    const bool in_place =
      mine == all + std::size_t(displacements[this_rank()]) * doubles_per_item;
    const ItemType item(doubles_per_item * sizeof(double));
    check(MPI_Allgatherv(in_place ? MPI_IN_PLACE : mine,
                         sizes[this_rank()],
                         item.type,
                         all,
                         sizes.data(),
                         displacements.data(),
                         item.type,
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



  std::vector<double>
  values_of_every_rank(const double value)
  {
    std::vector<double> all(rank_count());
    gather_from_all_ranks(&value,
                          std::vector<unsigned int>(rank_count(), 1),
                          all.data());
    return all;
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



  std::string
  first_message_over_ranks(const std::string &message)
  {
    const unsigned int ranks = rank_count();
    if (ranks == 1)
      return message;
    const int mine =
      message.empty() ? static_cast<int>(ranks) : static_cast<int>(this_rank());
    int first = mine;
    check(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, communicator()),
          "MPI_Allreduce");
    if (first == static_cast<int>(ranks))
      return {};
    std::string        text = message;
    unsigned long long size = text.size();
    check(MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG_LONG, first, communicator()),
          "MPI_Bcast");
    text.resize(size);
    check(MPI_Bcast(text.data(),
                    static_cast<int>(size),
                    MPI_CHAR,
                    first,
                    communicator()),
          "MPI_Bcast");
    return text;
  }



  void
  check_same_on_every_rank(const unsigned long long value,
                           const std::string       &what)
  {
    if (rank_count() == 1)
      return;
    unsigned long long first = value;
    broadcast_from_first_rank(&first, sizeof(first));
    const int differs = first != value ? static_cast<int>(this_rank()) : 0;
    if (const int rank = largest_over_ranks(differs); rank != 0)
      throw std::runtime_error(
        "The processes read different " + what + " (those of process " +
        std::to_string(rank) +
        " are not the first's): each process reads them itself, so on "
        "several machines the files must be the same (on a file system they "
        "share).");
  }



  bool
  every_rank_arrives_within(const double seconds)
  {
    if (rank_count() == 1)
      return true;
    MPI_Request request;
    check(MPI_Ibarrier(error_communicator, &request), "MPI_Ibarrier");
    const auto end =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    for (;;)
      {
        int arrived = 0;
        check(MPI_Test(&request, &arrived, MPI_STATUS_IGNORE), "MPI_Test");
        if (arrived)
          return true;
        if (std::chrono::steady_clock::now() > end)
          return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
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
