#ifndef estep_contact_first_contact_h
#define estep_contact_first_contact_h

#include <estep/contact/bounding_volume_hierarchy.h>
#include <estep/contact/continuous_collision.h>
#include <estep/contact/geometry.h>

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace estep
{
  namespace contact
  {
    /**
     * The first contact of two boundary primitives along a free flight, and
     * the gradient of their contact distance (the reflection normal).
     */
    struct FirstContact
    {
      /** Flight parameter of the contact (never later than the exact first
       * contact of the primitives). */
      double s = 0.;
      /** true: edge-edge (a0, a1, b0, b1); false: vertex-face (p, f0, f1, f2).
       */
      bool edge_edge = false;
      /** The four point indices. */
      std::array<unsigned int, 4> points = {{0, 0, 0, 0}};
      /**
       * The gradient of the contact distance with respect to point k is
       * weights[k] * normal. Vertex-face: (1, -w0, -w1, -w2) with w the
       * barycentric coordinates of the orthogonal projection of p on the face
       * plane; edge-edge: (1 - a, a, -(1 - b), -b) with a, b the parameters of
       * the closest points of the two lines, or of the two edges where the
       * lines' lie beyond an edge's end (the normal then along the difference
       * of those points, unless it is within round-off). The weights sum to
       * zero (no net force) and the lever arms are parallel to the normal (no
       * net torque).
       */
      std::array<double, 4> weights = {{0., 0., 0., 0.}};
      /** Unit normal, oriented so that the distance grows when the first
       * primitive moves along it. */
      Point3 normal = {{0., 0., 0.}};
    };

    /**
     * The earliest vertex-face or edge-edge contact along the flight q + s v,
     * 0 <= s <= s_max, between the surface triangles @p triangles (point
     * indices into q; pairs that share a vertex, and pairs in the same
     * exclusion group if @p groups is not empty, never touch).
     *
     * Candidate triangle pairs come from boxes swept over the flight; each
     * candidate yields 6 vertex-face and 9 edge-edge queries (duplicates
     * removed) for the conservative CCD (vertex_face_ccd(), edge_edge_ccd()),
     * whose times are never later than the exact contact times.
     *
     * Contacts at the start (the rule that avoids sticking and zero-length
     * steps right after a reflection): a primitive pair whose distance at s =
     * 0 is at most 2 sqrt(3) tolerance (along the normal, with the closest
     * points on the primitives themselves, not beyond an edge's end or a
     * face's boundary) and whose parting rate is positive is separating; it
     * is ignored on [0, s1] with s1 = 8 tolerance / rate and examined by the
     * CCD on [s1, s_max]. The parting rate is the distance rate (gradient .
     * v) with the sign of the pair's side, the sign of its distance: the
     * orientation of the normal, taken from one pair of faces, can be wrong
     * at an edge of two faces, and decides only a distance within round-off.
     * A pair that touches at s = 0 and approaches (parting rate negative) is
     * reported at s = 0 (several simultaneous contacts are then resolved one
     * by one). A rate within 64 units of round-off of sum_k |weights[k]
     * normal_i v_k,i| is neither: the pair is held and ignored for the flight
     * (no reflection could change a rate below the last bits of the
     * velocities).
     *
     * Returns nothing if no contact occurs on [0, s_max].
     */
    std::optional<FirstContact>
    find_first_contact(const std::vector<TriangleIndices> &triangles,
                       const std::vector<unsigned int>    &groups,
                       const double                       *q,
                       const double                       *v,
                       const std::size_t                   n,
                       const double                        s_max,
                       const CcdSettings &settings = CcdSettings());

    /**
     * The same, for the triangles and exclusion groups of @p tree, whose
     * topology is kept: its boxes are refitted to the flight (it is built if
     * it never was). Flight after flight this saves the tree's construction;
     * the result is that of a tree built for the flight, since the candidate
     * pairs are the same and their order does not matter. Refitted boxes
     * grow loose as the surface moves away from the configuration the tree
     * was built for: give the tree a rebuild interval
     * (BoundingVolumeHierarchy::set_rebuild_interval()).
     */
    std::optional<FirstContact>
    find_first_contact(BoundingVolumeHierarchy &tree,
                       const double            *q,
                       const double            *v,
                       const std::size_t        n,
                       const double             s_max,
                       const CcdSettings       &settings = CcdSettings());

    /**
     * Every primitive pair of @p tree's triangles touching at q (the rule of
     * find_first_contact(): a distance of at most 2 sqrt(3) tolerance along
     * the normal, the closest points on the primitives), whatever its
     * velocity: the contacts that may hold each other at this instant, every
     * pair that find_first_contact() may report at s = 0 among them (the
     * boxes of its broad phase are enlarged by the touching distance, not
     * the tolerance). Each
     * normal is turned to the side the pair lies on, so that the pair parts
     * when its points move with a positive rate sum_k weights[k] normal .
     * v_k. The tree's boxes are refitted to q.
     */
    std::vector<FirstContact>
    touching_contacts(BoundingVolumeHierarchy &tree,
                      const double            *q,
                      const std::size_t        n,
                      const CcdSettings       &settings = CcdSettings());

    /**
     * The contact normal and weights (see FirstContact) of the primitive pair
     * @p points at the positions @p x (point i at x[3 i]); @p edge_edge
     * selects the kind. @p orientation is a direction the normal should have
     * a positive component along (e.g. the outward normal of the face, or the
     * difference of the outward normals); the result has s = 0.
     */
    FirstContact
    contact_normal(const std::array<unsigned int, 4> &points,
                   const bool                         edge_edge,
                   const double                      *x,
                   const Point3                      &orientation);
  } // namespace contact
} // namespace estep

#endif
