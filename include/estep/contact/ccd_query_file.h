#ifndef estep_contact_ccd_query_file_h
#define estep_contact_ccd_query_file_h

#include <estep/contact/geometry.h>

#include <array>
#include <string>
#include <vector>

namespace estep
{
  namespace contact
  {
    /** One continuous collision query with its ground truth. */
    struct CcdQuery
    {
      /** true: edge-edge (a0, a1, b0, b1); false: vertex-face (p, f0, f1, f2).
       */
      bool edge_edge = false;
      /** The four points at t = 0. */
      std::array<Point3, 4> start;
      /** The four points at t = 1. */
      std::array<Point3, 4> end;
      /** Whether the primitives touch for some t in [0, 1]. */
      bool truth = false;
      /** Whether every coordinate was converted to double without rounding. */
      bool exact = true;
    };

    /**
     * Read a query file of the CCD benchmark of Wang et al. (2021): rows
     * "xnum,xden,ynum,yden,znum,zden,truth", eight rows per query (see the data
     * set's README). The kind (vertex-face or edge-edge) comes from the name of
     * a directory in the path ("vertex-face" or "edge-edge"). Coordinates
     * num/den are converted to the nearest doubles of num and den, then
     * divided; CcdQuery::exact records whether this was exact (denominator a
     * power of two, numerator representable).
     *
     * Throws std::runtime_error naming the file and the line for an unreadable
     * file, a path that names no kind, a malformed row, a zero denominator, a
     * truth value other than 0/1 or differing within a query, or a row count
     * that is not a multiple of 8.
     */
    std::vector<CcdQuery>
    read_ccd_query_file(const std::string &file_name);
  } // namespace contact
} // namespace estep

#endif
