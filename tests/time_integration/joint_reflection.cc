// The joint reflection off contacts touching at one instant: the projection's
// complementarity conditions, repeated normals, what the reflection keeps, and
// that it parts or holds every pair.
#include <estep/time_integration/joint_reflection.h>

#include <gtest/gtest.h>

#include <random>

namespace
{
  using namespace estep;

  Vector
  vector_of(const std::vector<double> &values)
  {
    Vector x(values.size());
    for (unsigned int i = 0; i < values.size(); ++i)
      x[i] = values[i];
    return x;
  }

  SparseNormal
  dense_normal(const std::vector<double> &values)
  {
    SparseNormal n;
    for (unsigned int i = 0; i < values.size(); ++i)
      if (values[i] != 0.)
        n.emplace_back(i, values[i]);
    return n;
  }

  double
  rate(const SparseNormal &n, const Vector &w)
  {
    double r = 0.;
    for (const auto &[i, value] : n)
      r += value * w[i];
    return r;
  }

  /** v - 2 (n . v) / (n . M^-1 n) M^-1 n. */
  Vector
  reflected(const Vector &v, const Vector &n, const Vector &inverse_mass)
  {
    double a = 0., m = 0.;
    for (unsigned int i = 0; i < v.size(); ++i)
      {
        a += n[i] * v[i];
        m += n[i] * inverse_mass[i] * n[i];
      }
    Vector w = v;
    for (unsigned int i = 0; i < v.size(); ++i)
      w[i] -= 2. * a / m * inverse_mass[i] * n[i];
    return w;
  }

  TEST(JointReflection, ReflectsAPointOutOfACornerAtOnce)
  {
    // A unit mass in the corner x >= 0, y >= 0, moving into both walls: the
    // projection stops it, the reflection turns it back.
    const Vector                    inverse_mass = vector_of({1., 1.});
    const Vector                    v            = vector_of({-1., -2.});
    const std::vector<SparseNormal> walls        = {dense_normal({1., 0.}),
                                                    dense_normal({0., 1.})};
    const Vector projection = parting_projection_normal(walls, v, inverse_mass);
    EXPECT_NEAR(projection[0], 1., 1e-15);
    EXPECT_NEAR(projection[1], 2., 1e-15);
    const Vector w = reflected(v,
                               joint_reflection_normal(walls, v, inverse_mass),
                               inverse_mass);
    EXPECT_NEAR(w[0], 1., 1e-15);
    EXPECT_NEAR(w[1], 2., 1e-15);
  }

  TEST(JointReflection, GivesTheProjectionOfAChainOfThreeMasses)
  {
    // Three unit masses on a line, touching, the first moving into the
    // others: the projection moves all three at 1/3; the reflection keeps
    // momentum 1 and kinetic energy 1/2, the first pair parts and the second
    // is held: (-1/3, 2/3, 2/3).
    const Vector                    inverse_mass = vector_of({1., 1., 1.});
    const Vector                    v            = vector_of({1., 0., 0.});
    const std::vector<SparseNormal> normals      = {dense_normal({-1., 1., 0.}),
                                                    dense_normal({0., -1., 1.})};
    const Vector n = parting_projection_normal(normals, v, inverse_mass);
    for (unsigned int i = 0; i < 3; ++i)
      EXPECT_NEAR(v[i] + inverse_mass[i] * n[i], 1. / 3., 1e-15) << i;
    const Vector w =
      reflected(v,
                joint_reflection_normal(normals, v, inverse_mass),
                inverse_mass);
    EXPECT_NEAR(w[0], -1. / 3., 1e-15);
    EXPECT_NEAR(w[1], 2. / 3., 1e-15);
    EXPECT_NEAR(w[2], 2. / 3., 1e-15);
  }

