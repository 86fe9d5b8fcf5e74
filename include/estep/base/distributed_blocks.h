#ifndef estep_base_distributed_blocks_h
#define estep_base_distributed_blocks_h

#include <estep/base/parallel_blocks.h>

#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

/**
 * @file
 * The per-cell loops of a run on several MPI processes (ranks). The blocks
 * of cells of parallel_blocks.h are shared among the ranks in contiguous
 * ranges; each rank computes its own on its threads; then every per-block
 * result is sent to every rank, and each adds them in block order. So every
 * rank holds the same sums, to the last bit, and the same as a run on one
 * process: the blocks depend on the mesh alone, and which rank computed a
 * block's result does not change it.
 *
 * Without distribute_blocks_over_mpi_ranks() (and on one rank) the loops are
 * those of parallel_blocks.h.
 */

namespace estep
{
  /**
   * Share the blocks of the distributed loops among the processes of
   * MPI_COMM_WORLD, which must be running (start_mpi()); or, if not
   * @p distribute, let this process compute every block itself again.
   */
  void
  distribute_blocks_over_mpi_ranks(const bool distribute = true);

  /** The number of ranks the blocks are shared among (1 without MPI). */
  unsigned int
  rank_count();

  /** This process's rank among them (0 without MPI). */
  unsigned int
  this_rank();

  /** The blocks [begin, end) of @p n_blocks that @p rank of @p n_ranks
   * computes: balanced contiguous ranges, in rank order. */
  BlockRange
  rank_blocks(const unsigned int n_blocks,
              const unsigned int rank,
              const unsigned int n_ranks = rank_count());

  /** The rank of @p n_ranks that computes each of @p n_blocks blocks (see
   * rank_blocks()). */
  std::vector<unsigned int>
  block_ranks(const unsigned int n_blocks,
              const unsigned int n_ranks = rank_count());

  /** The rank of @p n_ranks that computes each of @p n_cells cells: that of
   * its block (block_ranks()). */
  std::vector<unsigned int>
  cell_ranks(const unsigned int n_cells,
             const unsigned int n_ranks = rank_count());

  /** The cells [begin, end) of @p n_cells that @p rank of @p n_ranks
   * computes: those of its rank_blocks(). */
  BlockRange
  rank_cells(const unsigned int n_cells,
             const unsigned int rank,
             const unsigned int n_ranks = rank_count());

  /**
   * The coordinates a rank keeps current in a state shared among the ranks
   * (MechanicalSystem::kept_coordinates()): those flagged in @p read (one
   * flag per coordinate) and this rank's blocks of coordinates
   * (rank_blocks() of their n_blocks()), where the sums over coordinates are
   * taken; as sorted disjoint ranges cut at the ends of blocks, which the
   * threads share.
   */
  std::vector<BlockRange>
  kept_coordinate_ranges(std::vector<char> read);

  /** The items flagged in @p flags (one per item), as sorted disjoint ranges
   * cut at the ends of blocks. */
  std::vector<BlockRange>
  flagged_ranges(const std::vector<char> &flags);

  /**
   * @p items holds @p n_blocks items of @p item_bytes bytes each, of which
   * this rank has written those of rank_blocks(n_blocks, this_rank()); on
   * return every rank holds every item, each from the rank that computed it.
   * Collective: every rank must call it with the same sizes.
   */
  void
  share_block_items(void              *items,
                    const std::size_t  item_bytes,
                    const unsigned int n_blocks);

  /**
   * Rank r's @p counts[r] items of @p doubles_per_item doubles each,
   * concatenated in rank order into @p all, on every rank (this rank's are
   * @p mine, which may already be their place in @p all). Collective.
   */
  void
  gather_from_all_ranks(const double                    *mine,
                        const std::vector<unsigned int> &counts,
                        double                          *all,
                        const unsigned int               doubles_per_item = 1);

  /**
   * @p size bytes at @p bytes, on every rank as the first rank holds them.
   * Collective: every rank must call it with the same size.
   */
  void
  broadcast_from_first_rank(void *bytes, const std::size_t size);

  /** @p vector, resized, on every rank as the first rank holds it. T must be
   * trivially copyable. Collective. */
  template <typename T>
  void
  broadcast_from_first_rank(std::vector<T> &vector)
  {
    static_assert(std::is_trivially_copyable_v<T>,
                  "vectors are sent between ranks as bytes");
    std::size_t size = vector.size();
    broadcast_from_first_rank(&size, sizeof(size));
    vector.resize(size);
    broadcast_from_first_rank(vector.data(), size * sizeof(T));
  }

