#include <estep/contact/bounding_volume_hierarchy.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace estep
{
  namespace contact
  {
    namespace
    {
      constexpr unsigned int leaf_size = 4;

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
      std::vector<TriangleIndices> triangles_in)
      : triangles(std::move(triangles_in))
      , max_index(0)
    {
      for (const auto &t : triangles)
        for (const unsigned int i : t)
          max_index = std::max(max_index, i);
    }



    void
    BoundingVolumeHierarchy::compute_boxes(const double     *q,
                                           const double     *v,
                                           const std::size_t n,
                                           const double      s_max,
                                           const double      margin)
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
      for (std::size_t t = 0; t < triangles.size(); ++t)
        {
          BoundingBox &b = boxes[t];
          for (unsigned int k = 0; k < 3; ++k)
            {
              b.lower[k] = std::numeric_limits<double>::infinity();
              b.upper[k] = -std::numeric_limits<double>::infinity();
            }
          for (const unsigned int i : triangles[t])
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
          if (margin > 0.)
            for (unsigned int k = 0; k < 3; ++k)
              {
                b.lower[k] = round_down(b.lower[k] - margin);
                b.upper[k] = round_up(b.upper[k] + margin);
              }
        }
    }



    void
    BoundingVolumeHierarchy::build_tree()
    {
      const std::size_t n = triangles.size();
      order.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        order[i] = i;
      nodes.clear();
      if (n == 0)
        return;
      nodes.reserve(2 * (n / leaf_size + 1) + 1);
      std::vector<double> centre(3 * n);
      for (std::size_t i = 0; i < n; ++i)
        for (unsigned int k = 0; k < 3; ++k)
          centre[3 * i + k] = 0.5 * boxes[i].lower[k] + 0.5 * boxes[i].upper[k];

      nodes.push_back(Node{BoundingBox(), 0, static_cast<unsigned int>(n), 0});
      std::vector<unsigned int> stack = {0};
      while (!stack.empty())
        {
          const unsigned int node = stack.back();
          stack.pop_back();
          const unsigned int begin = nodes[node].begin, end = nodes[node].end;
          if (end - begin <= leaf_size)
            continue;
          double lo[3], hi[3];
          for (unsigned int k = 0; k < 3; ++k)
            {
              lo[k] = std::numeric_limits<double>::infinity();
              hi[k] = -lo[k];
            }
          for (unsigned int i = begin; i < end; ++i)
            for (unsigned int k = 0; k < 3; ++k)
              {
                lo[k] = std::min(lo[k], centre[3 * order[i] + k]);
                hi[k] = std::max(hi[k], centre[3 * order[i] + k]);
              }
          unsigned int axis = 0;
          for (unsigned int k = 1; k < 3; ++k)
            if (hi[k] - lo[k] > hi[axis] - lo[axis])
              axis = k;
          const unsigned int mid = begin + (end - begin) / 2;
          std::nth_element(order.begin() + begin,
                           order.begin() + mid,
                           order.begin() + end,
                           [&](const unsigned int a, const unsigned int b) {
                             return centre[3 * a + axis] < centre[3 * b + axis];
                           });
          const unsigned int child = nodes.size();
          nodes[node].first_child  = child;
          nodes.push_back(Node{BoundingBox(), begin, mid, 0});
          nodes.push_back(Node{BoundingBox(), mid, end, 0});
          stack.push_back(child);
          stack.push_back(child + 1);
        }
      ordered_triangles.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        ordered_triangles[i] = triangles[order[i]];
      refit_tree();
    }



    void
    BoundingVolumeHierarchy::refit_tree()
    {
      // Boxes and triangles in tree order, for cache-friendly leaf tests.
      ordered_boxes.resize(order.size());
      for (std::size_t i = 0; i < order.size(); ++i)
        ordered_boxes[i] = boxes[order[i]];
      // Children come after their parent: a backward sweep visits children
      // first.
      for (std::size_t j = nodes.size(); j-- > 0;)
        {
          Node &node = nodes[j];
          if (node.first_child == 0)
            {
              node.box = ordered_boxes[node.begin];
              for (unsigned int i = node.begin + 1; i < node.end; ++i)
                unite(node.box, ordered_boxes[i]);
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
      compute_boxes(q, nullptr, n, 0., margin);
      build_tree();
    }



    void
    BoundingVolumeHierarchy::build_swept(const double     *q,
                                         const double     *v,
                                         const std::size_t n,
                                         const double      s_max,
                                         const double      margin)
    {
      compute_boxes(q, v, n, s_max, margin);
      build_tree();
    }



    void
    BoundingVolumeHierarchy::refit(const double     *q,
                                   const std::size_t n,
                                   const double      margin)
    {
      if (!is_built())
        return build(q, n, margin);
      compute_boxes(q, nullptr, n, 0., margin);
      refit_tree();
    }



    void
    BoundingVolumeHierarchy::refit_swept(const double     *q,
                                         const double     *v,
                                         const std::size_t n,
                                         const double      s_max,
                                         const double      margin)
    {
      if (!is_built())
        return build_swept(q, v, n, s_max, margin);
      compute_boxes(q, v, n, s_max, margin);
      refit_tree();
    }



    void
    BoundingVolumeHierarchy::find_pairs(
      std::vector<std::pair<unsigned int, unsigned int>> &pairs) const
    {
      pairs.clear();
      if (nodes.empty())
        return;
      // a, b: positions in tree order.
      const auto test = [&](const unsigned int a, const unsigned int b) {
        if (ordered_boxes[a].overlaps(ordered_boxes[b]) &&
            !share_vertex(ordered_triangles[a], ordered_triangles[b]))
          pairs.emplace_back(std::min(order[a], order[b]),
                             std::max(order[a], order[b]));
      };
      std::vector<std::pair<unsigned int, unsigned int>> stack;
      stack.reserve(128);
      stack.emplace_back(0, 0);
      while (!stack.empty())
        {
          const auto [a, b] = stack.back();
          stack.pop_back();
          const Node &A = nodes[a], &B = nodes[b];
          if (a == b)
            {
              if (A.first_child == 0)
                {
                  for (unsigned int i = A.begin; i < A.end; ++i)
                    for (unsigned int j = i + 1; j < A.end; ++j)
                      test(i, j);
                }
              else
                {
                  stack.emplace_back(A.first_child, A.first_child);
                  stack.emplace_back(A.first_child + 1, A.first_child + 1);
                  stack.emplace_back(A.first_child, A.first_child + 1);
                }
              continue;
            }
          if (!A.box.overlaps(B.box))
            continue;
          const bool a_leaf = A.first_child == 0, b_leaf = B.first_child == 0;
          if (a_leaf && b_leaf)
            {
              for (unsigned int i = A.begin; i < A.end; ++i)
                if (ordered_boxes[i].overlaps(B.box))
                  for (unsigned int j = B.begin; j < B.end; ++j)
                    test(i, j);
            }
          else if (b_leaf || (!a_leaf && A.end - A.begin >= B.end - B.begin))
            {
              stack.emplace_back(A.first_child, b);
              stack.emplace_back(A.first_child + 1, b);
            }
          else
            {
              stack.emplace_back(a, B.first_child);
              stack.emplace_back(a, B.first_child + 1);
            }
        }
    }
  } // namespace contact
} // namespace estep