  TEST(JointReflection, KeepsPairsHeldWhileTheyPartedFromApproaching)
  {
    // The chain with the third mass moving away at 0.1: the projection
    // holds the second pair too (all three at 1.1/3). Its mirror image
    // makes that pair approach at 0.1; the joint reflection holds it, and
    // keeps momentum and kinetic energy.
    const Vector                    inverse_mass = vector_of({1., 1., 1.});
    const Vector                    v            = vector_of({1., 0., 0.1});
    const std::vector<SparseNormal> normals      = {dense_normal({-1., 1., 0.}),
                                                    dense_normal({0., -1., 1.})};
    const Vector                    projection =
      parting_projection_normal(normals, v, inverse_mass);
    for (unsigned int i = 0; i < 3; ++i)
      EXPECT_NEAR(v[i] + inverse_mass[i] * projection[i], 1.1 / 3., 1e-15) << i;
    EXPECT_NEAR(rate(normals[1], reflected(v, projection, inverse_mass)),
                -0.1,
                1e-15);
    const Vector w =
      reflected(v,
                joint_reflection_normal(normals, v, inverse_mass),
                inverse_mass);
    EXPECT_GT(rate(normals[0], w), 0.9);
    EXPECT_NEAR(rate(normals[1], w), 0., 1e-15);
    EXPECT_NEAR(w[0] + w[1] + w[2], 1.1, 1e-15);
    EXPECT_NEAR(w * w, v * v, 1e-15);
  }

  TEST(JointReflection, LeavesOutPairsThatPartAndGivesZeroWhenAllPart)
  {
    // The second wall parts: the projection and the reflection are off the
    // first alone, the plain reflection (1, 2).
    const Vector                    inverse_mass = vector_of({1., 1.});
    const Vector                    v            = vector_of({-1., 2.});
    const std::vector<SparseNormal> walls        = {dense_normal({1., 0.}),
                                                    dense_normal({0., 1.})};
    const Vector projection = parting_projection_normal(walls, v, inverse_mass);
    EXPECT_NEAR(projection[0], 1., 1e-15);
    EXPECT_EQ(projection[1], 0.);
    const Vector w = reflected(v,
                               joint_reflection_normal(walls, v, inverse_mass),
                               inverse_mass);
    EXPECT_NEAR(w[0], 1., 1e-15);
    EXPECT_NEAR(w[1], 2., 1e-15);
    for (const Vector &none :
         {joint_reflection_normal(walls, vector_of({1., 2.}), inverse_mass),
          parting_projection_normal(walls, vector_of({1., 2.}), inverse_mass),
          joint_reflection_normal({}, v, inverse_mass)})
      EXPECT_EQ(none.linfty_norm(), 0.);
  }

  TEST(JointReflection, TurnsAJammedPointBack)
  {
    // A unit mass between two walls, touching both, moving into the first:
    // no velocity parts both; the projection stops it, and the reflection
    // turns it back, into the second wall.
    const Vector                    inverse_mass = vector_of({1.});
    const Vector                    v            = vector_of({-1.});
    const std::vector<SparseNormal> walls        = {dense_normal({1.}),
                                                    dense_normal({-1.})};
    const Vector                    w            = reflected(v,
                               joint_reflection_normal(walls, v, inverse_mass),
                               inverse_mass);
    EXPECT_NEAR(w[0], 1., 1e-15);
  }

  TEST(JointReflection, DoesNotDependOnRepeatedNormals)
  {
    // The same wall given three times, once scaled: the projection is that
    // onto the one wall.
    const Vector inverse_mass = vector_of({0.5, 2.});
    const Vector v            = vector_of({1., -1.});
    const Vector n = parting_projection_normal({dense_normal({0., 1.}),
                                                dense_normal({0., 1.}),
                                                dense_normal({0., 2.})},
                                               v,
                                               inverse_mass);
    EXPECT_NEAR(v[0] + inverse_mass[0] * n[0], 1., 1e-15);
    EXPECT_NEAR(v[1] + inverse_mass[1] * n[1], 0., 1e-15);
  }

