// Conservative CCD on rounding-sensitive data (issue 13). More than 10^5
// constructed queries with an exact contact whose time is known by
// construction, with integer (dyadic) coordinates up to 2^24 and up to 2^26
// (where the round-off bound 2^-46 M of the box ranges nearly reaches the
// default tolerance 1e-6) and within 2^12 of a corner of [-2^26, 2^26]^3: a
// vertex resting in a face plane, a vertex moving in the face plane onto the
// face, a vertex crossing the face, parallel edges meeting, collinear edges
// meeting end to end, edges moving in a common plane, crossing edges, general
// motion; contacts at t = 0, at t = 1 and at times k/16 in between; every
// construction again with coordinates up to 2^28 and caps of 1 to 64 boxes.
// Besides: contacts at a corner of the parameter domain with full-mantissa
// coordinates (F at the contact evaluated with rounding), a vertex reaching an
// axis-aligned face where the computed distance is below the tolerance while
// the exact one is above, and near misses that exceed the tolerance by
// between a fraction of a unit in the last place and the tolerance itself.
//
// What is asserted is what continuous_collision.h promises:
//  - every exact contact is reported (no false negative), also when the
//    iteration cap decides;
//  - the reported time is no later than the exact contact time (for t = 0:
//    exactly 0);
//  - unless the cap decided, the primitives are within the tolerance (in every
//    coordinate of F) at the reported time: where the construction gives a
//    lower bound of the distance before the contact, the time is not earlier
//    than that bound allows;
//  - a pair that provably stays farther apart than the tolerance in some
//    coordinate of F is reported only if the cap decided.
// All data come from fixed seeds. The integer constructions are verified in
// exact integer arithmetic, the near misses in exact long double arithmetic;
// the full-mantissa contacts are exact by construction (the touching points
// are the same doubles, or the face lies in a coordinate plane).

#include <estep/contact/continuous_collision.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

using namespace estep::contact;

namespace
{
  static_assert(std::numeric_limits<long double>::digits >= 64,
                "the near-miss certificates need a 64-bit mantissa");

  using Int = std::int64_t;
  __extension__ typedef __int128 Wide;
  using IPoint = std::array<Int, 3>;

  /** Coordinates of the constructed contacts are integers in units of 2^-8. */
  constexpr int unit_bits = 8;

  /** One length unit in units of 2^-8. */
  constexpr Int one = Int(1) << unit_bits;

  /** Contact times are k / 2^time_bits, k = 0, ..., 16. */
  constexpr int time_bits = 4;

  /** Denominator of the contact times. */
  constexpr Int time_denominator = Int(1) << time_bits;

  /** Default tolerance of the CCD. */
  const double tolerance = CcdSettings().tolerance;

