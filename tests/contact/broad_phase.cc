// Broad phase: the hierarchy finds exactly the overlapping, non-adjacent pairs
// within one surface and between two surfaces (static, refitted, with margin
// and swept), also on structured meshes and degenerate inputs.


#include <estep/base/parallel_blocks.h>
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

  /** Brute force between two hierarchies: (i of a, j of b). */
  Pairs
  brute_force(const BoundingVolumeHierarchy &a,
              const BoundingVolumeHierarchy &b,
              const SharedVertices           shared)
  {
    Pairs       pairs;
    const auto &s = a.get_triangles(), &t = b.get_triangles();
    for (unsigned int i = 0; i < s.size(); ++i)
      for (unsigned int j = 0; j < t.size(); ++j)
        if (a.triangle_box(i).overlaps(b.triangle_box(j)) &&
            !(shared == SharedVertices::excluded && share_vertex(s[i], t[j])))
          pairs.emplace_back(i, j);
    return pairs;
  }

  Pairs
  sorted(Pairs p)
  {
    std::sort(p.begin(), p.end());
    return p;
  }

  /** Two touching unit spheres of 2 n (n - 1) triangles each, indexing q. */
  struct TouchingSpheres
  {
    std::vector<double>          q;
    std::vector<TriangleIndices> first, second, both;
    explicit TouchingSpheres(const unsigned int n)
    {
      estep_test::add_sphere(q, first, 0., 0., 0., 1., n, n);
      estep_test::add_sphere(q, second, 1.98, 0.01, 0.02, 1., n, n);
      both = first;
      both.insert(both.end(), second.begin(), second.end());
    }
  };

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

/** Two soups in one coordinate vector; some triangles of the second body
 * share a vertex with the first (as if glued), to test the exclusion. */
struct TwoBodies
{
  std::vector<double>          q;
  std::vector<TriangleIndices> first, second;
  explicit TwoBodies(std::mt19937_64 &rng)
  {
    soup(rng, q, first);
    const unsigned int  offset = q.size() / 3;
    std::vector<double> q2;
    soup(rng, q2, second);
    for (TriangleIndices &t : second)
      for (unsigned int &i : t)
        i += offset;
    // Shift the second body by half its size: the bodies overlap in part.
    for (std::size_t i = 0; i < q2.size(); ++i)
      q.push_back(q2[i] + (i % 3 == 0 ? 0.5 : 0.));
    for (unsigned int i = 0; i < std::min(first.size(), second.size()); i += 10)
      second[i][2] = first[i][0];
  }
};

TEST(BroadPhase, BodyVersusBodyFindsExactlyTheOverlappingPairs)
{
  std::mt19937_64         rng(43);
  TwoBodies               bodies(rng);
  auto                   &q = bodies.q;
  BoundingVolumeHierarchy a(bodies.first), b(bodies.second);
  a.build(q.data(), q.size());
  b.build(q.data(), q.size());
  Pairs found;
  a.find_pairs(b, found);
  EXPECT_GT(found.size(), 50u);
  EXPECT_EQ(sorted(found), sorted(brute_force(a, b, SharedVertices::excluded)));
  // The glued triangles' boxes overlap (shared vertex), so including them adds
  // pairs.
  Pairs with_shared;
  a.find_pairs(b, with_shared, SharedVertices::included);
  EXPECT_GT(with_shared.size(), found.size());
  EXPECT_EQ(sorted(with_shared),
            sorted(brute_force(a, b, SharedVertices::included)));
  // The other order gives the same pairs, swapped.
  Pairs reversed;
  b.find_pairs(a, reversed);
  for (auto &[i, j] : reversed)
    std::swap(i, j);
  EXPECT_EQ(sorted(reversed), sorted(found));

  // Refitted after a motion, and with a margin.
  std::normal_distribution<double> d(0., 0.05);
  for (double &x : q)
    x += d(rng);
  a.refit(q.data(), q.size());
  b.refit(q.data(), q.size());
  a.find_pairs(b, found);
  EXPECT_EQ(sorted(found), sorted(brute_force(a, b, SharedVertices::excluded)));
  a.refit(q.data(), q.size(), 0.02);
  b.refit(q.data(), q.size(), 0.02);
  Pairs with_margin;
  a.find_pairs(b, with_margin);
  EXPECT_GT(with_margin.size(), found.size());
  EXPECT_EQ(sorted(with_margin),
            sorted(brute_force(a, b, SharedVertices::excluded)));

  // Swept boxes of a free flight (rebuilt and refitted).
  std::vector<double> v(q.size());
  for (double &x : v)
    x = 3. * d(rng);
  for (const bool rebuild : {true, false})
    {
      if (rebuild)
        {
          a.build_swept(q.data(), v.data(), q.size(), 0.5);
          b.build_swept(q.data(), v.data(), q.size(), 0.5);
        }
      else
        {
          a.refit_swept(q.data(), v.data(), q.size(), 0.7, 0.01);
          b.refit_swept(q.data(), v.data(), q.size(), 0.7, 0.01);
        }
      Pairs swept;
      a.find_pairs(b, swept);
      EXPECT_GT(swept.size(), with_margin.size());
      EXPECT_EQ(sorted(swept),
                sorted(brute_force(a, b, SharedVertices::excluded)));
    }
}

