// The end positions of a flight are computed here as the integrator computes
// them (q.add(s, v): x + s v rounded twice), and once more with a fused
// multiply-add; the compiler must not fuse the first on its own.
#pragma GCC optimize("fp-contract=off")

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <estep/base/distributed_blocks.h>
#include <estep/composite/contact_system.h>
#include <estep/composite/half_space_obstacles.h>
#include <estep/systems/line_taylor_form.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    constexpr double epsilon  = std::numeric_limits<double>::epsilon();

    /** The touching band in units of round-off (see the class). */
    constexpr double band_units = 16.;

    /** The common part of two enclosures of the same quantity (their hull
     * if they do not overlap, which valid enclosures always do). */
    Interval
    intersection(const Interval &x, const Interval &y)
    {
      const Interval common = {std::max(x.lower, y.lower),
                               std::min(x.upper, y.upper)};
      if (common.lower <= common.upper)
        return common;
      return {std::min(x.lower, y.lower), std::max(x.upper, y.upper)};
    }

    bool
    bounded(const Interval &x)
    {
      return std::isfinite(x.lower) && std::isfinite(x.upper);
    }

    /** n . (x - p), summed over the components in order: the one evaluation
     * of the signed distance. */
    inline double
    distance(const double *x, const HalfSpace &plane, const unsigned int dim)
    {
      double d = 0.;
      for (unsigned int c = 0; c < dim; ++c)
        d += plane.normal[c] * (x[c] - plane.point[c]);
      return d;
    }

    /** n . w, summed in order. */
    inline double
    rate(const double *w, const HalfSpace &plane, const unsigned int dim)
    {
      double r = 0.;
      for (unsigned int c = 0; c < dim; ++c)
        r += plane.normal[c] * w[c];
      return r;
    }

    /** The largest magnitude of a coordinate of x. */
    inline double
    max_abs(const double *x, const unsigned int dim)
    {
      double m = 0.;
      for (unsigned int c = 0; c < dim; ++c)
        m = std::max(m, std::abs(x[c]));
      return m;
    }

    /** The touching band of @p plane for a point whose coordinates have
     * magnitudes up to @p x_max. */
    inline double
    band(const HalfSpace &plane, const double x_max, const unsigned int dim)
    {
      double n1 = 0.;
      for (unsigned int c = 0; c < dim; ++c)
        n1 += std::abs(plane.normal[c]);
      return band_units * epsilon * n1 *
             (x_max + max_abs(plane.point.data(), dim));
    }

    /**
     * Whether the point x moved to x + s w lies at least its touching band
     * in front of @p plane, with the end position computed as the integrator
     * computes it (x + s w, rounded twice) and with a fused multiply-add. The
     * band is taken for the largest coordinate along the segment (at one of
     * its ends), so that the point is in front of the plane on the whole
     * segment as computed.
     */
    inline bool
    ends_in_front(const double      *x,
                  const double      *w,
                  const double       s,
                  const HalfSpace   &plane,
                  const unsigned int dim)
    {
      double rounded[3], fused[3];
      double x_max = max_abs(x, dim);
      for (unsigned int c = 0; c < dim; ++c)
        {
          const double displacement = s * w[c];
          rounded[c]                = x[c] + displacement;
          fused[c]                  = std::fma(s, w[c], x[c]);
          x_max = std::max({x_max, std::abs(rounded[c]), std::abs(fused[c])});
        }
      const double required = band(plane, x_max, dim);
      return distance(rounded, plane, dim) >= required &&
             distance(fused, plane, dim) >= required;
    }

    /**
     * Step @p s down until ends_in_front() (or to 0): first to the next
     * smaller double, then by a step that doubles after each try.
     */
    inline double
    step_down(double             s,
              const double      *x,
              const double      *w,
              const HalfSpace   &plane,
              const unsigned int dim)
    {
      double decrement = s - std::nextafter(s, 0.);
      while (s > 0. && !ends_in_front(x, w, s, plane, dim))
        {
          s = (s > decrement) ? s - decrement : 0.;
          decrement *= 2.;
        }
      return s;
    }

    /** The penalty term of one point and plane along a flight:
     * d(s) = d0 + s rate, with bounds on the round-off of d0 and rate. */
    struct PenaltyPair
    {
      double d0;
      double rate;
      double d0_error;
      double rate_error;

      /** d(s) as every evaluation along the flight computes it. */
      double
      distance_at(const double s) const
      {
        return d0 + s * rate;
      }

      /** A bound on |computed d(s) - exact d(s)| for |s| <= s_abs. */
      double
      distance_error(const double s_abs) const
      {
        return d0_error + s_abs * rate_error +
               2. * epsilon * (std::abs(d0) + s_abs * std::abs(rate));
      }
    };

    /** The free flight of HalfSpaceObstacles in penalty mode. */
    class ObstacleFreeFlight : public FreeFlight
    {
    public:
      ObstacleFreeFlight(std::unique_ptr<FreeFlight>      base_flight,
                         const std::vector<HalfSpace>    &planes,
                         const std::vector<unsigned int> &points,
                         const unsigned int               dim,
                         const double                     eps,
                         const Vector                    &q,
                         const Vector                    &v)
        : base(std::move(base_flight))
        , inv_eps(1. / eps)
        , half_inv_eps(0.5 / eps)
      {
        for (const HalfSpace &plane : planes)
          for (const unsigned int i : points)
            {
              const double *x = q.data() + dim * i, *w = v.data() + dim * i;
              PenaltyPair   pair;
              pair.d0       = distance(x, plane, dim);
              pair.rate     = rate(w, plane, dim);
              double x_size = 0., w_size = 0.;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  x_size += std::abs(plane.normal[c]) *
                            (std::abs(x[c]) + std::abs(plane.point[c]));
                  w_size += std::abs(plane.normal[c]) * std::abs(w[c]);
                }
              // At most dim + 1 roundings in each (difference, products,
              // sums): 4 epsilon = 8 units covers dim <= 3 with room.
              pair.d0_error   = 4. * epsilon * x_size;
              pair.rate_error = 4. * epsilon * w_size;
              // A pair that stays in front for every s >= 0 (computed and
              // exact) contributes nothing to the flight.
              if (pair.d0 - pair.d0_error >= 0. &&
                  pair.rate - pair.rate_error >= 0.)
                continue;
              pairs.push_back(pair);
            }
        // The round-off of I at s = 0 (value_error of the pairs' forms at
        // s = 0, plus the summation).
        double sum = 0.;
        for (const PenaltyPair &p : pairs)
          {
            const double e = p.distance_error(0.);
            const double u = std::max(0., -(p.d0 - e));
            if (u == 0.)
              continue;
            penalty_tolerance += e * u * inv_eps * (1. + 4. * epsilon) +
                                 8. * epsilon * u * u * half_inv_eps;
            sum += u * u * half_inv_eps;
          }
        penalty_tolerance +=
          2. * epsilon * static_cast<double>(pairs.size()) * sum;
      }

      double
      value(const double s) const override
      {
        const double b = base->value(s);
        if (!std::isfinite(b))
          return infinity;
        return b + penalty_value(s);
      }

      LineValue
      value_and_derivative(const double s) const override
      {
        LineValue total = base->value_and_derivative(s);
        if (!std::isfinite(total.value))
          return {infinity, total.derivative};
        const LineValue p = penalty_value_and_derivative(s);
        total.value += p.value;
        total.derivative += p.derivative;
        return total;
      }

      LineEnclosure
      enclose(const double a, const double b) const override
      {
        const LineEnclosure base_enclosure = base->enclose(a, b);
        LineTaylorForm      form = LineTaylorForm::about_centre_of(a, b);
        const double        m = form.centre, r = form.radius;
        const double        lo = m - r, hi = m + r;
        const double        s_abs = std::max(std::abs(lo), std::abs(hi));

        // The pairs that may penetrate on [lo, hi]: their second-order forms
        // about m and their exact ranges.
        LineTaylorForm penalty_form = LineTaylorForm::about_centre_of(a, b);
        Interval       value = {0., 0.}, slope = {0., 0.}, curvature = {0., 0.};
        bool           active = false;
        for (const PenaltyPair &p : pairs)
          {
            // Computed d is monotone in s (each rounding is), so it lies
            // between its values at the ends; the exact d within the error.
            const double   d_lo = p.distance_at(lo), d_hi = p.distance_at(hi);
            const double   error = p.distance_error(s_abs);
            const Interval d     = {std::min(d_lo, d_hi) - error,
                                    std::max(d_lo, d_hi) + error};
            if (d.lower >= 0.)
              continue;
            active = true;
            // u = max(0, -d) >= 0 and the rate (exact and computed).
            const double   u_lo      = std::max(0., -d.upper);
            const double   u_hi      = std::max(0., -d.lower);
            const Interval u         = {u_lo, u_hi};
            const Interval rate      = {p.rate - p.rate_error,
                                        p.rate + p.rate_error};
            const double   rate_high = std::abs(p.rate) + p.rate_error;
            const double   rate_low =
              std::max(0., std::abs(p.rate) - p.rate_error);

            // Value u^2 / (2 eps) and slope -u rate / eps are monotone in s:
            // their ranges are those of u.
            value +=
              Interval{u_lo * u_lo * half_inv_eps, u_hi * u_hi * half_inv_eps}
                .widened(8. * epsilon);
            slope += ((-inv_eps) * (u * rate)).widened(4. * epsilon);
            // Curvature rate^2 / eps where behind, 0 where in front: the
            // lower bound is 0 unless the point is behind throughout (the
            // kink, where it crosses the plane, may lie in the interval).
            const bool     behind_throughout = d.upper < 0.;
            const Interval c                 = {behind_throughout ?
                                                  rate_low * rate_low * inv_eps *
                                                    (1. - 8. * epsilon) :
                                                  0.,
                                rate_high * rate_high * inv_eps *
                                  (1. + 8. * epsilon)};
            curvature += c;

            // The pair's form: computed value and slope at m, curvature c,
            // no kink term (the term is C^1), and the round-off bounds of
            // |computed - exact| over the interval.
            const double   dm = p.distance_at(m);
            LineTaylorForm f  = LineTaylorForm::about_centre_of(a, b);
            if (dm < 0.)
              {
                f.value = dm * dm * half_inv_eps;
                f.slope = dm * p.rate * inv_eps;
              }
            f.curvature   = c;
            f.value_error = error * u_hi * inv_eps * (1. + 4. * epsilon) +
                            8. * epsilon * u_hi * u_hi * half_inv_eps;
            f.slope_error = (error * std::abs(p.rate) + u_hi * p.rate_error) *
                              inv_eps * (1. + 4. * epsilon) +
                            8. * epsilon * u_hi * std::abs(p.rate) * inv_eps;
            penalty_form += f;
          }
        if (!active)
          return base_enclosure;

        // The base's first-order form from its enclosure, plus the pairs'.
        LineValue at_m = base_enclosure.sample_point == m ?
                           base_enclosure.sample :
                           base->value_and_derivative(m);
        form += LineTaylorForm::from_enclosure(m,
                                               r,
                                               at_m,
                                               base_enclosure,
                                               base->value_tolerance() +
                                                 64. * epsilon *
                                                   std::abs(at_m.value));
        form += penalty_form;
        const LineEnclosure combined = form.enclosure();

        LineEnclosure enclosure;
        enclosure.value =
          intersection(combined.value, base_enclosure.value + value);
        enclosure.derivative =
          intersection(combined.derivative, base_enclosure.derivative + slope);
        if (bounded(base_enclosure.curvature))
          enclosure.curvature = base_enclosure.curvature + curvature;
        // V and V' at m as value_and_derivative() computes them.
        if (std::isfinite(at_m.value))
          {
            const LineValue p = penalty_value_and_derivative(m);
            at_m.value += p.value;
            at_m.derivative += p.derivative;
          }
        else
          at_m.value = infinity;
        if (m >= a && m <= b)
          {
            enclosure.sample_point = m;
            enclosure.sample       = at_m;
          }
        return enclosure;
      }

      double
      value_tolerance() const override
      {
        return base->value_tolerance() + penalty_tolerance;
      }

      double
      admissible_limit() const override
      {
        return base->admissible_limit();
      }

    private:
      double
      penalty_value(const double s) const
      {
        double sum = 0.;
        for (const PenaltyPair &p : pairs)
          {
            const double d = p.distance_at(s);
            if (d < 0.)
              sum += d * d * half_inv_eps;
          }
        return sum;
      }

      LineValue
      penalty_value_and_derivative(const double s) const
      {
        LineValue sum = {0., 0.};
        for (const PenaltyPair &p : pairs)
          {
            const double d = p.distance_at(s);
            if (d < 0.)
              {
                sum.value += d * d * half_inv_eps;
                sum.derivative += d * p.rate * inv_eps;
              }
          }
        return sum;
      }

      std::unique_ptr<FreeFlight> base;
      std::vector<PenaltyPair>    pairs;
      double                      inv_eps;
      double                      half_inv_eps;
      double                      penalty_tolerance = 0.;
    };
  } // namespace



  HalfSpaceObstacles::HalfSpaceObstacles(
    std::shared_ptr<const MechanicalSystem> base,
    std::vector<HalfSpace>                  half_spaces,
    std::vector<unsigned int>               points_in,
    const Mode                              mode,
    const double                            penalty_parameter,
    const double                            penetration_limit)
    : SystemDecorator(std::move(base))
    , planes(std::move(half_spaces))
    , contact_points(std::move(points_in))
    , obstacle_mode(mode)
    , eps(mode == Mode::penalty ? penalty_parameter : 0.)
    , depth_limit(penetration_limit)
    , dim(base_system->spatial_dimension())
  {
    if (dim == 0 || dim > 3 || base_system->n_dofs() % dim != 0)
      throw std::invalid_argument(
        "HalfSpaceObstacles: the base's coordinates are not points of its "
        "spatial dimension");
    for (HalfSpace &plane : planes)
      {
        double norm = 0.;
        for (unsigned int c = 0; c < 3; ++c)
          {
            if (!std::isfinite(plane.normal[c]) ||
                !std::isfinite(plane.point[c]))
              throw std::invalid_argument(
                "HalfSpaceObstacles: a half-space is not finite");
            if (c < dim)
              norm += plane.normal[c] * plane.normal[c];
          }
        if (dim < 3 && plane.normal[2] != 0.)
          throw std::invalid_argument(
            "HalfSpaceObstacles: a normal leaves the plane of a 2D system");
        norm = std::sqrt(norm);
        if (!(norm > 0.))
          throw std::invalid_argument(
            "HalfSpaceObstacles: a half-space has a zero normal");
        for (unsigned int c = 0; c < 3; ++c)
          plane.normal[c] = (c < dim) ? plane.normal[c] / norm : 0.;
      }
    std::sort(contact_points.begin(), contact_points.end());
    contact_points.erase(std::unique(contact_points.begin(),
                                     contact_points.end()),
                         contact_points.end());
    if (!contact_points.empty() &&
        contact_points.back() >= base_system->n_dofs() / dim)
      throw std::invalid_argument("HalfSpaceObstacles: point " +
                                  std::to_string(contact_points.back()) +
                                  " out of range");
    if (mode == Mode::penalty &&
        !(penalty_parameter > 0. && std::isfinite(penalty_parameter)))
      throw std::invalid_argument(
        "HalfSpaceObstacles: the penalty parameter must be positive");
    // The obstacles read the contact points alone: the state can be shared
    // as the base shares it if every rank keeps all of them.
    if (rank_count() > 1)
      {
        bool every = false;
        if (const std::vector<BlockRange> *kept =
              base_system->kept_coordinates())
          {
            std::vector<char> is_kept(base_system->n_dofs(), 0);
            for (const BlockRange range : *kept)
              std::fill(is_kept.begin() + range.begin,
                        is_kept.begin() + range.end,
                        1);
            every =
              std::all_of(contact_points.begin(),
                          contact_points.end(),
                          [&](const unsigned int p) {
                            return std::count(is_kept.begin() + dim * p,
                                              is_kept.begin() + dim * (p + 1),
                                              1) == std::ptrdiff_t(dim);
                          });
          }
        shares_base_state = largest_over_ranks(every ? 0 : 1) == 0;
      }
  }



  HalfSpaceObstacles::~HalfSpaceObstacles() = default;



  double
  HalfSpaceObstacles::energy(const Vector &q) const
  {
    const double V = base_system->energy(q);
    if (obstacle_mode != Mode::penalty || !std::isfinite(V))
      return V;
    return V + obstacle_energy(q);
  }



  void
  HalfSpaceObstacles::gradient(const Vector &q, Vector &g) const
  {
    base_system->gradient(q, g);
    add_obstacle_gradient(q, g);
  }



  void
  HalfSpaceObstacles::kept_gradient(const Vector &q, Vector &g) const
  {
    base_kept_gradient(q, g);
    add_obstacle_gradient(q, g);
  }



  void
  HalfSpaceObstacles::add_obstacle_gradient(const Vector &q, Vector &g) const
  {
    if (obstacle_mode != Mode::penalty)
      return;
    const double inv_eps = 1. / eps;
    for (const HalfSpace &plane : planes)
      for (const unsigned int i : contact_points)
        {
          const double d = distance(q.data() + dim * i, plane, dim);
          if (d < 0.)
            for (unsigned int c = 0; c < dim; ++c)
              g[dim * i + c] += d * inv_eps * plane.normal[c];
        }
  }



  std::unique_ptr<FreeFlight>
  HalfSpaceObstacles::free_flight(const Vector &q, const Vector &v) const
  {
    auto base_flight = base_system->free_flight(q, v);
    if (obstacle_mode != Mode::penalty)
      return base_flight;
    return std::make_unique<ObstacleFreeFlight>(
      std::move(base_flight), planes, contact_points, dim, eps, q, v);
  }



  bool
  HalfSpaceObstacles::has_constraints() const
  {
    return obstacle_mode == Mode::impenetrability ||
           base_system->has_constraints();
  }



  std::optional<ConstraintEvent>
  HalfSpaceObstacles::first_constraint_event(const Vector &q,
                                             const Vector &v,
                                             const double  s_max) const
  {
    if (obstacle_mode != Mode::impenetrability)
      return base_system->first_constraint_event(q, v, s_max);
    if (!(s_max >= 0.))
      throw std::invalid_argument(
        "HalfSpaceObstacles::first_constraint_event: s_max must be >= 0");

    double       best      = s_max;
    bool         found     = false;
    unsigned int hit_point = 0, hit_plane = 0;
    for (unsigned int k = 0; k < planes.size() && !(found && best == 0.); ++k)
      for (const unsigned int i : contact_points)
        {
          const HalfSpace &plane = planes[k];
          const double    *x = q.data() + dim * i, *w = v.data() + dim * i;
          const double     r = rate(w, plane, dim);
          // Moving out or parallel: never a contact, even behind.
          if (!(r < 0.))
            continue;
          const double d0 = distance(x, plane, dim);
          double       s  = 0.;
          if (d0 < 4. * band(plane, max_abs(x, dim), dim))
            // On the plane, behind it or within round-off of it, moving
            // in: a contact now.
            s = 0.;
          else
            {
              const double crossing = d0 / (-r);
              if (crossing <= best)
                s = step_down(crossing, x, w, plane, dim);
              else
                {
                  // Beyond the flight, unless round-off would leave the
                  // point closer than its band at the end.
                  if (!std::isfinite(best) ||
                      ends_in_front(x, w, best, plane, dim))
                    continue;
                  s = step_down(best, x, w, plane, dim);
                }
            }
          if (!found || s < best)
            {
              best      = s;
              found     = true;
              hit_point = i;
              hit_plane = k;
              if (s == 0.)
                break;
            }
        }

    // The base's event, if it comes before (ties go to the obstacle).
    auto base_event =
      base_system->first_constraint_event(q, v, found ? best : s_max);
    if (base_event && (!found || base_event->s < best))
      return base_event;
    if (!found)
      return std::nullopt;
    ConstraintEvent event;
    event.s = best;
    event.normal.reinit(q.size());
    for (unsigned int c = 0; c < dim; ++c)
      event.normal[dim * hit_point + c] = planes[hit_plane].normal[c];
    return event;
  }



  std::vector<SparseNormal>
  HalfSpaceObstacles::touching_constraints(const Vector &q) const
  {
    std::vector<SparseNormal> normals = base_system->touching_constraints(q);
    if (obstacle_mode != Mode::impenetrability)
      return normals;
    for (const HalfSpace &plane : planes)
      for (const unsigned int i : contact_points)
        {
          const double *x = q.data() + dim * i;
          if (distance(x, plane, dim) < 4. * band(plane, max_abs(x, dim), dim))
            {
              SparseNormal &normal = normals.emplace_back();
              for (unsigned int c = 0; c < dim; ++c)
                normal.emplace_back(dim * i + c, plane.normal[c]);
            }
        }
    return normals;
  }



  void
  HalfSpaceObstacles::hessian(const Vector                 &q,
                              dealii::SparseMatrix<double> &H) const
  {
    base_system->hessian(q, H);
    if (obstacle_mode != Mode::penalty)
      return;
    const double                   inv_eps  = 1. / eps;
    const dealii::SparsityPattern &sparsity = H.get_sparsity_pattern();
    for (const HalfSpace &plane : planes)
      for (const unsigned int i : contact_points)
        if (distance(q.data() + dim * i, plane, dim) < 0.)
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int e = 0; e < dim; ++e)
              {
                if (!sparsity.exists(dim * i + c, dim * i + e))
                  throw std::logic_error(
                    "HalfSpaceObstacles::hessian: the base's sparsity "
                    "pattern lacks the block of point " +
                    std::to_string(i));
                H.add(dim * i + c,
                      dim * i + e,
                      plane.normal[c] * plane.normal[e] * inv_eps);
              }
  }



  std::vector<std::string>
  HalfSpaceObstacles::observable_names() const
  {
    std::vector<std::string> names = base_system->observable_names();
    names.emplace_back("points_behind_obstacles");
    return names;
  }



  std::vector<double>
  HalfSpaceObstacles::observables(const Vector &q, const Vector &v) const
  {
    std::vector<double> values = base_system->observables(q, v);
    values.push_back(n_points_behind(q));
    return values;
  }



  HalfSpaceObstacles::Mode
  HalfSpaceObstacles::mode() const
  {
    return obstacle_mode;
  }



  double
  HalfSpaceObstacles::penalty_parameter() const
  {
    return eps;
  }



  const std::vector<HalfSpace> &
  HalfSpaceObstacles::half_spaces() const
  {
    return planes;
  }



  const std::vector<unsigned int> &
  HalfSpaceObstacles::points() const
  {
    return contact_points;
  }



  std::string
  HalfSpaceObstacles::penetration(const Vector &q) const
  {
    if (std::string base = base_system->penetration(q); !base.empty())
      return base;
    const auto found = first_point_deeper_than(q, depth_limit);
    if (!found)
      return "";
    std::ostringstream text;
    text << "a boundary point (point " << found->point << ") lies "
         << found->depth << " behind half-space " << found->half_space + 1
         << ", deeper than the longest boundary edge " << depth_limit
         << " of the meshes; the penalty (Contact/Penalty parameter = " << eps
         << ", smaller is stiffer) is too soft to hold it out.";
    return text.str();
  }



  std::optional<HalfSpaceObstacles::PointBehind>
  HalfSpaceObstacles::first_point_deeper_than(const Vector &q,
                                              const double  depth) const
  {
    for (const unsigned int i : contact_points)
      for (unsigned int k = 0; k < planes.size(); ++k)
        if (const double d = -signed_distance(q, i, k); d > depth)
          return PointBehind{i, k, d};
    return std::nullopt;
  }



  double
  HalfSpaceObstacles::signed_distance(const Vector      &q,
                                      const unsigned int point,
                                      const unsigned int k) const
  {
    return distance(q.data() + dim * point, planes.at(k), dim);
  }



  double
  HalfSpaceObstacles::touching_band(const Vector      &q,
                                    const unsigned int point,
                                    const unsigned int k) const
  {
    return band(planes.at(k), max_abs(q.data() + dim * point, dim), dim);
  }



  unsigned int
  HalfSpaceObstacles::n_points_behind(const Vector &q) const
  {
    unsigned int count = 0;
    for (const unsigned int i : contact_points)
      for (const HalfSpace &plane : planes)
        if (distance(q.data() + dim * i, plane, dim) < 0.)
          {
            ++count;
            break;
          }
    return count;
  }



  double
  HalfSpaceObstacles::max_penetration(const Vector &q) const
  {
    double depth = 0.;
    for (const unsigned int i : contact_points)
      for (const HalfSpace &plane : planes)
        depth = std::max(depth, -distance(q.data() + dim * i, plane, dim));
    return depth;
  }



  double
  HalfSpaceObstacles::obstacle_energy(const Vector &q) const
  {
    if (obstacle_mode != Mode::penalty)
      return 0.;
    const double half_inv_eps = 0.5 / eps;
    double       sum          = 0.;
    for (const HalfSpace &plane : planes)
      for (const unsigned int i : contact_points)
        {
          const double d = distance(q.data() + dim * i, plane, dim);
          if (d < 0.)
            sum += d * d * half_inv_eps;
        }
    return sum;
  }



  std::vector<unsigned int>
  boundary_points(const ContactSystem &system)
  {
    std::vector<unsigned int> points;
    const auto               &triangles = system.boundary_triangles();
    for (unsigned int t = 0; t < triangles.size(); ++t)
      if (system.triangle_bodies()[t] < system.n_bodies())
        points.insert(points.end(), triangles[t].begin(), triangles[t].end());
    std::sort(points.begin(), points.end());
    points.erase(std::unique(points.begin(), points.end()), points.end());
    return points;
  }
} // namespace estep