  /** Vector arithmetic on integer points. */
  IPoint
  operator+(const IPoint &a, const IPoint &b)
  {
    return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}};
  }

  IPoint
  operator-(const IPoint &a, const IPoint &b)
  {
    return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}};
  }

  IPoint
  operator*(const Int s, const IPoint &a)
  {
    return {{s * a[0], s * a[1], s * a[2]}};
  }

  /** Exact division of every coordinate (the construction guarantees it). */
  IPoint
  divide(const IPoint &a, const Int d)
  {
    IPoint q;
    for (unsigned int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(a[k] % d, 0) << "inexact construction";
        q[k] = a[k] / d;
      }
    return q;
  }

  using WPoint = std::array<Wide, 3>;

  /** Exact cross product. */
  WPoint
  cross(const IPoint &a, const IPoint &b)
  {
    return {{Wide(a[1]) * b[2] - Wide(a[2]) * b[1],
             Wide(a[2]) * b[0] - Wide(a[0]) * b[2],
             Wide(a[0]) * b[1] - Wide(a[1]) * b[0]}};
  }

  /** Exact dot product. */
  Wide
  dot(const IPoint &a, const WPoint &b)
  {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  }

  /** Exact det[b - a, c - a, d - a]. */
  Wide
  orientation(const IPoint &a,
              const IPoint &b,
              const IPoint &c,
              const IPoint &d)
  {
    return dot(d - a, cross(b - a, c - a));
  }

  /** Exact det[b - a, c - a] of the projection that drops coordinate @p axis.
   */
  Wide
  orientation_2d(const IPoint      &a,
                 const IPoint      &b,
                 const IPoint      &c,
                 const unsigned int axis)
  {
    const unsigned int i = (axis + 1) % 3, j = (axis + 2) % 3;
    return Wide(b[i] - a[i]) * (c[j] - a[j]) -
           Wide(b[j] - a[j]) * (c[i] - a[i]);
  }

  /** The sign of @p x: -1, 0 or 1. */
  int
  sign(const Wide x)
  {
    return (x > 0) - (x < 0);
  }

  /** Whether all coordinates of @p n vanish. */
  bool
  is_zero(const WPoint &n)
  {
    return n[0] == 0 && n[1] == 0 && n[2] == 0;
  }

  /** The coordinate in which @p n is largest in magnitude. */
  unsigned int
  dominant_axis(const WPoint &n)
  {
    unsigned int k = 0;
    for (unsigned int i = 1; i < 3; ++i)
      if ((n[i] < 0 ? -n[i] : n[i]) > (n[k] < 0 ? -n[k] : n[k]))
        k = i;
    return k;
  }

  /** Euclidean norm (rounded in long double). */
  long double
  norm(const WPoint &n)
  {
    long double s = 0.;
    for (const Wide x : n)
      s += static_cast<long double>(x) * static_cast<long double>(x);
    return std::sqrt(s);
  }

  /** Euclidean norm (rounded in long double). */
  long double
  norm(const IPoint &a)
  {
    return norm(WPoint{{a[0], a[1], a[2]}});
  }

  /** Whether c lies on the segment [a, b], all three being collinear. */
  bool
  on_collinear_segment(const IPoint &a, const IPoint &b, const IPoint &c)
  {
    for (unsigned int k = 0; k < 3; ++k)
      if (c[k] < std::min(a[k], b[k]) || c[k] > std::max(a[k], b[k]))
        return false;
    return true;
  }

  /** Exact test: does the point p lie in the closed triangle (a, b, c)? */
  bool
  point_in_triangle(const IPoint &p,
                    const IPoint &a,
                    const IPoint &b,
                    const IPoint &c)
  {
    const WPoint n = cross(b - a, c - a);
    if (is_zero(n) || orientation(a, b, c, p) != 0)
      return false;
    const unsigned int axis = dominant_axis(n);
    const int          s0   = sign(orientation_2d(a, b, p, axis)),
              s1            = sign(orientation_2d(b, c, p, axis)),
              s2            = sign(orientation_2d(c, a, p, axis));
    return (s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0);
  }

  /** Exact test: do the closed segments [a0, a1] and [b0, b1] intersect? */
  bool
  segments_intersect(const IPoint &a0,
                     const IPoint &a1,
                     const IPoint &b0,
                     const IPoint &b1)
  {
    if (orientation(a0, a1, b0, b1) != 0)
      return false;
    // A normal of the common plane, unless all four points are collinear.
    WPoint n = cross(a1 - a0, b0 - a0);
    if (is_zero(n))
      n = cross(a1 - a0, b1 - a0);
    if (is_zero(n))
      n = cross(b1 - b0, a0 - b0);
    if (is_zero(n))
      return on_collinear_segment(a0, a1, b0) ||
             on_collinear_segment(a0, a1, b1) ||
             on_collinear_segment(b0, b1, a0) ||
             on_collinear_segment(b0, b1, a1);
    const unsigned int axis = dominant_axis(n);
    const int          d0   = sign(orientation_2d(a0, a1, b0, axis)),
              d1            = sign(orientation_2d(a0, a1, b1, axis)),
              d2            = sign(orientation_2d(b0, b1, a0, axis)),
              d3            = sign(orientation_2d(b0, b1, a1, axis));
    if (d0 * d1 < 0 && d2 * d3 < 0)
      return true;
    return (d0 == 0 && on_collinear_segment(a0, a1, b0)) ||
           (d1 == 0 && on_collinear_segment(a0, a1, b1)) ||
           (d2 == 0 && on_collinear_segment(b0, b1, a0)) ||
           (d3 == 0 && on_collinear_segment(b0, b1, a1));
  }

  /**
   * A constructed query with an exact contact at time tau = tau_numerator /
   * 16; coordinates in units of 2^-8.
   */
  struct ExactQuery
  {
    bool                  edge_edge = false;
    std::array<IPoint, 4> start, end;
    Int                   tau_numerator = 0;
    /**
     * If positive: the Euclidean distance of the primitives at a time t <= tau
     * is at least (tau - t) times this (in length units per unit time), and
     * it is convex in t (the primitives move by a relative translation), so
     * that tau is the first contact and the distance decreases up to it.
     */
    long double approach = 0.;
  };

  /**
   * Sets point @p i of @p q to be at @p x at time tau and to move with
   * velocity @p v (a multiple of 2^time_bits units, so that the positions at
   * t = 0 and 1 are exact).
   */
  void
  place(ExactQuery &q, const unsigned int i, const IPoint &x, const IPoint &v)
  {
    q.start[i] = x - divide(q.tau_numerator * v, time_denominator);
    q.end[i] =
      x + divide((time_denominator - q.tau_numerator) * v, time_denominator);
  }

  /** The positions at time tau, exactly (integers, by construction). */
  std::array<IPoint, 4>
  positions_at_tau(const ExactQuery &q)
  {
    std::array<IPoint, 4> x;
    for (unsigned int i = 0; i < 4; ++i)
      x[i] = divide(time_denominator * q.start[i] +
                      q.tau_numerator * (q.end[i] - q.start[i]),
                    time_denominator);
    return x;
  }

  /** Exact test that the primitives touch at tau. */
  bool
  touches_at_tau(const ExactQuery &q)
  {
    const std::array<IPoint, 4> x = positions_at_tau(q);
    return q.edge_edge ? segments_intersect(x[0], x[1], x[2], x[3]) :
                         point_in_triangle(x[0], x[1], x[2], x[3]);
  }

  /** Largest coordinate magnitude of @p q at t = 0 and 1, in units. */
  Int
  largest_coordinate(const ExactQuery &q)
  {
    Int m = 0;
    for (const auto *x : {&q.start, &q.end})
      for (const IPoint &p : *x)
        for (const Int c : p)
          m = std::max(m, c < 0 ? -c : c);
    return m;
  }

  /** The points in length units (exact: |x| < 2^53 units). */
  std::array<Point3, 4>
  to_double(const std::array<IPoint, 4> &x)
  {
    std::array<Point3, 4> y;
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int k = 0; k < 3; ++k)
        y[i][k] = std::ldexp(static_cast<double>(x[i][k]), -unit_bits);
    return y;
  }

  /** A query's data, for failure messages. */
  std::string
  describe(const std::array<Point3, 4> &start, const std::array<Point3, 4> &end)
  {
    std::ostringstream s;
    s << std::setprecision(17);
    for (const auto *x : {&start, &end})
      {
        s << (x == &start ? "start" : " end");
        for (const Point3 &p : *x)
          s << " (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
      }
    return s.str();
  }

  /** Sizes of the random data. */
  struct Scale
  {
    /** Coordinates at most 2^bits in magnitude. */
    int bits;
    /**
     * If false, points within 2^(bits-1) of the origin and vectors up to
     * 2^(bits-2); if true, points within 2^12 of a base point whose
     * coordinates are +-(2^bits - 2^14), vectors up to 2^11.
     */
    bool offset;
  };

  /** Random integer data for the constructions. */
  class Generator
  {
  public:
    Generator(const std::uint64_t seed, const Scale scale)
      : rng(seed)
      , scale(scale)
    {}

    Int
    uniform(const Int lo, const Int hi)
    {
      return std::uniform_int_distribution<Int>(lo, hi)(rng);
    }

    bool
    coin()
    {
      return uniform(0, 1) == 1;
    }

    /** Chooses the base point of the next query (offset scale). */
    void
    new_query()
    {
      const Int b = (Int(1) << scale.bits) - (Int(1) << 14);
      for (Int &x : base)
        x = coin() ? b : -b;
    }

    /** A point with integer coordinates, in units. */
    IPoint
    point()
    {
      const Int r = scale.offset ? Int(1) << 12 : Int(1) << (scale.bits - 1);
      IPoint    p;
      for (unsigned int k = 0; k < 3; ++k)
        p[k] = one * ((scale.offset ? base[k] : 0) + uniform(-r, r));
      return p;
    }

    /** A vector with integer coordinates up to 2^-shift of the vector range. */
    IPoint
    vector(const int shift = 0)
    {
      const Int r =
        (scale.offset ? Int(1) << 11 : Int(1) << (scale.bits - 2)) >> shift;
      return one * IPoint{{uniform(-r, r), uniform(-r, r), uniform(-r, r)}};
    }

    /** A velocity: zero or a random vector. */
    IPoint
    velocity()
    {
      return coin() ? IPoint{{0, 0, 0}} : vector();
    }

    /** A contact time: 0 (a quarter), 1 (a quarter) or k/16, 0 < k < 16. */
    Int
    time()
    {
      const Int c = uniform(0, 3);
      return c == 0 ? 0 : c == 1 ? time_denominator : uniform(1, 15);
    }

    /** Barycentric weights (i, j, k) / 4, i + j + k = 4, all >= 0. */
    std::array<Int, 3>
    weights()
    {
      const Int i = uniform(0, 4), j = uniform(0, 4 - i);
      return {{i, j, 4 - i - j}};
    }

    /** Largest coordinate magnitude of a query, in units. */
    Int
    max_coordinate() const
    {
      return one * (Int(1) << scale.bits);
    }

    std::mt19937_64 rng;

  private:
    const Scale scale;
    IPoint      base = {{0, 0, 0}};
  };

  /** A non-degenerate triangle (a, b, c). */
  std::array<IPoint, 3>
  triangle(Generator &g)
  {
    while (true)
      {
        const std::array<IPoint, 3> t = {{g.point(), g.point(), g.point()}};
        if (!is_zero(cross(t[1] - t[0], t[2] - t[0])))
          return t;
      }
  }

  /** Swaps the two edges and the ends of each edge at random. */
  void
  shuffle_edges(Generator &g, ExactQuery &q)
  {
    // The same choices at both ends of the step.
    const bool swap_edges = g.coin(), swap_a = g.coin(), swap_b = g.coin();
    for (auto *x : {&q.start, &q.end})
      {
        if (swap_a)
          std::swap((*x)[0], (*x)[1]);
        if (swap_b)
          std::swap((*x)[2], (*x)[3]);
        if (swap_edges)
          {
            std::swap((*x)[0], (*x)[2]);
            std::swap((*x)[1], (*x)[3]);
          }
      }
  }

  /** Vertex and face at rest relative to each other (a common translation),
   * the vertex in the closed face: contact at every time, first at t = 0. */
  ExactQuery
  vertex_resting_in_face(Generator &g)
  {
    ExactQuery                  q;
    const std::array<IPoint, 3> t = triangle(g);
    const std::array<Int, 3>    w = g.weights();
    const IPoint p = divide(w[0] * t[0] + w[1] * t[1] + w[2] * t[2], 4);
    const IPoint v = g.velocity();
    place(q, 0, p, v);
    for (unsigned int i = 0; i < 3; ++i)
      place(q, i + 1, t[i], v);
    return q;
  }

  /** A vertex moving in the plane of the face, entering it across the edge
   * (b, c) (possibly at b or c) at tau. */
  ExactQuery
  vertex_entering_face_in_plane(Generator &g)
  {
    ExactQuery                  q;
    const std::array<IPoint, 3> t = triangle(g);
    q.tau_numerator               = g.time();
    const Int    j                = g.uniform(0, 4);
    const IPoint p                = divide(j * t[1] + (4 - j) * t[2], 4);
    Int          alpha = 0, beta = 0;
    while (alpha == 0 && beta == 0)
      {
        alpha = g.uniform(0, 1);
        beta  = g.uniform(0, 1);
      }
    // Inward: the weight of a grows.
    const IPoint w  = divide(alpha * (t[0] - t[1]) + beta * (t[0] - t[2]), 8);
    const IPoint bc = t[2] - t[1];
    q.approach      = norm(cross(w, bc)) / norm(bc) / one;
    const IPoint v  = g.velocity();
    place(q, 0, p, w + v);
    for (unsigned int i = 0; i < 3; ++i)
      place(q, i + 1, t[i], v);
    return q;
  }

  /** A vertex crossing the face's plane at tau, in the closed face then; the
   * face moves by a translation or not at all. */
  ExactQuery
  vertex_crossing_face(Generator &g)
  {
    ExactQuery                  q;
    const std::array<IPoint, 3> t = triangle(g);
    q.tau_numerator               = g.time();
    const std::array<Int, 3> w    = g.weights();
    const IPoint p = divide(w[0] * t[0] + w[1] * t[1] + w[2] * t[2], 4);
    const WPoint n = cross(t[1] - t[0], t[2] - t[0]);
    IPoint       u;
    do
      u = g.vector();
    while (dot(u, n) == 0);
    const Wide un = dot(u, n);
    q.approach    = static_cast<long double>(un < 0 ? -un : un) / norm(n) / one;
    const IPoint v = g.velocity();
    place(q, 0, p, u + v);
    for (unsigned int i = 0; i < 3; ++i)
      place(q, i + 1, t[i], v);
    return q;
  }

  /** A vertex in the closed face at tau, all four points moving
   * independently (tau need not be the first contact). */
  ExactQuery
  vertex_face_general_motion(Generator &g)
  {
    ExactQuery                  q;
    const std::array<IPoint, 3> t = triangle(g);
    q.tau_numerator               = g.time();
    const std::array<Int, 3> w    = g.weights();
    place(q,
          0,
          divide(w[0] * t[0] + w[1] * t[1] + w[2] * t[2], 4),
          g.velocity());
    for (unsigned int i = 0; i < 3; ++i)
      place(q, i + 1, t[i], g.velocity());
    return q;
  }

  /** Edges at x = a0 + s (a1 - a0) = b0 + r (b1 - b0), s, r in {0, 1/4, ...,
   * 1}, at tau (b possibly on the line of a); written to @p x. */
  void
  crossing_edges(Generator &g, std::array<IPoint, 4> &x, const bool collinear)
  {
    do
      {
        x[0] = g.point();
        x[1] = g.point();
    } while (x[0] == x[1]);
    const Int    s = g.uniform(0, 4), r = g.uniform(0, 4);
    const IPoint c = divide((4 - s) * x[0] + s * x[1], 4);
    IPoint       w;
    if (collinear)
      w = divide(g.uniform(1, 3) * (g.coin() ? 1 : -1) * (x[1] - x[0]), 2);
    else
      do
        w = g.vector();
      while (is_zero(cross(w, x[1] - x[0])));
    x[2] = c - divide(r * w, 4);
    x[3] = c + divide((4 - r) * w, 4);
  }

  /** Two edges crossing (or collinear and overlapping, a quarter) at rest
   * relative to each other: contact at every time, first at t = 0. */
  ExactQuery
  edges_resting(Generator &g)
  {
    ExactQuery q;
    q.edge_edge = true;
    std::array<IPoint, 4> x;
    crossing_edges(g, x, g.uniform(0, 3) == 0);
    const IPoint v = g.velocity();
    for (unsigned int i = 0; i < 4; ++i)
      place(q, i, x[i], v);
    shuffle_edges(g, q);
    return q;
  }

  /** Two edges crossing at tau, one translating out of their common plane. */
  ExactQuery
  edges_crossing(Generator &g)
  {
    ExactQuery q;
    q.edge_edge     = true;
    q.tau_numerator = g.time();
    std::array<IPoint, 4> x;
    crossing_edges(g, x, false);
    const WPoint m = cross(x[1] - x[0], x[3] - x[2]);
    IPoint       u;
    do
      u = g.vector();
    while (dot(u, m) == 0);
    const Wide um = dot(u, m);
    q.approach    = static_cast<long double>(um < 0 ? -um : um) / norm(m) / one;
    const IPoint v = g.velocity();
    for (unsigned int i = 0; i < 4; ++i)
      place(q, i, x[i], i < 2 ? v : u + v);
    shuffle_edges(g, q);
    return q;
  }

  /** Parallel edges whose lines coincide at tau, overlapping then (possibly
   * in one end point only). */
  ExactQuery
  parallel_edges_meeting(Generator &g)
  {
    ExactQuery q;
    q.edge_edge     = true;
    q.tau_numerator = g.time();
    const IPoint a0 = g.point();
    IPoint       d;
    do
      d = g.vector();
    while (d == IPoint{{0, 0, 0}});
    // b at a0 + (r0 / 4) d, a0 + (r1 / 4) d with [r0, r1] meeting [0, 4].
    Int r0 = 0, r1 = 0;
    while (r0 == r1 || std::max(r0, r1) < 0 || std::min(r0, r1) > 4)
      {
        r0 = g.uniform(-4, 8);
        r1 = g.uniform(-4, 8);
      }
    IPoint u;
    do
      u = g.vector();
    while (is_zero(cross(u, d)));
    q.approach     = norm(cross(u, d)) / norm(d) / one;
    const IPoint v = g.velocity();
    place(q, 0, a0, v);
    place(q, 1, a0 + d, v);
    place(q, 2, a0 + divide(r0 * d, 4), u + v);
    place(q, 3, a0 + divide(r1 * d, 4), u + v);
    shuffle_edges(g, q);
    return q;
  }

  /** Collinear edges sliding along their common line, meeting end to end at
   * tau. */
  ExactQuery
  collinear_edges_meeting(Generator &g)
  {
    ExactQuery q;
    q.edge_edge     = true;
    q.tau_numerator = g.time();
    const IPoint a0 = g.point();
    IPoint       d;
    do
      d = g.vector();
    while (d == IPoint{{0, 0, 0}});
    const Int    m = g.uniform(1, 8), speed = g.uniform(1, 4);
    const IPoint v = g.velocity();
    place(q, 0, a0, v);
    place(q, 1, a0 + d, v);
    if (g.coin())
      {
        // b beyond a1, moving back towards it.
        place(q, 2, a0 + d, v - divide(speed * d, 4));
        place(q, 3, a0 + d + divide(m * d, 4), v - divide(speed * d, 4));
      }
    else
      {
        // b before a0, moving forward.
        place(q, 2, a0 - divide(m * d, 4), v + divide(speed * d, 4));
        place(q, 3, a0, v + divide(speed * d, 4));
      }
    q.approach = speed * norm(d) / 4 / one;
    shuffle_edges(g, q);
    return q;
  }

  /** Two edges in a common plane, b translating in that plane onto a: its
   * end point b0 reaches a (possibly an end point of a) at tau, b lying on
   * one side of the line of a before (the edges and their ends are then
   * shuffled). */
  ExactQuery
  coplanar_edges_meeting(Generator &g)
  {
    ExactQuery q;
    q.edge_edge     = true;
    q.tau_numerator = g.time();
    const IPoint o  = g.point();
    IPoint       e1, e2;
    do
      {
        e1 = g.vector(4);
        e2 = g.vector(4);
    } while (is_zero(cross(e1, e2)));
    // Plane coordinates (x, y) / 4 map to o + (x e1 + y e2) / 4.
    const auto map = [&](const Int x, const Int y) {
      return o + divide(x * e1 + y * e2, 4);
    };
    const auto cross_2d =
      [](const Int x0, const Int y0, const Int x1, const Int y1) {
        return x0 * y1 - y0 * x1;
      };
    Int ax0, ay0, ax1, ay1;
    do
      {
        ax0 = 4 * g.uniform(-8, 8);
        ay0 = 4 * g.uniform(-8, 8);
        ax1 = 4 * g.uniform(-8, 8);
        ay1 = 4 * g.uniform(-8, 8);
    } while (ax0 == ax1 && ay0 == ay1);
    const Int s = g.uniform(0, 4);
    // Contact point (in quarters): a0 + (s / 4) (a1 - a0).
    const Int cx = ax0 + s * (ax1 - ax0) / 4, cy = ay0 + s * (ay1 - ay0) / 4;
    // b1 - b0 strictly on the positive side of the line of a.
    Int ex, ey, side;
    do
      {
        ex   = 4 * g.uniform(-8, 8);
        ey   = 4 * g.uniform(-8, 8);
        side = cross_2d(ax1 - ax0, ay1 - ay0, ex, ey);
    } while (side == 0);
    if (side < 0)
      {
        ex = -ex;
        ey = -ey;
      }
    // b moves towards the negative side.
    Int ux, uy;
    do
      {
        ux   = g.uniform(-4, 4);
        uy   = g.uniform(-4, 4);
        side = cross_2d(ax1 - ax0, ay1 - ay0, ux, uy);
    } while (side == 0);
    if (side > 0)
      {
        ux = -ux;
        uy = -uy;
      }
    const IPoint u  = ux * e1 + uy * e2;
    const IPoint da = map(ax1, ay1) - map(ax0, ay0);
    q.approach      = norm(cross(u, da)) / norm(da) / one;
    const IPoint v  = g.velocity();
    place(q, 0, map(ax0, ay0), v);
    place(q, 1, map(ax1, ay1), v);
    place(q, 2, map(cx, cy), u + v);
    place(q, 3, map(cx + ex, cy + ey), u + v);
    shuffle_edges(g, q);
    return q;
  }

  /** Edges crossing at tau, all four points moving independently (tau need
   * not be the first contact). */
  ExactQuery
  edge_edge_general_motion(Generator &g)
  {
    ExactQuery q;
    q.edge_edge     = true;
    q.tau_numerator = g.time();
    std::array<IPoint, 4> x;
    crossing_edges(g, x, g.uniform(0, 7) == 0);
    for (unsigned int i = 0; i < 4; ++i)
      place(q, i, x[i], g.velocity());
    shuffle_edges(g, q);
    return q;
  }

  /** Counts of one category of constructed contacts. */
  struct Tally
  {
    std::size_t n = 0, at_start = 0, at_end = 0, capped = 0;
    std::size_t missed = 0, late = 0, early = 0, bad_construction = 0;
  };

  /** Runs the CCD on @p q and checks what the documentation promises. */
  void
  check_exact_contact(const ExactQuery  &q,
                      const CcdSettings &settings,
                      Tally             &tally)
  {
    ++tally.n;
    if (!touches_at_tau(q))
      {
        if (++tally.bad_construction <= 3)
          ADD_FAILURE() << "construction without contact at tau";
        return;
      }
    const std::array<Point3, 4> start = to_double(q.start),
                                end   = to_double(q.end);
    const double tau =
      std::ldexp(static_cast<double>(q.tau_numerator), -time_bits);
    tally.at_start += (q.tau_numerator == 0);
    tally.at_end += (q.tau_numerator == time_denominator);
    const CcdResult r = q.edge_edge ? edge_edge_ccd(start, end, settings) :
                                      vertex_face_ccd(start, end, settings);
    tally.capped += r.capped;
    const char *kind = q.edge_edge ? "edge-edge" : "vertex-face";
    if (!r.hit)
      {
        if (++tally.missed <= 5)
          ADD_FAILURE() << kind << " contact at t = " << tau
                        << " missed: " << describe(start, end);
        return;
      }
    if (!(r.time >= 0. && r.time <= tau))
      {
        if (++tally.late <= 5)
          ADD_FAILURE() << kind << " contact at t = " << tau
                        << " reported at t = " << r.time << ": "
                        << describe(start, end);
        return;
      }
    // Within the tolerance in every coordinate of F at the reported time, so
    // within sqrt(3) times the tolerance in length.
    if (!r.capped && q.approach > 0. &&
        (tau - r.time) * q.approach >
          std::sqrt(3.L) * settings.tolerance * (1. + 1e-9))
      {
        if (++tally.early <= 5)
          ADD_FAILURE() << kind << " contact at t = " << tau
                        << " reported at t = " << r.time
                        << ", when the distance is at least "
                        << static_cast<double>((tau - r.time) * q.approach)
                        << ": " << describe(start, end);
      }
  }

  /**
   * Runs @p n queries of one construction and checks them: a third with
   * coordinates up to 2^24 and the default tolerance 1e-6 (the round-off
   * bound 2^-46 M of the box ranges is at most 0.24 times the tolerance), a
   * third with coordinates up to 2^26 and a third within 2^12 of a corner of
   * [-2^26, 2^26]^3, both with the tolerance 2^-18 (four times the round-off
   * bound at 2^26; with the tolerance 1e-6 the bound, 0.95e-6, would leave
   * box ranges too wide to be accepted and too close to 0 to be discarded, so
   * that most queries would reach the iteration cap). The iteration cap is
   * @p max_iterations (queries it decides are still checked: a contact, not
   * late). With @p capped_run: coordinates up to 2^28, the default tolerance
   * (below the round-off bound there, so that no box can be accepted) and
   * caps of 1 to 64 boxes, so that the cap decides every query not rejected.
   */
  template <typename Construction>
  void
  run_exact_contacts(const std::string  &name,
                     const Construction &construct,
                     const std::uint64_t seed,
                     const unsigned int  n,
                     const unsigned int  max_iterations,
                     const bool          capped_run = false)
  {
    Tally                    tally;
    std::array<Generator, 3> generators = {
      {Generator(seed, capped_run ? Scale{28, false} : Scale{24, false}),
       Generator(seed + 1, Scale{26, false}),
       Generator(seed + 2, Scale{26, true})}};
    for (unsigned int i = 0; i < n; ++i)
      {
        const unsigned int s = capped_run ? 0 : i % 3;
        Generator         &g = generators[s];
        ExactQuery         q;
        do
          {
            g.new_query();
            q = construct(g);
        } while (largest_coordinate(q) > g.max_coordinate());
        CcdSettings settings;
        settings.max_iterations = capped_run ? 1 + i % 64 : max_iterations;
        if (s > 0)
          settings.tolerance = 0x1p-18;
        check_exact_contact(q, settings, tally);
      }
    EXPECT_EQ(tally.bad_construction, 0u) << name;
    EXPECT_EQ(tally.missed, 0u) << name << ": false negatives";
    EXPECT_EQ(tally.late, 0u) << name << ": reported later than the contact";
    EXPECT_EQ(tally.early, 0u)
      << name << ": reported when farther apart than the tolerance";
    std::cout << name << ": " << tally.n << " exact contacts ("
              << tally.at_start << " at t = 0, " << tally.at_end
              << " at t = 1), " << tally.capped
              << " decided by the iteration cap; missed " << tally.missed
              << ", late " << tally.late << ", too early " << tally.early
              << std::endl;
  }

  /** Number of queries of each construction (10 constructions: 10^5). */
  constexpr unsigned int n_per_construction = 10000;

  /** Iteration cap of the constructed contacts (instead of 10^5, for time). */
  constexpr unsigned int test_max_iterations = 10000;
} // namespace