TEST(BroadPhase, BodyVersusBodyWithSeparateCoordinateVectors)
{
  // Each body indexes its own coordinates from 0: equal indices mean nothing,
  // so shared vertices must be included to find every overlapping pair.
  std::mt19937_64              rng(44);
  std::vector<double>          q1, q2;
  std::vector<TriangleIndices> t1, t2;
  soup(rng, q1, t1);
  soup(rng, q2, t2);
  BoundingVolumeHierarchy a(t1), b(t2);
  a.build(q1.data(), q1.size());
  b.build(q2.data(), q2.size());
  Pairs found;
  a.find_pairs(b, found, SharedVertices::included);
  EXPECT_GT(found.size(), 100u);
  EXPECT_EQ(sorted(found), sorted(brute_force(a, b, SharedVertices::included)));
  EXPECT_GT(found.size(), brute_force(a, b, SharedVertices::excluded).size());
}

TEST(BroadPhase, TouchingSpheres)
{
  // Structured surfaces (the benchmark's configuration, coarser): the self
  // query and the body-versus-body query equal brute force, and the body
  // pairs are exactly the self pairs that join the two spheres.
  const TouchingSpheres   spheres(24);
  const auto             &q     = spheres.q;
  const auto             &first = spheres.first;
  BoundingVolumeHierarchy all(spheres.both), a(first), b(spheres.second);
  for (const double margin : {0., 0.01})
    {
      all.build(q.data(), q.size(), margin);
      a.build(q.data(), q.size(), margin);
      b.build(q.data(), q.size(), margin);
      Pairs self, between;
      all.find_pairs(self);
      a.find_pairs(b, between);
      EXPECT_EQ(sorted(self), sorted(brute_force(all)));
      EXPECT_EQ(sorted(between),
                sorted(brute_force(a, b, SharedVertices::excluded)));
      EXPECT_GT(between.size(), 5u);
      Pairs joining;
      for (const auto &[i, j] : self)
        if (i < first.size() && j >= first.size())
          joining.emplace_back(i, j - first.size());
      EXPECT_EQ(sorted(joining), sorted(between));
    }
}

