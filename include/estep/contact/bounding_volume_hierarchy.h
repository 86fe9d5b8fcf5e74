#ifndef estep_contact_bounding_volume_hierarchy_h
#define estep_contact_bounding_volume_hierarchy_h

#include <estep/contact/geometry.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace estep
{
  namespace contact
  {
    /** An axis-aligned box [lower, upper] (closed). */
    struct BoundingBox
    {
      std::array<double, 3> lower;
      std::array<double, 3> upper;

      /** The empty box (lower above upper), which adding points grows. */
      static BoundingBox
      empty()
      {
        constexpr double inf = std::numeric_limits<double>::infinity();
        return {{{inf, inf, inf}}, {{-inf, -inf, -inf}}};
      }

      /** Grow the box to hold @p p. */
      void
      add(const Point3 &p)
      {
        for (unsigned int k = 0; k < 3; ++k)
          {
            lower[k] = std::min(lower[k], p[k]);
            upper[k] = std::max(upper[k], p[k]);
          }
      }

      /** Whether the closed box holds @p p. */
      bool
      contains(const Point3 &p) const
      {
        return lower[0] <= p[0] && p[0] <= upper[0] && lower[1] <= p[1] &&
               p[1] <= upper[1] && lower[2] <= p[2] && p[2] <= upper[2];
      }

      /** Whether the closed boxes share a point. */
      bool
      overlaps(const BoundingBox &other) const
      {
        return lower[0] <= other.upper[0] && other.lower[0] <= upper[0] &&
               lower[1] <= other.upper[1] && other.lower[1] <= upper[1] &&
               lower[2] <= other.upper[2] && other.lower[2] <= upper[2];
      }
    };

    /**
     * Whether a query skips pairs of triangles that share a vertex index.
     */
    enum class SharedVertices
    {
      /** Skip them: both triangle sets index one coordinate vector, and a
       * shared index means neighbours on a surface. */
      excluded,
      /** Keep them: the triangle sets index different coordinate vectors, so
       * equal indices mean nothing. */
      included
    };

    /**
     * Broad phase over the triangles of a surface: a bounding volume hierarchy
     * (binary tree of axis-aligned boxes, at most eight triangles per leaf)
     * that finds all pairs of triangles whose boxes overlap, except pairs that
     * share a vertex (neighbours on the surface) and pairs within one
     * exclusion group (e.g. two triangles of one body, where there is no
     * self-contact), within one surface (find_pairs()) or between two
     * surfaces (find_pairs(other, ...)).
     *
     * Exclusion groups prune the self query: a subtree whose triangles all
     * lie in one group is not descended against itself, nor two such
     * subtrees of the same group against each other. Without that, the query
     * over several bodies would visit every pair of neighbouring triangles
     * within each body, only for them to be discarded. They also spare the
     * boxes of a group that is alone: where groups are bodies, on a refit, a
     * group whose box (computed from its points, as a triangle's) meets no
     * other group's box can have no pair, and its triangles get empty boxes,
     * which the descent never enters; the pairs found, and their order, are
     * those without this. A group's box costs a pass over its points, so this
     * is done for groups of 16 triangles or more on average.
     *
     * Construction: the triangles are sorted by the Morton code (bit
     * interleaving of the quantised coordinates, 21 bits per axis) of their
     * box centres, and each node's range of that order is split where the
     * codes' highest differing bit changes, that is at the midplane of the
     * node's octree cell (in the middle where all codes agree). The radix
     * sort is linear and each split one binary search; on 2e5 triangles this
     * was about 3 times cheaper than median splits. The boxes are the exact
     * unions of the triangles' boxes, so the choice of splits affects speed,
     * never the result.
     *
     * Coordinates: q is point-major, point i at q[3i], q[3i + 1], q[3i + 2].
     * Boxes are computed from the vertex coordinates (min and max are exact)
     * and then enlarged by a user margin; coordinates computed by the class
     * (the end of a free flight, q + s v) are rounded outward, so a box always
     * holds the exact geometric object. The tree's topology is built once
     * (build()) and its boxes updated as the mesh moves (refit(), linear cost);
     * rebuild when the motion has been large, since refitted boxes grow loose.
     *
     * Not thread-safe for concurrent updates; queries on a fixed tree are
     * const.
     */
    class BoundingVolumeHierarchy
    {
    public:
      /**
       * @p triangles are vertex-index triples; every index must be below
       * n_points of the coordinate vectors passed later (checked there,
       * std::invalid_argument otherwise).
       */
      explicit BoundingVolumeHierarchy(
        std::vector<TriangleIndices> triangles        = {},
        std::vector<unsigned int>    exclusion_groups = {});

      /**
       * One group per triangle (or none: empty): the self query find_pairs()
       * then skips the pairs of two triangles of one group (the query between
       * two hierarchies does not look at groups). The tree must be built
       * (again) after this call. Throws std::invalid_argument if the size is
       * neither 0 nor the number of triangles.
       */
      void
      set_exclusion_groups(std::vector<unsigned int> groups);

      /** Build the tree for the configuration q (size n) with boxes enlarged by
       * margin. */
      void
      build(const double *q, const std::size_t n, const double margin = 0.);

      /**
       * Build the tree for a free flight: each triangle's box holds the
       * triangle at every q + s v with 0 <= s <= s_max (the box of its
       * positions at s = 0 and s = s_max, since points move on straight lines),
       * enlarged by margin.
       */
      void
      build_swept(const double     *q,
                  const double     *v,
                  const std::size_t n,
                  const double      s_max,
                  const double      margin = 0.);

      /** Recompute the boxes for a new configuration, keeping the tree (same as
       * build's); build it if it is not built, or if the rebuild interval
       * says so. */
      void
      refit(const double *q, const std::size_t n, const double margin = 0.);

      /** Recompute the boxes for a new free flight, keeping the tree; build
       * it as refit() does. */
      void
      refit_swept(const double     *q,
                  const double     *v,
                  const std::size_t n,
                  const double      s_max,
                  const double      margin = 0.);

      /**
       * Let every @p interval-th refit since the tree was built build it
       * anew (0, the default: never). Refitted boxes grow loose as the
       * surface moves and turns away from the configuration the tree was
       * built for. The topology changes the speed and the order of the pairs
       * found, never the pairs.
       */
      void
      set_rebuild_interval(const unsigned int interval)
      {
        rebuild_interval = interval;
      }

      /**
       * All pairs (i, j), i < j, of triangle numbers whose boxes overlap,
       * which share no vertex index and lie in different exclusion groups.
       * Replaces the content of @p pairs; their order depends on the tree
       * alone, not on the number of threads (the descent splits into tasks at
       * a fixed frontier), nor on the groups: it is the order of the query
       * without groups, with the pairs within a group left out.
       */
      void
      find_pairs(
        std::vector<std::pair<unsigned int, unsigned int>> &pairs) const;

      /**
       * All pairs (i, j) of a triangle number i of this hierarchy and a
       * triangle number j of @p other whose boxes overlap (body versus body:
       * the two trees are descended simultaneously, so the cost follows the
       * region where the bodies are close, not their size). With
       * SharedVertices::excluded (both hierarchies index one coordinate
       * vector) pairs sharing a vertex index are skipped as in find_pairs();
       * with SharedVertices::included (each body has its own coordinate
       * vector) they are kept. Both hierarchies must be built (with the
       * boxes, margins and sweeps wanted; boxes are compared as they are).
       * Replaces the content of @p pairs; their order depends on the trees
       * alone, as in find_pairs(). @p other
       * may be this hierarchy: then every unordered overlapping pair is found
       * in both orders, plus (i, i) if shared vertices are included.
       */
      void
      find_pairs(const BoundingVolumeHierarchy                      &other,
                 std::vector<std::pair<unsigned int, unsigned int>> &pairs,
                 const SharedVertices shared = SharedVertices::excluded) const;

      /** Whether build() or build_swept() has been called. */
      bool
      is_built() const
      {
        return !nodes.empty() || triangles.empty();
      }

      /** Number of triangles. */
      std::size_t
      n_triangles() const
      {
        return triangles.size();
      }

      /** The triangles as passed to the constructor. */
      const std::vector<TriangleIndices> &
      get_triangles() const
      {
        return triangles;
      }

      /** The points the triangles use, in increasing order. */
      const std::vector<unsigned int> &
      vertices() const
      {
        return triangle_vertices;
      }

      /** The largest |x_i| over the coordinates of vertices() in the
       * point-major @p x (0 without triangles): the scale of the round-off
       * of positions and velocities that reach the triangles. */
      double
      largest_vertex_coordinate(const double *x) const;

      /** The exclusion groups as last set (empty: none). */
      const std::vector<unsigned int> &
      get_exclusion_groups() const
      {
        return groups;
      }

      /** Box of triangle i as last computed (empty, lower above upper, for
       * a triangle of a group alone after a refit). */
      const BoundingBox &
      triangle_box(const unsigned int i) const
      {
        return boxes[i];
      }

    private:
      struct Node
      {
        BoundingBox box;
        // Leaf: triangles order[begin, end), first_child = 0. Inner: children
        // first_child and first_child + 1 (never 0, the root).
        unsigned int begin, end, first_child;
        // The exclusion group of all its triangles, or mixed_groups.
        unsigned int group;
      };

      /** Node::group of a node whose triangles lie in several groups. */
      static constexpr unsigned int mixed_groups = ~0u;

      /** The boxes of the triangles for the configuration q, swept over
       * q + s v, 0 <= s <= s_max, if v is given, and enlarged by margin;
       * with @p skip_isolated_groups, empty boxes for the triangles of the
       * groups that isolated_groups() finds, kept in isolated. */
      void
      compute_boxes(const double     *q,
                    const double     *v,
                    const std::size_t n,
                    const double      s_max,
                    const double      margin,
                    const bool        skip_isolated_groups);

      /** Whether each group's box, computed from its points as a
       * triangle's box is, meets no other group's box; empty if groups this
       * small would not pay (see the class's documentation). */
      std::vector<bool>
      isolated_groups(const double *q,
                      const double *v,
                      const double  s_max,
                      const double  margin) const;

      void
      sort_by_morton_code();

      void
      build_tree();

      /** Counts a refit; whether it is the rebuild interval's. */
      bool
      rebuild_due();

      void
      refit_tree();

      std::vector<TriangleIndices> triangles;
      std::vector<unsigned int>    triangle_vertices;
      unsigned int                 max_index;
      std::vector<BoundingBox>     boxes;
      std::vector<unsigned int>    order;
      std::vector<Node>            nodes;
      std::vector<BoundingBox>     ordered_boxes;
      std::vector<TriangleIndices> ordered_triangles;
      /** The exclusion group of each triangle (empty: none), and in tree
       * order (each triangle its own group when there are none). */
      std::vector<unsigned int> groups, ordered_groups;
      /** Lists the points of each group (on the first refit, so that a
       * hierarchy that is only built, once per flight, never pays for it),
       * where groups have 16 triangles or more on average. */
      void
      index_group_points();

      /** The points of the triangles of group g:
       * group_points[group_point_start[g], group_point_start[g + 1]); empty
       * where isolated_groups() would not pay. */
      std::vector<unsigned int> group_point_start, group_points;
      /** Whether index_group_points() has run since the groups were set. */
      bool group_points_indexed = false;
      /** The groups alone at the last computation of the boxes (empty: none
       * looked for). */
      std::vector<bool> isolated;
      /** See set_rebuild_interval(); the refits since the last build. */
      unsigned int rebuild_interval = 0, refits_since_build = 0;
      // Scratch of the construction (kept to avoid reallocation on rebuild):
      // Morton codes in tree order and the radix sort's buffers.
      std::vector<std::uint64_t> codes, code_buffer;
      std::vector<unsigned int>  order_buffer;
    };

    /**
     * The pairs (a, b), a < b, of the closed boxes that overlap, in no
     * particular order, by a sweep along x: the boxes in the order of their
     * lower ends, each compared only with those that start before it ends.
     * For few boxes, such as one per body.
     */
    std::vector<std::pair<unsigned int, unsigned int>>
    overlapping_pairs(const std::vector<BoundingBox> &boxes);

    /** Whether two triangles share a vertex index. */
    inline bool
    share_vertex(const TriangleIndices &a, const TriangleIndices &b)
    {
      for (const unsigned int i : a)
        if (i == b[0] || i == b[1] || i == b[2])
          return true;
      return false;
    }
  } // namespace contact
} // namespace estep

#endif