TEST(CcdRounding, VertexRestingInFacePlane)
{
  run_exact_contacts("vertex resting in face plane",
                     vertex_resting_in_face,
                     1301,
                     n_per_construction,
                     test_max_iterations);
}

TEST(CcdRounding, VertexEnteringFaceInItsPlane)
{
  run_exact_contacts("vertex entering face in its plane",
                     vertex_entering_face_in_plane,
                     1302,
                     n_per_construction,
                     test_max_iterations);
}

TEST(CcdRounding, VertexCrossingFace)
{
  run_exact_contacts("vertex crossing face",
                     vertex_crossing_face,
                     1303,
                     n_per_construction,
                     test_max_iterations);
}

TEST(CcdRounding, VertexFaceGeneralMotion)
{
  run_exact_contacts("vertex-face general motion",
                     vertex_face_general_motion,
                     1304,
                     n_per_construction,
                     test_max_iterations);
}

TEST(CcdRounding, EdgesResting)
{
  run_exact_contacts("edges resting",
                     edges_resting,
                     1305,
                     n_per_construction,
                     test_max_iterations);
}

TEST(CcdRounding, EdgesCrossing)
{
  run_exact_contacts("edges crossing",
                     edges_crossing,
                     1306,
                     n_per_construction,
                     test_max_iterations);
}

