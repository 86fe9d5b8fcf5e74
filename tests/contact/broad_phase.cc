// Broad phase: the hierarchy finds exactly the overlapping, non-adjacent pairs
// (static, refitted and swept), and the deal.II adapter extracts a closed,
// outward-oriented surface.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <estep/contact/boundary_triangles.h>
#include <estep/contact/bounding_volume_hierarchy.h>
#include <estep/contact/triangle_intersection.h>

#include <gtest/gtest.h>

#include "test_meshes.h"

#include <algorithm>
#include <map>
#include <random>
#include <set>

using namespace estep::contact;
using Pairs = std::vector<std::pair<unsigned int, unsigned int>>;

namespace
{
  Pairs
  brute_force(const BoundingVolumeHierarchy &bvh)
  {
    Pairs       pairs;
    const auto &t = bvh.get_triangles();
    for (unsigned int i = 0; i < t.size(); ++i)
      for (unsigned int j = i + 1; j < t.size(); ++j)
        if (bvh.triangle_box(i).overlaps(bvh.triangle_box(j)) &&
            !share_vertex(t[i], t[j]))
          pairs.emplace_back(i, j);
    return pairs;
  }

  Pairs
  sorted(Pairs p)
  {
    std::sort(p.begin(), p.end());
    return p;
  }

  /** A soup of small random triangles sharing some vertices. */
  void
  soup(std::mt19937_64              &rng,
       std::vector<double>          &q,
       std::vector<TriangleIndices> &tris)
  {
    std::uniform_real_distribution<double> u(0., 1.), s(-0.05, 0.05);
    std::uniform_int_distribution<int>     pick(0, 399);
    for (unsigned int i = 0; i < 400; ++i)
      {
        const double c[3] = {u(rng), u(rng), u(rng)};
        for (unsigned int v = 0; v < 3; ++v)
          for (unsigned int k = 0; k < 3; ++k)
            q.push_back(c[k] + s(rng));
      }
    for (unsigned int i = 0; i < 400; ++i)
      {
        TriangleIndices t = {{3 * i, 3 * i + 1, 3 * i + 2}};
        if (i % 4 == 0)
          t[0] = 3 * pick(rng) + 1; // shared with another triangle
        if (t[0] != t[1] && t[0] != t[2])
          tris.push_back(t);
      }
  }
} // namespace

TEST(BroadPhase, FindsExactlyTheOverlappingNonAdjacentPairs)
{
  std::mt19937_64              rng(41);
  std::vector<double>          q;
  std::vector<TriangleIndices> tris;
  soup(rng, q, tris);
  BoundingVolumeHierarchy bvh(tris);
  bvh.build(q.data(), q.size());
  Pairs found;
  bvh.find_pairs(found);
  EXPECT_GT(found.size(), 50u);
  EXPECT_EQ(sorted(found), sorted(brute_force(bvh)));

  // Move everything and refit: still exact.
  std::normal_distribution<double> d(0., 0.05);
  for (double &x : q)
    x += d(rng);
  bvh.refit(q.data(), q.size());
  bvh.find_pairs(found);
  EXPECT_EQ(sorted(found), sorted(brute_force(bvh)));

  // Margin enlarges the boxes.
  bvh.refit(q.data(), q.size(), 0.02);
  Pairs with_margin;
  bvh.find_pairs(with_margin);
  EXPECT_GT(with_margin.size(), found.size());
  EXPECT_EQ(sorted(with_margin), sorted(brute_force(bvh)));
}

TEST(BroadPhase, SweptBoxesHoldEveryIntersectionOfTheFlight)
{
  std::mt19937_64              rng(42);
  std::vector<double>          q;
  std::vector<TriangleIndices> tris;
  soup(rng, q, tris);
  std::normal_distribution<double> d(0., 0.3);
  std::vector<double>              v(q.size());
  for (double &x : v)
    x = d(rng);
  const double            s_max = 0.5;
  BoundingVolumeHierarchy swept(tris);
  swept.build_swept(q.data(), v.data(), q.size(), s_max);
  Pairs candidates;
  swept.find_pairs(candidates);
  EXPECT_EQ(sorted(candidates), sorted(brute_force(swept)));
  const std::set<std::pair<unsigned int, unsigned int>> set(candidates.begin(),
                                                            candidates.end());
  unsigned int                                          n_intersections = 0;
  for (unsigned int step = 0; step <= 10; ++step)
    {
      const double s = s_max * step / 10.;
      const auto   X = [&](const TriangleIndices &t) {
        Triangle3 T;
        for (unsigned int a = 0; a < 3; ++a)
          for (unsigned int k = 0; k < 3; ++k)
            T[a][k] = q[3 * t[a] + k] + s * v[3 * t[a] + k];
        return T;
      };
      for (unsigned int i = 0; i < tris.size(); ++i)
        for (unsigned int j = i + 1; j < tris.size(); ++j)
          if (!share_vertex(tris[i], tris[j]) &&
              triangles_intersect(X(tris[i]), X(tris[j])))
            {
              ++n_intersections;
              EXPECT_TRUE(set.count({i, j})) << i << " " << j << " s = " << s;
            }
    }
  EXPECT_GT(n_intersections, 10u);
}

TEST(BroadPhase, BadInputThrows)
{
  BoundingVolumeHierarchy bvh(std::vector<TriangleIndices>{{{0, 1, 7}}});
  std::vector<double>     q(9, 0.);
  EXPECT_THROW(bvh.build(q.data(), q.size()), std::invalid_argument);
}

TEST(BoundaryTriangles, ClosedOutwardSurfaceOfSimplexCube)
{
  dealii::Triangulation<3> tria;
  dealii::GridGenerator::subdivided_hyper_cube_with_simplices(tria, 2, 0., 2.);
  const std::vector<TriangleIndices> tris = boundary_triangles(tria);
  EXPECT_EQ(tris.size(), 6u * 4u * 2u);
  // Divergence theorem: sum of centroid . area-normal / 3 is the volume 8.
  double                                               volume = 0.;
  std::map<std::pair<unsigned int, unsigned int>, int> edge_use;
  for (const auto &t : tris)
    {
      dealii::Point<3> p[3];
      for (unsigned int a = 0; a < 3; ++a)
        p[a] = tria.get_vertices()[t[a]];
      const dealii::Tensor<1, 3> n =
        dealii::cross_product_3d(p[1] - p[0], p[2] - p[0]) / 2.;
      volume += ((p[0] + p[1] + p[2]) / 3.) * n / 3.;
      for (unsigned int a = 0; a < 3; ++a)
        ++edge_use[{t[a], t[(a + 1) % 3]}];
    }
  EXPECT_NEAR(volume, 8., 1e-12);
  // Closed and consistently oriented: every directed edge once, its reverse
  // once.
  for (const auto &[e, n] : edge_use)
    {
      EXPECT_EQ(n, 1);
      EXPECT_EQ(edge_use.count({e.second, e.first}), 1u);
    }
  dealii::Triangulation<3> hex;
  dealii::GridGenerator::hyper_cube(hex);
  EXPECT_THROW(boundary_triangles(hex), std::invalid_argument);
}
