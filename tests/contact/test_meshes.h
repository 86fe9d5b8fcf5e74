#ifndef estep_tests_contact_test_meshes_h
#define estep_tests_contact_test_meshes_h

// Small surface meshes for the contact tests.

#include <estep/contact/bounding_volume_hierarchy.h>

#include <cmath>
#include <vector>

namespace estep_test
{
  /** A closed latitude-longitude sphere: appends points to q and triangles to
   * tris. */
  inline void
  add_sphere(std::vector<double>                          &q,
             std::vector<estep::contact::TriangleIndices> &tris,
             const double                                  cx,
             const double                                  cy,
             const double                                  cz,
             const double                                  radius,
             const unsigned int                            n_lat,
             const unsigned int                            n_lon)
  {
    const double       pi    = 3.14159265358979323846;
    const unsigned int first = q.size() / 3;
    auto push = [&](const double x, const double y, const double z) {
      q.push_back(cx + radius * x);
      q.push_back(cy + radius * y);
      q.push_back(cz + radius * z);
    };
    push(0., 0., 1.);
    for (unsigned int i = 1; i < n_lat; ++i)
      for (unsigned int j = 0; j < n_lon; ++j)
        {
          const double th = pi * i / n_lat,
                       ph = 2. * pi * (j + 0.5 * (i % 2)) / n_lon;
          push(std::sin(th) * std::cos(ph),
               std::sin(th) * std::sin(ph),
               std::cos(th));
        }
    push(0., 0., -1.);
    const unsigned int south = first + 1 + (n_lat - 1) * n_lon;
    auto               ring  = [&](const unsigned int i, const unsigned int j) {
      return first + 1 + (i - 1) * n_lon + (j % n_lon);
    };
    for (unsigned int j = 0; j < n_lon; ++j)
      {
        tris.push_back({{first, ring(1, j), ring(1, j + 1)}});
        tris.push_back({{south, ring(n_lat - 1, j + 1), ring(n_lat - 1, j)}});
      }
    for (unsigned int i = 1; i + 1 < n_lat; ++i)
      for (unsigned int j = 0; j < n_lon; ++j)
        {
          tris.push_back({{ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)}});
          tris.push_back({{ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)}});
        }
  }
} // namespace estep_test

#endif