// Boxes just before the lines meet can only be discarded at a resolution of
// about the tolerance over the whole overlap (the normal direction of two
// parallel edges is undefined), so the CCD reaches any cap unless the contact
// is at t = 0: a cap of 500 boxes keeps the run time small.
TEST(CcdRounding, ParallelEdgesMeeting)
{
  run_exact_contacts("parallel edges meeting",
                     parallel_edges_meeting,
                     1307,
                     n_per_construction,
                     500);
}

TEST(CcdRounding, CollinearEdgesMeeting)
{
  run_exact_contacts("collinear edges meeting",
                     collinear_edges_meeting,
                     1308,
                     n_per_construction,
                     test_max_iterations);
}

TEST(CcdRounding, CoplanarEdgesMeeting)
{
  run_exact_contacts("coplanar edges meeting",
                     coplanar_edges_meeting,
                     1309,
                     n_per_construction,
                     test_max_iterations);
}

TEST(CcdRounding, EdgeEdgeGeneralMotion)
{
  run_exact_contacts("edge-edge general motion",
                     edge_edge_general_motion,
                     1310,
                     n_per_construction,
                     test_max_iterations);
}

// Coordinates up to 2^28: the round-off bound 2^-46 M exceeds the tolerance,
// so no box is ever within it and the iteration cap (1 to 64 boxes) decides
// every query that is not rejected: still a contact, never late.
TEST(CcdRounding, IterationCapReportsContacts)
{
  const std::pair<const char *, ExactQuery (*)(Generator &)> constructions[] = {
    {"capped: vertex resting in face plane", vertex_resting_in_face},
    {"capped: vertex entering face in its plane",
     vertex_entering_face_in_plane},
    {"capped: vertex crossing face", vertex_crossing_face},
    {"capped: vertex-face general motion", vertex_face_general_motion},
    {"capped: edges resting", edges_resting},
    {"capped: edges crossing", edges_crossing},
    {"capped: parallel edges meeting", parallel_edges_meeting},
    {"capped: collinear edges meeting", collinear_edges_meeting},
    {"capped: coplanar edges meeting", coplanar_edges_meeting},
    {"capped: edge-edge general motion", edge_edge_general_motion}};
  std::uint64_t seed = 1400;
  for (const auto &c : constructions)
    run_exact_contacts(c.first, c.second, ++seed, 1000, 0, true);
}