  /** Send @p size bytes at @p bytes from the first rank to rank @p rank,
   * which takes them with receive_bytes_from_first_rank(). */
  void
  send_bytes_from_first_rank(const unsigned int rank,
                             const void        *bytes,
                             const std::size_t  size);

  /** Take @p size bytes into @p bytes that the first rank sends this rank
   * with send_bytes_from_first_rank(). */
  void
  receive_bytes_from_first_rank(void *bytes, const std::size_t size);

  /** The @p n values at @p values, from the first rank to rank @p rank, which
   * takes them with receive_from_first_rank(std::vector<T> &). */
  template <typename T>
  void
  send_from_first_rank(const unsigned int rank, const T *values, std::size_t n)
  {
    static_assert(std::is_trivially_copyable_v<T>,
                  "values are sent between ranks as bytes");
    send_bytes_from_first_rank(rank, &n, sizeof(n));
    send_bytes_from_first_rank(rank, values, n * sizeof(T));
  }

  /** @p vector, resized, as the first rank sends it to this rank. */
  template <typename T>
  void
  receive_from_first_rank(std::vector<T> &vector)
  {
    std::size_t n = 0;
    receive_bytes_from_first_rank(&n, sizeof(n));
    vector.resize(n);
    receive_bytes_from_first_rank(vector.data(), n * sizeof(T));
  }

  /** Every rank's @p value, in rank order, on every rank. Collective. */
  std::vector<double>
  values_of_every_rank(const double value);

  /** The largest of the ranks' @p value. Collective. */
  int
  largest_over_ranks(const int value);

  /**
   * The @p message of the lowest rank whose message is not empty, on every
   * rank (empty if all are): an error some ranks met, known to all.
   * Collective.
   */
  std::string
  first_message_over_ranks(const std::string &message);

  /**
   * Throw std::runtime_error on every rank if a rank's @p value differs
   * from the first rank's; @p what (e.g. "checkpoints <run/checkpoint.bin>")
   * names what the values stand for, which each process read for itself.
   * Collective.
   */
  void
  check_same_on_every_rank(const unsigned long long value,
                           const std::string       &what);

  /**
   * Whether every rank calls this within @p seconds (on a communicator of
   * its own, so that ranks waiting in another collective call cannot meet
   * it): after an error, whether the other ranks met it too, or wait for this
   * one in vain. Collective if they all call it.
   */
  bool
  every_rank_arrives_within(const double seconds);

  /**
   * The number of ranks on this machine (1 without MPI): the machine's cores
   * are theirs to share.
   */
  unsigned int
  ranks_on_this_machine();

  /** End every rank's process at once with exit code @p code (after an error
   * one rank alone met, which the others would wait for in vain). */
  [[noreturn]] void
  end_all_ranks(const int code);

  /**
   * The results @p term(b) of every block b < @p n_blocks, on every rank;
   * each rank computes those of its rank_blocks() on its threads. T must be
   * trivially copyable (it is sent as bytes). Collective.
   */
  template <typename T, typename Term>
  std::vector<T>
  distributed_block_terms(const unsigned int n_blocks, const Term &term)
  {
    static_assert(std::is_trivially_copyable_v<T>,
                  "block results are sent between ranks as bytes");
    std::vector<T>   terms(n_blocks);
    const BlockRange mine = rank_blocks(n_blocks, this_rank());
    for_each_block(mine.end - mine.begin, [&](const unsigned int i) {
      terms[mine.begin + i] = term(mine.begin + i);
    });
    share_block_items(terms.data(), sizeof(T), n_blocks);
    return terms;
  }

  /**
   * The sum of @p term(b) over b < @p n_blocks (at least one), the terms
   * computed by the ranks (see distributed_block_terms()) and added in the
   * order of b, the same on every rank. Collective.
   */
  template <typename T, typename Term>
  T
  sum_over_distributed_blocks(const unsigned int n_blocks, const Term &term)
  {
    const std::vector<T> terms = distributed_block_terms<T>(n_blocks, term);
    T                    total = terms[0];
    for (unsigned int b = 1; b < n_blocks; ++b)
      total += terms[b];
    return total;
  }

  /**
   * sum_over_distributed_blocks() for blocks that every rank could compute,
   * their data being on every rank (the contact's candidate pairs): the ranks
   * share the work of two or more blocks, and compute a single block each
   * itself, without a collective call. The same sum on every rank, to the
   * last bit. Collective if @p n_blocks > 1.
   */
  template <typename T, typename Term>
  T
  sum_over_shared_blocks(const unsigned int n_blocks, const Term &term)
  {
    return n_blocks > 1 ? sum_over_distributed_blocks<T>(n_blocks, term) :
                          T(term(0));
  }
} // namespace estep

#endif