TEST(BroadPhase, ExclusionGroupsLeaveOutExactlyThePairsWithinAGroup)
{
  // The self query with exclusion groups is the query without them, minus the
  // pairs within a group, in the same order (on 1 and 2 threads): so the
  // pruning of single-group subtrees loses no pair between groups. Groups by
  // region, with a slab in the middle where three groups mix (mixed leaves
  // and nodes), on 6,000 small triangles: enough for the descent's
  // depth-first part, where the pruning happens, to do most of the work.
  std::mt19937_64                        rng(7);
  std::uniform_real_distribution<double> u(0., 1.), s(-0.03, 0.03);
  std::vector<double>                    q;
  std::vector<TriangleIndices>           tris;
  std::vector<unsigned int>              groups;
  for (unsigned int i = 0; i < 6000; ++i)
    {
      const double c[3] = {u(rng), u(rng), u(rng)};
      for (unsigned int v = 0; v < 3; ++v)
        for (unsigned int k = 0; k < 3; ++k)
          q.push_back(c[k] + s(rng));
      tris.push_back({{3 * i, 3 * i + 1, 3 * i + 2}});
      groups.push_back(c[0] < 0.35 ? 0u :
                       c[0] > 0.65 ? 1u :
                                     static_cast<unsigned int>(rng() % 3));
    }
  BoundingVolumeHierarchy plain(tris), grouped(tris, groups);
  plain.build(q.data(), q.size());
  grouped.build(q.data(), q.size());
  Pairs all;
  plain.find_pairs(all);
  Pairs between_groups;
  for (const auto &[i, j] : all)
    if (groups[i] != groups[j])
      between_groups.emplace_back(i, j);
  ASSERT_GT(between_groups.size(), 500u);
  ASSERT_GT(all.size(), 2 * between_groups.size());
  for (const unsigned int threads : {1u, 2u})
    {
      estep::set_thread_count(threads);
      Pairs found;
      grouped.find_pairs(found);
      EXPECT_EQ(found, between_groups) << threads << " threads";
    }
  estep::set_thread_count(1);

  // Two touching spheres, a group each: the self query gives exactly the
  // pairs of the query between the two spheres' hierarchies.
  const TouchingSpheres     two(40);
  const auto               &p = two.q;
  std::vector<unsigned int> body(two.both.size(), 0u);
  std::fill(body.begin() + two.first.size(), body.end(), 1u);
  BoundingVolumeHierarchy spheres(two.both, body), a(two.first), b(two.second);
  spheres.build(p.data(), p.size());
  a.build(p.data(), p.size());
  b.build(p.data(), p.size());
  Pairs self, joining;
  spheres.find_pairs(self);
  a.find_pairs(b, joining);
  ASSERT_GT(joining.size(), 5u);
  for (auto &[i, j] : joining)
    j += two.first.size();
  EXPECT_EQ(sorted(self), sorted(joining));

  // Groups set after construction take effect at the next build; a wrong
  // number of them is refused.
  spheres.set_exclusion_groups({});
  spheres.build(p.data(), p.size());
  spheres.find_pairs(self);
  EXPECT_EQ(sorted(self), sorted(brute_force(spheres)));
  EXPECT_THROW(spheres.set_exclusion_groups({0u, 1u}), std::invalid_argument);
}