namespace
{
  /**
   * A contact exactly at t = tau in {0, 1} between coordinates with full
   * 53-bit mantissas, so that the CCD evaluates F at the contact with
   * rounding: the vertex meets a vertex of the face (or an end point of edge
   * a meets one of edge b) that is extreme in the coordinate @p axis, the
   * other points lying on one side, so that F_axis has one sign over the whole
   * parameter domain and vanishes only at the contact (a corner of the domain).
   * |F_axis| >= |t - tau| rate.
   */
  struct CornerContact
  {
    bool                  edge_edge = false;
    std::array<Point3, 4> start, end;
    double                tau  = 0.;
    long double           rate = 0.;
  };

  CornerContact
  corner_contact(std::mt19937_64 &rng, const bool edge_edge, const double m)
  {
    std::uniform_real_distribution<double> coordinate(-m / 2., m / 2.),
      height(0., m / 4.);
    std::uniform_int_distribution<int> pick(0, 5);
    const auto                         random_point = [&]() {
      return Point3{{coordinate(rng), coordinate(rng), coordinate(rng)}};
    };
    CornerContact q;
    q.edge_edge             = edge_edge;
    const unsigned int axis = pick(rng) % 3;
    const double       up   = (pick(rng) % 2) ? 1. : -1.;
    q.tau                   = pick(rng) % 2;
    // The points lying "above" the contact in the coordinate axis (the face,
    // or edge a) and the one or two "below" it (the vertex, or edge b); the
    // touching ones first.
    const std::array<unsigned int, 4> order =
      edge_edge ?
        std::array<unsigned int, 4>{
          {static_cast<unsigned int>(pick(rng) % 2),
           0,
           static_cast<unsigned int>(2 + pick(rng) % 2),
           0}} :
        std::array<unsigned int, 4>{
          {static_cast<unsigned int>(1 + pick(rng) % 3), 0, 0, 0}};
    const unsigned int touching_above = order[0],
                       touching_below = edge_edge ? order[2] : 0;
    for (unsigned int s = 0; s < 2; ++s)
      {
        std::array<Point3, 4> &x       = (s == 0 ? q.start : q.end);
        const bool             contact = (s == q.tau);
        const Point3           c       = random_point();
        for (unsigned int i = 0; i < 4; ++i)
          {
            const bool above = edge_edge ? (i < 2) : (i > 0);
            if (i == touching_above)
              x[i] = c;
            else if (i == touching_below)
              {
                // At the contact time on the touching point above, otherwise
                // strictly below it.
                x[i] = contact ? c : random_point();
                if (!contact)
                  x[i][axis] = c[axis] - up * (1. + height(rng));
              }
            else
              {
                x[i]       = random_point();
                x[i][axis] = c[axis] + (above ? up : -up) * (1. + height(rng));
              }
          }
      }
    // |F_axis| >= (x_touching_above - x_below) up (for the lowest point
    // below), linear in t, zero at tau.
    const std::array<Point3, 4> &other = (q.tau == 0. ? q.end : q.start);
    q.rate = std::numeric_limits<long double>::infinity();
    for (unsigned int i = (edge_edge ? 2 : 0); i < (edge_edge ? 4 : 1); ++i)
      q.rate =
        std::min(q.rate,
                 up * (static_cast<long double>(other[touching_above][axis]) -
                       static_cast<long double>(other[i][axis])));
    return q;
  }
} // namespace

