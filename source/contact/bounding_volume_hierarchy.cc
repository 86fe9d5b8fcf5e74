#include <estep/base/parallel_blocks.h>
#include <estep/contact/bounding_volume_hierarchy.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace estep
{
  namespace contact
  {
    namespace
    {
      // Larger leaves trade node visits for triangle tests, which are cheaper
      // (branch-free, contiguous): 8 was about 10% faster than 4 on the
      // self-query of the benchmark's two spheres.
      constexpr unsigned int leaf_size = 8;

      // Outward rounding of a computed coordinate: two units in the last place
      // of its magnitude plus the smallest normal number (covers the single
      // rounding of q + s v and of the bound itself).
      inline double
      round_down(const double x)
      {
        return x - (std::abs(x) * 4.5e-16 + std::numeric_limits<double>::min());
      }

      inline double
      round_up(const double x)
      {
        return x + (std::abs(x) * 4.5e-16 + std::numeric_limits<double>::min());
      }

      // Same result as BoundingBox::overlaps(), without short-circuit
      // evaluation: in the queries' inner loops the outcome is hard to
      // predict, and six comparisons cost less than the mispredicted branches.
      inline bool
      overlap(const BoundingBox &a, const BoundingBox &b)
      {
        return (a.lower[0] <= b.upper[0]) & (b.lower[0] <= a.upper[0]) &
               (a.lower[1] <= b.upper[1]) & (b.lower[1] <= a.upper[1]) &
               (a.lower[2] <= b.upper[2]) & (b.lower[2] <= a.upper[2]);
      }

      // Same result as share_vertex(), evaluated without branches (the test
      // follows every box overlap, and most overlapping boxes in a surface
      // belong to neighbours).
      inline bool
      share_index(const TriangleIndices &a, const TriangleIndices &b)
      {
        return (a[0] == b[0]) | (a[0] == b[1]) | (a[0] == b[2]) |
               (a[1] == b[0]) | (a[1] == b[1]) | (a[1] == b[2]) |
               (a[2] == b[0]) | (a[2] == b[1]) | (a[2] == b[2]);
      }

      // Adds point i at q, and at q + s_max v if v is given (rounded
      // outward), to the box.
      inline void
      add_point(BoundingBox       &b,
                const double      *q,
                const double      *v,
                const double       s_max,
                const unsigned int i)
      {
        for (unsigned int k = 0; k < 3; ++k)
          {
            const double x = q[3 * i + k];
            b.lower[k]     = std::min(b.lower[k], x);
            b.upper[k]     = std::max(b.upper[k], x);
            if (v != nullptr)
              {
                const double y = x + s_max * v[3 * i + k];
                b.lower[k]     = std::min(b.lower[k], round_down(y));
                b.upper[k]     = std::max(b.upper[k], round_up(y));
              }
          }
      }

      inline void
      enlarge(BoundingBox &b, const double margin)
      {
        if (margin > 0.)
          for (unsigned int k = 0; k < 3; ++k)
            {
              b.lower[k] = round_down(b.lower[k] - margin);
              b.upper[k] = round_up(b.upper[k] + margin);
            }
      }

      inline void
      unite(BoundingBox &a, const BoundingBox &b)
      {
        for (unsigned int k = 0; k < 3; ++k)
          {
            a.lower[k] = std::min(a.lower[k], b.lower[k]);
            a.upper[k] = std::max(a.upper[k], b.upper[k]);
          }
      }
    } // namespace



    BoundingVolumeHierarchy::BoundingVolumeHierarchy(
      std::vector<TriangleIndices> triangles_in,
      std::vector<unsigned int>    exclusion_groups)
      : triangles(std::move(triangles_in))
      , max_index(0)
    {
      for (const auto &t : triangles)
        for (const unsigned int i : t)
          {
            max_index = std::max(max_index, i);
            triangle_vertices.push_back(i);
          }
      std::sort(triangle_vertices.begin(), triangle_vertices.end());
      triangle_vertices.erase(std::unique(triangle_vertices.begin(),
                                          triangle_vertices.end()),
                              triangle_vertices.end());
      set_exclusion_groups(std::move(exclusion_groups));
    }



    double
    BoundingVolumeHierarchy::largest_vertex_coordinate(const double *x) const
    {
      double largest = 0.;
      for (const unsigned int i : triangle_vertices)
        for (unsigned int d = 0; d < 3; ++d)
          largest = std::max(largest, std::abs(x[3 * i + d]));
      return largest;
    }



    void
    BoundingVolumeHierarchy::set_exclusion_groups(
      std::vector<unsigned int> exclusion_groups)
    {
      if (!exclusion_groups.empty() &&
          exclusion_groups.size() != triangles.size())
        throw std::invalid_argument("BoundingVolumeHierarchy: " +
                                    std::to_string(exclusion_groups.size()) +
                                    " exclusion groups for " +
                                    std::to_string(triangles.size()) +
                                    " triangles; one per triangle expected");
      groups = std::move(exclusion_groups);
      nodes.clear();
      order.clear();
      group_point_start.clear();
      group_points.clear();
      group_points_indexed = false;
    }



    void
    BoundingVolumeHierarchy::index_group_points()
    {
      group_points_indexed = true;
      if (groups.empty())
        return;
      const unsigned int n_groups =
        *std::max_element(groups.begin(), groups.end()) + 1;
      if (16 * std::size_t(n_groups) > triangles.size())
        return;
      std::vector<std::pair<unsigned int, unsigned int>> group_and_point;
      for (unsigned int t = 0; t < triangles.size(); ++t)
        for (const unsigned int i : triangles[t])
          group_and_point.emplace_back(groups[t], i);
      std::sort(group_and_point.begin(), group_and_point.end());
      group_and_point.erase(std::unique(group_and_point.begin(),
                                        group_and_point.end()),
                            group_and_point.end());
      group_point_start.assign(n_groups + 1, 0);
      for (const auto &[group, point] : group_and_point)
        {
          ++group_point_start[group + 1];
          group_points.push_back(point);
        }
      for (unsigned int g = 0; g < n_groups; ++g)
        group_point_start[g + 1] += group_point_start[g];
    }



    std::vector<bool>
    BoundingVolumeHierarchy::isolated_groups(const double *q,
                                             const double *v,
                                             const double  s_max,
                                             const double  margin) const
    {
      if (group_point_start.empty())
        return {};
      const unsigned int       n_groups = group_point_start.size() - 1;
      std::vector<BoundingBox> box(n_groups, BoundingBox::empty());
      for (unsigned int g = 0; g < n_groups; ++g)
        {
          for (unsigned int p = group_point_start[g];
               p < group_point_start[g + 1];
               ++p)
            add_point(box[g], q, v, s_max, group_points[p]);
          enlarge(box[g], margin);
        }
      std::vector<bool> isolated(n_groups, true);
      for (const auto &[a, b] : overlapping_pairs(box))
        isolated[a] = isolated[b] = false;
      return isolated;
    }



    std::vector<std::pair<unsigned int, unsigned int>>
    overlapping_pairs(const std::vector<BoundingBox> &boxes)
    {
      const unsigned int        n = boxes.size();
      std::vector<unsigned int> by_x(n);
      std::iota(by_x.begin(), by_x.end(), 0u);
      std::sort(by_x.begin(), by_x.end(), [&](unsigned int a, unsigned int b) {
        return boxes[a].lower[0] < boxes[b].lower[0];
      });
      std::vector<std::pair<unsigned int, unsigned int>> pairs;
      for (unsigned int a = 0; a < n; ++a)
        for (unsigned int b = a + 1;
             b < n && boxes[by_x[b]].lower[0] <= boxes[by_x[a]].upper[0];
             ++b)
          if (boxes[by_x[a]].overlaps(boxes[by_x[b]]))
            pairs.push_back(std::minmax(by_x[a], by_x[b]));
      return pairs;
    }



    void
    BoundingVolumeHierarchy::compute_boxes(const double     *q,
                                           const double     *v,
                                           const std::size_t n,
                                           const double      s_max,
                                           const double      margin,
                                           const bool skip_isolated_groups)
    {
      if (!triangles.empty() && 3 * std::size_t(max_index) + 2 >= n)
        throw std::invalid_argument(
          "BoundingVolumeHierarchy: a triangle refers to point " +
          std::to_string(max_index) + " but the coordinate vector has only " +
          std::to_string(n) + " entries (" + std::to_string(n / 3) +
          " points)");
      if (!(margin >= 0.) || (v != nullptr && !(s_max >= 0.)))
        throw std::invalid_argument(
          "BoundingVolumeHierarchy: margin and s_max must be non-negative");
      boxes.resize(triangles.size());
      if (skip_isolated_groups && !group_points_indexed)
        index_group_points();
      isolated = skip_isolated_groups ? isolated_groups(q, v, s_max, margin) :
                                        std::vector<bool>();
      // Each box on its own: in parallel blocks, the same bits on any number
      // of threads.
      const unsigned int n_triangles = triangles.size();
      for_each_block(n_blocks(n_triangles), [&](const unsigned int block) {
        const BlockRange range = block_range(block, n_triangles);
        for (unsigned int t = range.begin; t < range.end; ++t)
          {
            BoundingBox &b = boxes[t];
            b              = BoundingBox::empty();
            if (!isolated.empty() && isolated[groups[t]])
              continue;
            for (const unsigned int i : triangles[t])
              add_point(b, q, v, s_max, i);
            enlarge(b, margin);
          }
      });
    }



    namespace
    {
      constexpr unsigned int morton_bits = 21; // per axis: 63-bit codes

      // Spread the low 21 bits of x so that bit i moves to bit 3i.
      inline std::uint64_t
      spread_bits(std::uint64_t x)
      {
        x &= 0x1fffff;
        x = (x | x << 32) & 0x1f00000000ffffULL;
        x = (x | x << 16) & 0x1f0000ff0000ffULL;
        x = (x | x << 8) & 0x100f00f00f00f00fULL;
        x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
        x = (x | x << 2) & 0x1249249249249249ULL;
        return x;
      }
    } // namespace



    void
    BoundingVolumeHierarchy::sort_by_morton_code()
    {
      const std::size_t n = triangles.size();
      // Quantise the box centres on a cubic grid over their bounding box (the
      // same cell size on every axis, so that splits at cell midplanes cut
      // the longest extent first).
      double lo[3], hi[3];
      for (unsigned int k = 0; k < 3; ++k)
        {
          lo[k] = std::numeric_limits<double>::infinity();
          hi[k] = -lo[k];
        }
      for (const BoundingBox &b : boxes)
        for (unsigned int k = 0; k < 3; ++k)
          {
            const double c = 0.5 * b.lower[k] + 0.5 * b.upper[k];
            lo[k]          = std::min(lo[k], c);
            hi[k]          = std::max(hi[k], c);
          }
      const double extent =
        std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
      constexpr double cells = double(1u << morton_bits);
      // Infinite or NaN extents (non-finite input) put everything in cell 0:
      // the tree is then balanced by middle splits, still correct.
      const double scale =
        (extent > 0. && extent < std::numeric_limits<double>::infinity()) ?
          cells / extent :
          0.;
      codes.resize(n);
      order.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        {
          std::uint64_t code = 0;
          for (unsigned int k = 0; k < 3; ++k)
            {
              const double c =
                (0.5 * boxes[i].lower[k] + 0.5 * boxes[i].upper[k] - lo[k]) *
                scale;
              const std::uint64_t cell =
                c > 0. ? std::min<std::uint64_t>(c, cells - 1.) : 0;
              code |= spread_bits(cell) << k;
            }
          codes[i] = code;
          order[i] = i;
        }

      // Least significant digit radix sort, 11 bits per pass (six passes
      // cover 63 bits; passes where all codes have the same digit are
      // skipped). Stable, so equal codes keep the triangle order.
      constexpr unsigned int digit_bits = 11, n_buckets = 1u << digit_bits;
      code_buffer.resize(n);
      order_buffer.resize(n);
      std::vector<std::size_t> count(n_buckets);
      for (unsigned int shift = 0; shift < 3 * morton_bits; shift += digit_bits)
        {
          std::fill(count.begin(), count.end(), 0);
          for (std::size_t i = 0; i < n; ++i)
            ++count[(codes[i] >> shift) & (n_buckets - 1)];
          if (count[(codes[0] >> shift) & (n_buckets - 1)] == n)
            continue;
          std::size_t sum = 0;
          for (std::size_t &c : count)
            sum += std::exchange(c, sum);
          for (std::size_t i = 0; i < n; ++i)
            {
              const std::size_t j =
                count[(codes[i] >> shift) & (n_buckets - 1)]++;
              code_buffer[j]  = codes[i];
              order_buffer[j] = order[i];
            }
          codes.swap(code_buffer);
          order.swap(order_buffer);
        }
    }



    void
    BoundingVolumeHierarchy::build_tree()
    {
      const std::size_t n = triangles.size();
      nodes.clear();
      order.clear();
      refits_since_build = 0;
      if (n == 0)
        return;
      sort_by_morton_code();

      // A node of more than leaf_size triangles is split where its codes'
      // highest differing bit changes (the codes are sorted, so that is one
      // binary search); if all codes agree (triangles in one cell) it is cut
      // in the middle. Both halves are non-empty, so the tree has at most
      // 2 n - 1 nodes.
      nodes.reserve(2 * n);
      nodes.push_back(
        Node{BoundingBox(), 0, static_cast<unsigned int>(n), 0, mixed_groups});
      std::vector<unsigned int> stack = {0};
      while (!stack.empty())
        {
          const unsigned int node = stack.back();
          stack.pop_back();
          const unsigned int begin = nodes[node].begin, end = nodes[node].end;
          if (end - begin <= leaf_size)
            continue;
          const std::uint64_t differing = codes[begin] ^ codes[end - 1];
          unsigned int        mid       = begin + (end - begin) / 2;
          if (differing != 0)
            {
              std::uint64_t bit = std::uint64_t(1) << 63;
              while ((bit & differing) == 0)
                bit >>= 1;
              mid = std::partition_point(codes.begin() + begin,
                                         codes.begin() + end,
                                         [bit](const std::uint64_t c) {
                                           return (c & bit) == 0;
                                         }) -
                    codes.begin();
            }
          const unsigned int child = nodes.size();
          nodes[node].first_child  = child;
          nodes.push_back(Node{BoundingBox(), begin, mid, 0, mixed_groups});
          nodes.push_back(Node{BoundingBox(), mid, end, 0, mixed_groups});
          stack.push_back(child);
          stack.push_back(child + 1);
        }
      ordered_triangles.resize(n);
      ordered_groups.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        {
          ordered_triangles[i] = triangles[order[i]];
          ordered_groups[i]    = groups.empty() ? order[i] : groups[order[i]];
        }
      // Each node's group, children before their parent (they come after
      // it).
      for (std::size_t j = nodes.size(); j-- > 0;)
        {
          Node &node = nodes[j];
          if (node.first_child == 0)
            {
              node.group = ordered_groups[node.begin];
              for (unsigned int i = node.begin + 1; i < node.end; ++i)
                if (ordered_groups[i] != node.group)
                  node.group = mixed_groups;
            }
          else if (nodes[node.first_child].group ==
                   nodes[node.first_child + 1].group)
            node.group = nodes[node.first_child].group;
        }
      refit_tree();
    }



    void
    BoundingVolumeHierarchy::refit_tree()
    {
      // Boxes in tree order, for cache-friendly leaf tests, gathered leaf by
      // leaf. Children come after their parent: a backward sweep visits
      // children first. A subtree of a group alone gets an empty box
      // without a look at its triangles, which the descent never enters.
      ordered_boxes.resize(order.size());
      for (std::size_t j = nodes.size(); j-- > 0;)
        {
          Node &node = nodes[j];
          if (!isolated.empty() && node.group != mixed_groups &&
              isolated[node.group])
            node.box = BoundingBox::empty();
          else if (node.first_child == 0)
            {
              node.box = BoundingBox::empty();
              for (unsigned int i = node.begin; i < node.end; ++i)
                {
                  ordered_boxes[i] = boxes[order[i]];
                  unite(node.box, ordered_boxes[i]);
                }
            }
          else
            {
              node.box = nodes[node.first_child].box;
              unite(node.box, nodes[node.first_child + 1].box);
            }
        }
    }



    void
    BoundingVolumeHierarchy::build(const double     *q,
                                   const std::size_t n,
                                   const double      margin)
    {
      compute_boxes(q, nullptr, n, 0., margin, false);
      build_tree();
    }



    void
    BoundingVolumeHierarchy::build_swept(const double     *q,
                                         const double     *v,
                                         const std::size_t n,
                                         const double      s_max,
                                         const double      margin)
    {
      compute_boxes(q, v, n, s_max, margin, false);
      build_tree();
    }



    bool
    BoundingVolumeHierarchy::rebuild_due()
    {
      return rebuild_interval > 0 && ++refits_since_build >= rebuild_interval;
    }



    void
    BoundingVolumeHierarchy::refit(const double     *q,
                                   const std::size_t n,
                                   const double      margin)
    {
      if (!is_built() || rebuild_due())
        return build(q, n, margin);
      compute_boxes(q, nullptr, n, 0., margin, true);
      refit_tree();
    }



    void
    BoundingVolumeHierarchy::refit_swept(const double     *q,
                                         const double     *v,
                                         const std::size_t n,
                                         const double      s_max,
                                         const double      margin)
    {
      if (!is_built() || rebuild_due())
        return build_swept(q, v, n, s_max, margin);
      compute_boxes(q, v, n, s_max, margin, true);
      refit_tree();
    }



    namespace
    {
      using NodePair = std::pair<unsigned int, unsigned int>;

      /** The node pairs a descent starts from before it splits into tasks. */
      constexpr std::size_t descent_tasks = 64;

      /**
       * A simultaneous descent of two trees from the node pair @p root:
       * @p visit(node pair, next, pairs, prune) handles one node pair, adding
       * the triangle pairs it finds to pairs and the node pairs to descend
       * into to next. The node pairs are first visited breadth first until
       * descent_tasks of them wait (or none); each of those then starts a
       * depth-first descent, on the threads, into its own list; the lists are
       * appended in turn. The order of the pairs so depends on the trees
       * alone, not on the number of threads. Node pairs that can hold no
       * wanted triangle pair may be pruned (prune = true) in the depth-first
       * descents only: pruning there removes whole subtrees from a descent
       * and leaves the order of the rest, while in the breadth-first part it
       * would change which node pairs start the descents.
       */
      template <typename Visit>
      void
      descend(const NodePair                                     &root,
              const Visit                                        &visit,
              std::vector<std::pair<unsigned int, unsigned int>> &pairs)
      {
        std::vector<NodePair> waiting{root}, next;
        std::size_t           first = 0;
        while (first < waiting.size() && waiting.size() - first < descent_tasks)
          {
            next.clear();
            visit(waiting[first++], next, pairs, false);
            waiting.insert(waiting.end(), next.begin(), next.end());
          }
        const unsigned int n_tasks = waiting.size() - first;
        std::vector<std::vector<std::pair<unsigned int, unsigned int>>> found(
          n_tasks);
        for_each_block(n_tasks, [&](const unsigned int task) {
          std::vector<NodePair> stack{waiting[first + task]};
          stack.reserve(128);
          while (!stack.empty())
            {
              const NodePair pair = stack.back();
              stack.pop_back();
              visit(pair, stack, found[task], true);
            }
        });
        for (const auto &task_pairs : found)
          pairs.insert(pairs.end(), task_pairs.begin(), task_pairs.end());
      }
    } // namespace



    void
    BoundingVolumeHierarchy::find_pairs(
      std::vector<std::pair<unsigned int, unsigned int>> &pairs) const
    {
      pairs.clear();
      if (nodes.empty())
        return;
      // Simultaneous descent of the tree against itself (a, b: nodes; i, j:
      // positions in tree order): a node against itself gives its children
      // against themselves and against each other; other pairs of nodes are
      // only descended into if their boxes overlap, and not at all if all
      // their triangles lie in one exclusion group.
      const auto visit =
        [&](const NodePair                                     &ab,
            std::vector<NodePair>                              &next,
            std::vector<std::pair<unsigned int, unsigned int>> &found,
            const bool                                          prune) {
          const auto test = [&](const unsigned int i, const unsigned int j) {
            if (overlap(ordered_boxes[i], ordered_boxes[j]) &
                !share_index(ordered_triangles[i], ordered_triangles[j]) &
                (ordered_groups[i] != ordered_groups[j]))
              found.emplace_back(std::min(order[i], order[j]),
                                 std::max(order[i], order[j]));
          };
          const auto [a, b] = ab;
          const Node &A = nodes[a], &B = nodes[b];
          if (prune && A.group != mixed_groups && A.group == B.group)
            return;
          const bool a_leaf = A.first_child == 0, b_leaf = B.first_child == 0;
          if (a == b)
            {
              if (a_leaf)
                {
                  for (unsigned int i = A.begin; i < A.end; ++i)
                    for (unsigned int j = i + 1; j < A.end; ++j)
                      test(i, j);
                }
              else
                {
                  const unsigned int c = A.first_child;
                  next.emplace_back(c, c);
                  next.emplace_back(c + 1, c + 1);
                  if (overlap(nodes[c].box, nodes[c + 1].box))
                    next.emplace_back(c, c + 1);
                }
            }
          else if (a_leaf && b_leaf)
            {
              for (unsigned int i = A.begin; i < A.end; ++i)
                if (overlap(ordered_boxes[i], B.box))
                  for (unsigned int j = B.begin; j < B.end; ++j)
                    test(i, j);
            }
          else if (b_leaf || (!a_leaf && A.end - A.begin >= B.end - B.begin))
            {
              for (const unsigned int c : {A.first_child, A.first_child + 1})
                if (overlap(nodes[c].box, B.box))
                  next.emplace_back(c, b);
            }
          else
            {
              for (const unsigned int c : {B.first_child, B.first_child + 1})
                if (overlap(A.box, nodes[c].box))
                  next.emplace_back(a, c);
            }
        };
      descend({0, 0}, visit, pairs);
    }



    void
    BoundingVolumeHierarchy::find_pairs(
      const BoundingVolumeHierarchy                      &other,
      std::vector<std::pair<unsigned int, unsigned int>> &pairs,
      const SharedVertices                                shared) const
    {
      pairs.clear();
      if (nodes.empty() || other.nodes.empty() ||
          !overlap(nodes[0].box, other.nodes[0].box))
        return;
      const bool skip_shared = (shared == SharedVertices::excluded);
      // Simultaneous descent: a pair of nodes (a of this tree, b of other's)
      // is only visited if their boxes overlap; the larger one is split.
      const auto visit =
        [&](const NodePair                                     &ab,
            std::vector<NodePair>                              &next,
            std::vector<std::pair<unsigned int, unsigned int>> &found,
            bool /*prune: nothing to prune between two trees*/) {
          const auto [a, b] = ab;
          const Node &A = nodes[a], &B = other.nodes[b];
          const bool  a_leaf = A.first_child == 0, b_leaf = B.first_child == 0;
          if (a_leaf && b_leaf)
            {
              for (unsigned int i = A.begin; i < A.end; ++i)
                if (overlap(ordered_boxes[i], B.box))
                  for (unsigned int j = B.begin; j < B.end; ++j)
                    if (overlap(ordered_boxes[i], other.ordered_boxes[j]) &
                        !(skip_shared &
                          share_index(ordered_triangles[i],
                                      other.ordered_triangles[j])))
                      found.emplace_back(order[i], other.order[j]);
            }
          else if (b_leaf || (!a_leaf && A.end - A.begin >= B.end - B.begin))
            {
              for (const unsigned int c : {A.first_child, A.first_child + 1})
                if (overlap(nodes[c].box, B.box))
                  next.emplace_back(c, b);
            }
          else
            {
              for (const unsigned int c : {B.first_child, B.first_child + 1})
                if (overlap(A.box, other.nodes[c].box))
                  next.emplace_back(a, c);
            }
        };
      descend({0, 0}, visit, pairs);
    }
  } // namespace contact
} // namespace estep
