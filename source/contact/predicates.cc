// The filters' error bounds assume that every operation is rounded separately:
// no contraction of a * b + c into a fused multiply-add by the compiler.
#pragma GCC optimize("fp-contract=off")

#include <estep/contact/predicates.h>

#include <cmath>
#include <vector>

namespace estep
{
  namespace contact
  {
    namespace
    {
      // Floating-point expansion arithmetic (Priest, Shewchuk): a number is an
      // unevaluated sum of doubles ordered by increasing magnitude and
      // non-overlapping; its sign is the sign of its last (largest) non-zero
      // component.
      using Expansion = std::vector<double>;

      // x + y = a + b exactly, x = fl(a + b) (Knuth's branch-free two-sum).
      inline void
      two_sum(const double a, const double b, double &x, double &y)
      {
        x               = a + b;
        const double bv = x - a;
        const double av = x - bv;
        const double br = b - bv;
        const double ar = a - av;
        y               = ar + br;
      }

      // x + y = a * b exactly, x = fl(a * b) (the fused multiply-add rounds
      // once).
      inline void
      two_product(const double a, const double b, double &x, double &y)
      {
        x = a * b;
        y = std::fma(a, b, -x);
      }

      // The difference a - b as an exact two-component expansion.
      Expansion
      difference(const double a, const double b)
      {
        double x, y;
        two_sum(a, -b, x, y);
        Expansion e;
        if (y != 0.)
          e.push_back(y);
        if (x != 0.)
          e.push_back(x);
        return e;
      }

      // e + b (Shewchuk's Grow-Expansion with zero elimination).
      Expansion
      grow(const Expansion &e, const double b)
      {
        Expansion h;
        h.reserve(e.size() + 1);
        double q = b;
        for (const double ei : e)
          {
            double s, r;
            two_sum(q, ei, s, r);
            if (r != 0.)
              h.push_back(r);
            q = s;
          }
        if (q != 0.)
          h.push_back(q);
        return h;
      }

      Expansion
      sum(const Expansion &e, const Expansion &f)
      {
        Expansion h = e;
        for (const double fi : f)
          h = grow(h, fi);
        return h;
      }

      Expansion
      negate(Expansion e)
      {
        for (double &x : e)
          x = -x;
        return e;
      }

      // e * b (Shewchuk's Scale-Expansion with zero elimination; two-sum
      // throughout).
      Expansion
      scale(const Expansion &e, const double b)
      {
        Expansion h;
        if (e.empty() || b == 0.)
          return h;
        h.reserve(2 * e.size());
        double q, r;
        two_product(e[0], b, q, r);
        if (r != 0.)
          h.push_back(r);
        for (std::size_t i = 1; i < e.size(); ++i)
          {
            double p, pe;
            two_product(e[i], b, p, pe);
            double s, t;
            two_sum(q, pe, s, t);
            if (t != 0.)
              h.push_back(t);
            two_sum(p, s, q, t);
            if (t != 0.)
              h.push_back(t);
          }
        if (q != 0.)
          h.push_back(q);
        return h;
      }

      Expansion
      product(const Expansion &e, const Expansion &f)
      {
        Expansion h;
        for (const double fi : f)
          h = sum(h, scale(e, fi));
        return h;
      }

      int
      sign(const Expansion &e)
      {
        for (auto it = e.rbegin(); it != e.rend(); ++it)
          if (*it != 0.)
            return (*it > 0.) ? 1 : -1;
        return 0;
      }

      constexpr double unit_roundoff = 1.1102230246251565e-16; // 2^-53
      constexpr double orient2d_bound =
        (3. + 16. * unit_roundoff) * unit_roundoff;
      constexpr double orient3d_bound =
        (7. + 56. * unit_roundoff) * unit_roundoff;
    } // namespace



    int
    orient2d_exact(const Point2 &a, const Point2 &b, const Point2 &c)
    {
      const Expansion bax = difference(b[0], a[0]);
      const Expansion bay = difference(b[1], a[1]);
      const Expansion cax = difference(c[0], a[0]);
      const Expansion cay = difference(c[1], a[1]);
      return sign(sum(product(bax, cay), negate(product(bay, cax))));
    }



    int
    orient2d(const Point2 &a, const Point2 &b, const Point2 &c)
    {
      // Shewchuk's evaluation order: det[a - c, b - c], which equals det[b - a,
      // c - a].
      const double detleft  = (a[0] - c[0]) * (b[1] - c[1]);
      const double detright = (a[1] - c[1]) * (b[0] - c[0]);
      const double det      = detleft - detright;
      const double errbound =
        orient2d_bound * (std::abs(detleft) + std::abs(detright));
      if (det > errbound)
        return 1;
      if (-det > errbound)
        return -1;
      return orient2d_exact(a, b, c);
    }



    int
    orient3d_exact(const Point3 &a,
                   const Point3 &b,
                   const Point3 &c,
                   const Point3 &d)
    {
      std::array<std::array<Expansion, 3>, 3> m;
      for (unsigned int k = 0; k < 3; ++k)
        {
          m[0][k] = difference(b[k], a[k]);
          m[1][k] = difference(c[k], a[k]);
          m[2][k] = difference(d[k], a[k]);
        }
      const Expansion minor0 =
        sum(product(m[1][1], m[2][2]), negate(product(m[1][2], m[2][1])));
      const Expansion minor1 =
        sum(product(m[1][2], m[2][0]), negate(product(m[1][0], m[2][2])));
      const Expansion minor2 =
        sum(product(m[1][0], m[2][1]), negate(product(m[1][1], m[2][0])));
      return sign(sum(sum(product(m[0][0], minor0), product(m[0][1], minor1)),
                      product(m[0][2], minor2)));
    }



    int
    orient3d(const Point3 &a, const Point3 &b, const Point3 &c, const Point3 &d)
    {
      // Shewchuk's orient3d(a, b, c, d) = det[a - d, b - d, c - d] evaluated in
      // his order, for which his bound holds; it is the negative of our
      // determinant.
      const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
      const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
      const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];

      const double bdxcdy = bdx * cdy;
      const double cdxbdy = cdx * bdy;
      const double cdxady = cdx * ady;
      const double adxcdy = adx * cdy;
      const double adxbdy = adx * bdy;
      const double bdxady = bdx * ady;

      const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) +
                         cdz * (adxbdy - bdxady);
      const double permanent =
        (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
        (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
        (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
      const double errbound = orient3d_bound * permanent;
      if (det > errbound)
        return -1;
      if (-det > errbound)
        return 1;
      return orient3d_exact(a, b, c, d);
    }
  } // namespace contact
} // namespace estep