// Contacts exactly at t = 0 or t = 1 at a corner of the parameter domain
// (vertex on a vertex of the face, end point on end point), with coordinates
// of full 53-bit mantissas up to 2^24 (default tolerance) and 2^26 (tolerance
// 2^-18): F at the contact is evaluated with rounding, and one coordinate of F
// keeps one sign over the whole domain, so that only the round-off bound keeps
// the box from being discarded. Never missed, never late, never earlier than
// the tolerance allows (|F_axis| >= |t - tau| rate).
TEST(CcdRounding, CornerContactsWithRounding)
{
  std::mt19937_64 rng(1600);
  for (const bool edge_edge : {false, true})
    {
      Tally tally;
      for (unsigned int i = 0; i < 5000; ++i)
        {
          const bool          large = (i % 2 == 1);
          const CornerContact q =
            corner_contact(rng, edge_edge, large ? 0x1p26 : 0x1p24);
          CcdSettings settings;
          settings.max_iterations = 10000;
          if (large)
            settings.tolerance = 0x1p-18;
          ++tally.n;
          tally.at_start += (q.tau == 0.);
          tally.at_end += (q.tau == 1.);
          const CcdResult r = edge_edge ?
                                edge_edge_ccd(q.start, q.end, settings) :
                                vertex_face_ccd(q.start, q.end, settings);
          tally.capped += r.capped;
          if (!r.hit)
            {
              if (++tally.missed <= 5)
                ADD_FAILURE() << "contact at t = " << q.tau
                              << " missed: " << describe(q.start, q.end);
              continue;
            }
          if (!(r.time >= 0. && r.time <= q.tau))
            {
              if (++tally.late <= 5)
                ADD_FAILURE()
                  << "contact at t = " << q.tau << " reported at t = " << r.time
                  << ": " << describe(q.start, q.end);
              continue;
            }
          if (!r.capped &&
              (q.tau - r.time) * q.rate > settings.tolerance * (1. + 1e-9))
            if (++tally.early <= 5)
              ADD_FAILURE()
                << "contact at t = " << q.tau << " reported at t = " << r.time
                << ", when one coordinate of F is at least "
                << static_cast<double>((q.tau - r.time) * q.rate) << ": "
                << describe(q.start, q.end);
        }
      EXPECT_EQ(tally.missed, 0u);
      EXPECT_EQ(tally.late, 0u);
      EXPECT_EQ(tally.early, 0u);
      std::cout << (edge_edge ? "edge-edge" : "vertex-face")
                << " corner contacts with rounding: " << tally.n
                << " exact contacts (" << tally.at_start << " at t = 0, "
                << tally.at_end << " at t = 1), " << tally.capped
                << " decided by the iteration cap; missed " << tally.missed
                << ", late " << tally.late << ", too early " << tally.early
                << std::endl;
    }
}