TEST(BroadPhase, GroupsAloneAreSkippedWithoutLosingAPair)
{
  // On a refit, the triangles of a group whose box meets no other group's
  // get empty boxes; the pairs found are still exactly those between groups
  // of the triangles' own boxes (a hierarchy without groups, built for the
  // same flight, gives them). Twelve spheres of 60 triangles in a row along
  // x, 1.27 apart: the first reaches the second only by its sweep; the
  // seventh, 0.77 from the sixth, meets it only within the margin.
  std::vector<double>          q;
  std::vector<TriangleIndices> tris;
  std::vector<unsigned int>    groups;
  for (unsigned int g = 0; g < 12; ++g)
    {
      const std::size_t first = tris.size();
      estep_test::add_sphere(
        q, tris, 3. * g - (g == 6 ? 0.5 : 0.), 0.1 * g, 0., 1., 6, 6);
      groups.resize(tris.size(), g);
      ASSERT_GE(tris.size() - first, 16u);
    }
  std::vector<double> v(q.size(), 0.);
  const std::size_t   first_sphere_points = q.size() / 12;
  for (std::size_t i = 0; i < first_sphere_points; i += 3)
    v[i] = 1.5;
  const auto pairs_between_groups = [&](const double margin) {
    BoundingVolumeHierarchy plain(tris);
    plain.build_swept(q.data(), v.data(), q.size(), 1., margin);
    Pairs between;
    for (const auto &[i, j] : brute_force(plain))
      if (groups[i] != groups[j])
        between.emplace_back(i, j);
    return between;
  };
  BoundingVolumeHierarchy grouped(tris, groups);
  grouped.build(q.data(), q.size());
  for (const double margin : {0., 0.45})
    {
      grouped.refit_swept(q.data(), v.data(), q.size(), 1., margin);
      const Pairs expected = pairs_between_groups(margin);
      Pairs       found;
      grouped.find_pairs(found);
      EXPECT_EQ(sorted(found), sorted(expected)) << "margin " << margin;
      EXPECT_GT(expected.size(), 0u);
      // The last sphere is alone: its boxes were not computed.
      const BoundingBox &alone = grouped.triangle_box(tris.size() - 1);
      EXPECT_GT(alone.lower[0], alone.upper[0]) << "margin " << margin;
      // Without the margin, only the sweep joins two groups.
      unsigned int by_margin = 0;
      for (const auto &[i, j] : expected)
        {
          const unsigned int joined = groups[i] + groups[j];
          EXPECT_TRUE(joined == 1u || (margin > 0. && joined == 11u))
            << groups[i] << " and " << groups[j] << ", margin " << margin;
          by_margin += (joined == 11u);
        }
      EXPECT_EQ(by_margin > 0, margin > 0.);
    }

  // Groups whose boxes only touch, at x = 1: their triangles' boxes touch
  // too, and every such pair is found.
  std::vector<double>          flat;
  std::vector<TriangleIndices> strips;
  std::vector<unsigned int>    sides;
  for (unsigned int side = 0; side < 2; ++side)
    for (unsigned int i = 0; i < 16; ++i)
      {
        const unsigned int first = flat.size() / 3;
        for (const double p : {0. + side,
                               0. + i,
                               0.,
                               1. + side,
                               0. + i,
                               0.,
                               0.5 + side,
                               i + 0.5,
                               1.})
          flat.push_back(p);
        strips.push_back({{first, first + 1, first + 2}});
        sides.push_back(side);
      }
  BoundingVolumeHierarchy touching(strips, sides);
  touching.build(flat.data(), flat.size());
  touching.refit(flat.data(), flat.size());
  Pairs found;
  touching.find_pairs(found);
  EXPECT_EQ(found.size(), 16u);
  EXPECT_EQ(sorted(found), sorted(brute_force(touching)));
}

TEST(BroadPhase, DegenerateInputs)
{
  // All triangles in one place (equal Morton codes: the tree is split in the
  // middle), a single triangle, no triangles.
  std::vector<double>          q(3 * 300);
  std::vector<TriangleIndices> tris;
  for (unsigned int i = 0; i < 100; ++i)
    {
      for (unsigned int k = 0; k < 9; ++k)
        q[9 * i + k] = (k % 3 == k / 3 ? 1. : 0.);
      tris.push_back({{3 * i, 3 * i + 1, 3 * i + 2}});
    }
  BoundingVolumeHierarchy same(tris);
  same.build(q.data(), q.size());
  Pairs found;
  same.find_pairs(found);
  EXPECT_EQ(found.size(), 100u * 99u / 2u);
  EXPECT_EQ(sorted(found), sorted(brute_force(same)));
  same.find_pairs(same, found);
  EXPECT_EQ(found.size(), 100u * 99u);

  BoundingVolumeHierarchy one(std::vector<TriangleIndices>{{{0, 1, 2}}});
  BoundingVolumeHierarchy none(std::vector<TriangleIndices>{});
  one.build(q.data(), q.size());
  none.build(q.data(), q.size());
  one.find_pairs(found);
  EXPECT_TRUE(found.empty());
  one.find_pairs(one, found, SharedVertices::included);
  EXPECT_EQ(found, (Pairs{{0, 0}}));
  one.find_pairs(none, found);
  EXPECT_TRUE(found.empty());
  none.find_pairs(one, found);
  EXPECT_TRUE(found.empty());
  none.find_pairs(found);
  EXPECT_TRUE(found.empty());
  one.find_pairs(same, found, SharedVertices::included);
  EXPECT_EQ(found.size(), 100u);
}

TEST(BroadPhase, BadInputThrows)
{
  BoundingVolumeHierarchy bvh(std::vector<TriangleIndices>{{{0, 1, 7}}});
  std::vector<double>     q(9, 0.);
  EXPECT_THROW(bvh.build(q.data(), q.size()), std::invalid_argument);
}
