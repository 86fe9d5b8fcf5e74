#ifndef estep_tests_contact_cgal_oracle_h
#define estep_tests_contact_cgal_oracle_h

// CGAL as the oracle of the contact tests (never used by the library).

#include <estep/contact/triangle_intersection.h>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <cstdlib>
#include <random>
#include <string>

namespace estep_test
{
  using Kernel    = CGAL::Exact_predicates_exact_constructions_kernel;
  using CPoint    = Kernel::Point_3;
  using CSegment  = Kernel::Segment_3;
  using CTriangle = Kernel::Triangle_3;

  inline CPoint
  to_cgal(const estep::contact::Point3 &p)
  {
    return CPoint(p[0], p[1], p[2]);
  }

  inline CTriangle
  to_cgal(const estep::contact::Triangle3 &T)
  {
    return CTriangle(to_cgal(T[0]), to_cgal(T[1]), to_cgal(T[2]));
  }

  inline estep::contact::Point3
  to_double(const CPoint &p)
  {
    // Through the exact value: to_double() of a lazy number may return its
    // interval's midpoint.
    return {{CGAL::to_double(CGAL::exact(p.x())),
             CGAL::to_double(CGAL::exact(p.y())),
             CGAL::to_double(CGAL::exact(p.z()))}};
  }

  /** Problem sizes: small in the unit tier, full size in the long tier. */
  inline unsigned int
  size(const unsigned int unit, const unsigned int long_run)
  {
#ifdef ESTEP_CONTACT_LONG
    (void)unit;
    return long_run;
#else
    (void)long_run;
    return unit;
#endif
  }
} // namespace estep_test

#endif