// A vertex moving along a coordinate axis onto a face in the plane x_axis = Z
// (Z in [2^24, 2^25), full mantissa), reaching it at t = 1 at an interior
// point, |F_axis| = (1 - t) g exactly. The speed g is chosen so that at t = 1
// - 2^-m, a box boundary, the distance 2^-m g exceeds the tolerance 1e-6 by
// less than 2^(-m-28); the position there rounds to the grid 2^-28 of Z's
// binade, on which the tolerance lies 0.435 steps above a grid point, so the
// computed distance at that time is below the tolerance. A box starting there
// may be accepted only if the round-off bound is accounted for: the reported
// time must satisfy (1 - time) g <= tolerance unless the cap decided.
TEST(CcdRounding, VertexReachingAxisAlignedFace)
{
  std::mt19937_64 rng(1700);
  const auto      uniform = [&](const Int lo, const Int hi) {
    return std::uniform_int_distribution<Int>(lo, hi)(rng);
  };
  Tally tally;
  for (unsigned int n = 0; n < 5000; ++n)
    {
      const unsigned int k = uniform(0, 2), i = (k + 1) % 3, j = (k + 2) % 3;
      const double       up = uniform(0, 1) ? 1. : -1.;
      const double       z =
        up * std::ldexp(static_cast<double>(
                          uniform((Int(1) << 52) + (Int(1) << 38),
                                  (Int(1) << 53) - (Int(1) << 38))),
                        -28);
      std::array<Int, 3> x, y;
      do
        for (unsigned int p = 0; p < 3; ++p)
          {
            x[p] = uniform(-(Int(1) << 23), Int(1) << 23);
            y[p] = uniform(-(Int(1) << 23), Int(1) << 23);
          }
      while ((x[1] - x[0]) * (y[2] - y[0]) == (x[2] - x[0]) * (y[1] - y[0]));
      const int    m = uniform(12, 26);
      const double g =
        std::ldexp(std::ceil(std::ldexp(tolerance, m + 28)), -28);
      std::array<Point3, 4> start, end;
      for (unsigned int p = 0; p < 3; ++p)
        {
          start[p + 1][i] = end[p + 1][i] = static_cast<double>(x[p]);
          start[p + 1][j] = end[p + 1][j] = static_cast<double>(y[p]);
          start[p + 1][k] = end[p + 1][k] = z;
        }
      // (a + b + 2 c) / 4, strictly inside.
      start[0][i] = end[0][i] =
        static_cast<double>(x[0] + x[1] + 2 * x[2]) / 4.;
      start[0][j] = end[0][j] =
        static_cast<double>(y[0] + y[1] + 2 * y[2]) / 4.;
      start[0][k] = z - up * g;
      end[0][k]   = z;
      CcdSettings settings;
      settings.max_iterations = test_max_iterations;
      const CcdResult r       = vertex_face_ccd(start, end, settings);
      ++tally.n;
      tally.capped += r.capped;
      if (!r.hit)
        {
          if (++tally.missed <= 5)
            ADD_FAILURE() << "contact at t = 1 missed: "
                          << describe(start, end);
          continue;
        }
      if (!r.capped && (1.L - r.time) * static_cast<long double>(g) >
                         tolerance * (1. + 1e-15))
        if (++tally.early <= 5)
          ADD_FAILURE() << "contact at t = 1 reported at t = " << r.time
                        << ", when the distance is "
                        << static_cast<double>((1.L - r.time) * g) << ": "
                        << describe(start, end);
    }
  EXPECT_EQ(tally.missed, 0u);
  EXPECT_EQ(tally.early, 0u);
  std::cout << "vertex reaching an axis-aligned face: " << tally.n
            << " exact contacts (at t = 1), " << tally.capped
            << " decided by the iteration cap; missed " << tally.missed
            << ", too early " << tally.early << std::endl;
}

namespace
{
  /** A query that provably never comes within the tolerance. */
  struct NearMiss
  {
    bool                  edge_edge = false;
    std::array<Point3, 4> start, end;
  };

  /**
   * Exact certificate that some coordinate of F(t, u, v) (vertex minus face
   * point, or point of edge a minus point of edge b) exceeds the tolerance in
   * magnitude, with one sign, over the whole parameter domain: F is affine in
   * (u, v) for fixed t and affine in t, so its range is the hull of its values
   * at t in {0, 1} and (u, v) at the vertices of the domain. The differences
   * are exact in long double for the data below (multiples of 2^-30 smaller
   * than 2^29). Returns the smallest |F_k| of the separating coordinate, or 0.
   */
  long double
  separation(const NearMiss &q)
  {
    long double best = 0.;
    for (unsigned int k = 0; k < 3; ++k)
      {
        long double lo = std::numeric_limits<long double>::infinity(), hi = -lo;
        for (const auto *x : {&q.start, &q.end})
          for (unsigned int i = 0; i < (q.edge_edge ? 2 : 1); ++i)
            for (unsigned int j = (q.edge_edge ? 2 : 1); j < 4; ++j)
              {
                const long double f = static_cast<long double>((*x)[i][k]) -
                                      static_cast<long double>((*x)[j][k]);
                lo = std::min(lo, f);
                hi = std::max(hi, f);
              }
        best = std::max({best, lo, -hi});
      }
    return best;
  }