  TEST(JointReflection, MeetsTheComplementarityConditionsOnRandomCones)
  {
    // Random normals, more of them than coordinates, some repeated, and
    // random masses and velocities: the projection v + M^-1 n parts or
    // holds every pair (w_k >= 0), held pairs only push (lambda . w = 0
    // shows as n . (v + M^-1 n) = 0), and no other such velocity is closer
    // to v. The joint reflection keeps the kinetic energy, parts every pair
    // that approached, and, where the normals are independent (no jam),
    // parts or holds every other pair, where the projection's mirror image
    // often does not.
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> uniform(-1., 1.);
    unsigned int independent = 0, mirror_approaches = 0;
    for (unsigned int trial = 0; trial < 200; ++trial)
      {
        const unsigned int n_dofs = 3 + trial % 7, K = 2 + trial % 13;
        Vector             inverse_mass(n_dofs), v(n_dofs);
        for (unsigned int i = 0; i < n_dofs; ++i)
          {
            inverse_mass[i] = 1.5 + uniform(random);
            v[i]            = uniform(random);
          }
        std::vector<SparseNormal> normals;
        for (unsigned int k = 0; k < K; ++k)
          {
            if (k > 0 && k % 5 == 0)
              {
                normals.push_back(normals[k - 1]);
                continue;
              }
            std::vector<double> values(n_dofs);
            for (double &x : values)
              x = uniform(random);
            normals.push_back(dense_normal(values));
          }
        const Vector n = parting_projection_normal(normals, v, inverse_mass);
        Vector       projection = v;
        for (unsigned int i = 0; i < n_dofs; ++i)
          projection[i] += inverse_mass[i] * n[i];
        for (const SparseNormal &normal : normals)
          EXPECT_GE(rate(normal, projection), -1e-10 * (1. + n.l2_norm()))
            << "trial " << trial;
        EXPECT_NEAR(n * projection, 0., 1e-10 * (1. + n.l2_norm()))
          << "trial " << trial << ", |n| = " << n.l2_norm();
        // The projection is the closest: n . w >= 0 for every velocity w
        // that parts or holds every pair, such as the projections of other
        // velocities (n = -M (v - projection) lies in the polar cone).
        for (unsigned int other = 0; other < 5; ++other)
          {
            Vector u(n_dofs);
            for (unsigned int i = 0; i < n_dofs; ++i)
              u[i] = uniform(random);
            Vector w = parting_projection_normal(normals, u, inverse_mass);
            for (unsigned int i = 0; i < n_dofs; ++i)
              w[i] = u[i] + inverse_mass[i] * w[i];
            EXPECT_GE(n * w, -1e-10 * (1. + n.l2_norm()) * (1. + w.l2_norm()))
              << "trial " << trial;
          }
        double kinetic = 0., approaching = 0.;
        for (unsigned int i = 0; i < n_dofs; ++i)
          kinetic += v[i] * v[i] / inverse_mass[i];
        for (const SparseNormal &normal : normals)
          approaching = std::min(approaching, rate(normal, v));
        if (approaching == 0.)
          {
            EXPECT_EQ(n.linfty_norm(), 0.);
            continue;
          }
        const Vector w =
          reflected(v,
                    joint_reflection_normal(normals, v, inverse_mass),
                    inverse_mass);
        double reflected_kinetic = 0.;
        for (unsigned int i = 0; i < n_dofs; ++i)
          reflected_kinetic += w[i] * w[i] / inverse_mass[i];
        EXPECT_NEAR(reflected_kinetic, kinetic, 1e-12 * kinetic);
        const Vector mirror = reflected(v, n, inverse_mass);
        const bool   jam    = K - (K - 1) / 5 > n_dofs;
        independent += !jam;
        bool mirror_approached = false;
        for (const SparseNormal &normal : normals)
          {
            if (rate(normal, v) < 0.)
              EXPECT_GT(rate(normal, w), 0.) << "trial " << trial;
            else if (!jam)
              EXPECT_GE(rate(normal, w), -1e-12) << "trial " << trial;
            mirror_approached |= rate(normal, mirror) < -1e-12;
          }
        mirror_approaches += !jam && mirror_approached;
      }
    EXPECT_GT(independent, 50u);
    EXPECT_GT(mirror_approaches, 5u);
  }
} // namespace