  /**
   * A near miss on the scale 2^e: the face (edge a) lies on the side x_k >=
   * Z of a plane of the coordinate k, touching it at a (a0), the vertex (edge
   * b) on the side x_k <= Z - h, h = tolerance (1 + 2^-j), j = 0, ..., 24,
   * rounded with Z - h (resampled unless it still exceeds the tolerance); at
   * the end points the distance h is reached at t = 0, at t = 1
   * or throughout. The vertex (edge b) passes close to a (a0) in the other
   * coordinates. With probability 1/2 all four points share one more
   * coordinate (coplanar motion; edges then possibly parallel).
   */
  NearMiss
  near_miss(std::mt19937_64 &rng, const bool edge_edge, const int e)
  {
    const auto uniform = [&](const Int lo, const Int hi) {
      return std::uniform_int_distribution<Int>(lo, hi)(rng);
    };
    const Int quarter = Int(1) << (e - 2);
    NearMiss  q;
    q.edge_edge          = edge_edge;
    const unsigned int k = uniform(0, 2), i = (k + 1) % 3, j = (k + 2) % 3;
    const bool         coplanar = uniform(0, 1) == 1;
    // Edges: parallel to each other and to the plane; face: parallel to the
    // plane (not together with coplanar, which would flatten it).
    const bool parallel = uniform(0, 3) == 0 && (edge_edge || !coplanar);
    // The separating plane x_k = Z and the near side's coordinate Z - h.
    const Int    z    = uniform(2 * quarter, 3 * quarter);
    const double gap  = tolerance * (1. + std::ldexp(1., -int(uniform(0, 24))));
    const double zp   = static_cast<double>(z) - gap;
    const Int    d    = uniform(1, quarter);
    const int    mode = uniform(0, 2);
    // Far side: a (a0) on the plane, the others at or beyond it.
    for (unsigned int p = (edge_edge ? 0 : 1); p < (edge_edge ? 2 : 4); ++p)
      {
        const bool on_plane = (p == (edge_edge ? 0u : 1u)) || parallel;
        q.start[p][k]       = q.end[p][k] =
          static_cast<double>(z + (on_plane ? 0 : uniform(0, quarter)));
      }
    // Near side: at Z - h at t = 0, at t = 1 or throughout; edge b translates
    // (parallel) or its second end lies farther.
    const Int b_extra = parallel ? 0 : uniform(0, quarter);
    for (unsigned int p = (edge_edge ? 2 : 0); p < (edge_edge ? 4 : 1); ++p)
      {
        const double extra = (p == 3) ? static_cast<double>(b_extra) : 0.;
        q.start[p][k] = zp - extra - (mode == 1 ? static_cast<double>(d) : 0.);
        q.end[p][k]   = zp - extra - (mode == 2 ? static_cast<double>(d) : 0.);
      }
    // The other coordinates: random on the scale 2^(e-1), the near side
    // passing by a (a0) in a straight line, a common translation.
    const Int half = 2 * quarter;
    const Int ti = uniform(-quarter, quarter), tj = uniform(-quarter, quarter);
    const double       c       = static_cast<double>(uniform(-half, half));
    const unsigned int far_ref = edge_edge ? 0 : 1;
    for (unsigned int p = 0; p < 4; ++p)
      {
        const bool near_side = edge_edge ? (p >= 2) : (p == 0);
        Int        x0        = uniform(-half / 2, half / 2),
            y0               = uniform(-half / 2, half / 2);
        if (near_side)
          {
            // Placed below after the far side is known.
            continue;
          }
        if (parallel && edge_edge && p != far_ref)
          {
            // Parallel to the first far point's line along j.
            x0 = static_cast<Int>(q.start[far_ref][i]);
          }
        q.start[p][i] = static_cast<double>(x0);
        q.start[p][j] = static_cast<double>(y0);
        q.end[p][i]   = static_cast<double>(x0 + ti);
        q.end[p][j]   = static_cast<double>(y0 + tj);
      }
    // Near side: the vertex (b0) passes by a (a0); b1 elsewhere, or parallel
    // to a (along j) when parallel.
    const Int r0 = uniform(-quarter, quarter), s0 = uniform(-quarter, quarter);
    const Int r1 = -r0 + uniform(-2, 2), s1 = -s0 + uniform(-2, 2);
    const Point3 &a0s = q.start[far_ref], &a0e = q.end[far_ref];
    for (unsigned int p = 0; p < 4; ++p)
      {
        const bool near_side = edge_edge ? (p >= 2) : (p == 0);
        if (!near_side)
          continue;
        Int di = 0, dj = 0;
        if (p == 3)
          {
            di = parallel ? 0 : uniform(-half / 2, half / 2);
            dj = uniform(-half / 2, half / 2);
          }
        q.start[p][i] = a0s[i] + static_cast<double>(r0 + di);
        q.start[p][j] = a0s[j] + static_cast<double>(s0 + dj);
        q.end[p][i]   = a0e[i] + static_cast<double>(r1 + di);
        q.end[p][j]   = a0e[j] + static_cast<double>(s1 + dj);
      }
    if (coplanar)
      for (auto *x : {&q.start, &q.end})
        for (Point3 &p : *x)
          p[i] = c;
    return q;
  }
} // namespace

// Pairs that never come within the tolerance (in the separating coordinate of
// F) by less than a unit in the last place up to the tolerance itself (the
// gap is between the tolerance and twice the tolerance), on the scales 2^24,
// 2^26 and 2^28 (where the round-off bound of the box ranges is 0.24, 0.95 and
// 3.8 times the tolerance), passing close by in the other coordinates, with
// the nearest distance at t = 0, at t = 1 or throughout: a hit would claim
// that they came within the tolerance, so a hit is allowed only if the
// iteration cap decided it.
TEST(CcdRounding, NearMissesAreNotContacts)
{
  std::mt19937_64 rng(1500);
  CcdSettings     settings;
  settings.max_iterations = 2000;
  for (const bool edge_edge : {false, true})
    {
      std::size_t n = 0, hits = 0, capped = 0, uncapped_hits = 0;
      for (unsigned int m = 0; m < 6000; ++m)
        {
          const int e = 24 + 2 * (m % 3);
          NearMiss  q;
          do
            q = near_miss(rng, edge_edge, e);
          while (!(separation(q) > tolerance));
          const CcdResult r = edge_edge ?
                                edge_edge_ccd(q.start, q.end, settings) :
                                vertex_face_ccd(q.start, q.end, settings);
          ++n;
          hits += r.hit;
          capped += r.capped;
          if (r.hit && !r.capped && ++uncapped_hits <= 5)
            ADD_FAILURE() << (edge_edge ? "edge-edge" : "vertex-face")
                          << " pair separated by "
                          << static_cast<double>(separation(q))
                          << " reported at t = " << r.time << ": "
                          << describe(q.start, q.end);
        }
      EXPECT_EQ(uncapped_hits, 0u);
      std::cout << (edge_edge ? "edge-edge" : "vertex-face")
                << " near misses: " << n << ", reported: " << hits
                << " (decided by the cap: " << capped
                << "), reported without the cap: " << uncapped_hits
                << std::endl;
    }
}
