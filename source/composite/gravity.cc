// The error-free transformations of the compensated dot product assume that
// every operation is rounded separately: no contraction of a * b + c into a
// fused multiply-add by the compiler (the one fma below is explicit).
#pragma GCC optimize("fp-contract=off")

#include <estep/base/parallel_blocks.h>
#include <estep/composite/gravity.h>
#include <estep/systems/line_taylor_form.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace estep
{
  namespace
  {
    constexpr double epsilon = std::numeric_limits<double>::epsilon();
    constexpr double unit    = epsilon / 2.;

    /** Dot2 of a block of coordinates: its running sum, the errors of the
     * products and of the running sum, and sum_i |x_i y_i|. Blocks are
     * joined in order as Dot2 adds a product: the running sums by two-sum,
     * the errors plainly. */
    struct CompensatedDot
    {
      double sum = 0., error = 0., gross = 0.;

      /** Dot2 of @p x and @p y over the indices of @p range that are
       * @p phase modulo @p step: the others must have x_i = 0, whose terms
       * (a product, its error and its magnitude, all zeros) would change no
       * bit of sums that start at +0 (and so are never -0). */
      static CompensatedDot
      of(const Vector      &x,
         const Vector      &y,
         const BlockRange   range,
         const unsigned int step  = 1,
         const unsigned int phase = 0)
      {
        CompensatedDot dot;
        for (unsigned int i =
               range.begin + (phase + step - range.begin % step) % step;
             i < range.end;
             i += step)
          {
            const double product = x[i] * y[i];
            dot.error += std::fma(x[i], y[i], -product);
            dot.add_to_sum(product);
            dot.gross += std::abs(product);
          }
        return dot;
      }

      CompensatedDot &
      operator+=(const CompensatedDot &other)
      {
        error += other.error;
        add_to_sum(other.sum);
        gross += other.gross;
        return *this;
      }

      double
      value() const
      {
        return sum + error;
      }

    private:
      /** Knuth's two-sum: sum + x exactly, as the new sum and its error. */
      void
      add_to_sum(const double x)
      {
        const double t = sum + x;
        const double z = t - sum;
        error += (sum - (t - z)) + (x - z);
        sum = t;
      }
    };

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

    /**
     * The free flight of a Gravity system: f(s) = f_base(s) + l(s) with the
     * linear term l(s) = c0 + c1 s, c0 = -w . q and c1 = -w . v.
     *
     * The computed l(s) = fl(c0 + c1 s) (one fused multiply-add) is a
     * monotone function of s, since rounding is monotone; so are the sums
     * fl(f_base + l) in each argument. The enclosures are therefore:
     * - the sum of the base's enclosures and of the hull of l(a), l(b),
     *   widened by the rounding of l (2 units of round-off of its largest
     *   magnitude on [a, b]) and by the interval sums' own margin; the
     *   slope enclosure is the base's shifted by c1;
     * - where the base reports a sample p in [a, b]: intersected with the
     *   first-order form of the sum about p (LineTaylorForm::from_enclosure()
     *   of the base, with the base's value tolerance plus 64 units of
     *   round-off of its value at p, plus the exact form of l), whose value
     *   range follows the slope of the sum, f'_base + c1, not the sum of the
     *   two slopes' magnitudes: where the base's slope cancels the weight's
     *   (a body resting on a support) the enclosure stays narrow;
     * - the curvature is the base's (l'' = 0), the sample the base's sample
     *   point with f and f' there computed as value_and_derivative() does.
     *
     * value_tolerance(): the base's plus 8 units of round-off (of the double
     * precision epsilon) of sum_i |w_i q_i|: c0 and c1 are compensated dot
     * products, and energy() sums the linear term the same way, so that the
     * flight's l(s) and the linear term energy() computes at q + s v differ
     * from the exact -w . (q + s v) by about one unit of round-off of sum_i
     * |w_i x_i| each, near s = 0.
     */
    class GravityFlight : public FreeFlight
    {
    public:
      /** @p c0 = -w . q, @p c1 = -w . v, and @p magnitude_q =
       * sum_i |w_i q_i|. */
      GravityFlight(std::unique_ptr<FreeFlight> base_flight,
                    const double                c0,
                    const double                c1,
                    const double                magnitude_q)
        : base(std::move(base_flight))
        , c0(c0)
        , c1(c1)
        , linear_tolerance(8. * epsilon * magnitude_q)
      {}

      double
      value(const double s) const override
      {
        return base->value(s) + linear(s);
      }

      LineValue
      value_and_derivative(const double s) const override
      {
        return with_linear_term(s, base->value_and_derivative(s));
      }

      LineEnclosure
      enclose(const double a, const double b) const override
      {
        const double        base_tolerance = base->value_tolerance();
        const LineEnclosure e              = base->enclose(a, b);

        // The linear term over [a, b]: its computed values are monotone in s.
        const double   la = linear(a), lb = linear(b);
        const Interval l = Interval::hull(la, lb).widened(
          0., 2. * unit * std::max(std::abs(la), std::abs(lb)));
        LineEnclosure enclosure;
        enclosure.value      = e.value + l;
        enclosure.derivative = e.derivative + Interval::point(c1);
        enclosure.curvature  = e.curvature;

        const double p = e.sample_point;
        if (p >= a && p <= b)
          {
            enclosure.sample_point = p;
            enclosure.sample       = with_linear_term(p, e.sample);
            if (std::isfinite(e.sample.value) &&
                std::isfinite(e.sample.derivative))
              {
                // The first-order form of the sum about the sample.
                LineTaylorForm about_p;
                about_p.centre      = p;
                about_p.radius      = std::max(b - p, p - a) * (1. + 4. * unit);
                LineTaylorForm form = LineTaylorForm::from_enclosure(
                  p,
                  about_p.radius,
                  e.sample,
                  e,
                  base_tolerance + 64. * epsilon * std::abs(e.sample.value));
                LineTaylorForm linear_form = about_p;
                linear_form.value          = linear(p);
                linear_form.slope          = c1;
                // The rounding of l anywhere on [a, b].
                linear_form.value_error =
                  2. * unit * std::max(std::abs(la), std::abs(lb));
                form += linear_form;
                const LineEnclosure combined = form.enclosure();
                enclosure.value = intersection(enclosure.value, combined.value);
                enclosure.derivative =
                  intersection(enclosure.derivative, combined.derivative);
              }
          }
        return enclosure;
      }

      double
      value_tolerance() const override
      {
        return base->value_tolerance() + linear_tolerance;
      }

      double
      admissible_limit() const override
      {
        return base->admissible_limit();
      }

    private:
      /** l(s) = c0 + c1 s, rounded once. */
      double
      linear(const double s) const
      {
        return std::fma(c1, s, c0);
      }

      /** The base's value and slope at @p s plus the linear term's. */
      LineValue
      with_linear_term(const double s, const LineValue &base_value) const
      {
        return {base_value.value + linear(s), base_value.derivative + c1};
      }

      std::unique_ptr<FreeFlight> base;
      double                      c0, c1;
      double                      linear_tolerance;
    };
  } // namespace



  double
  compensated_dot(const Vector &x, const Vector &y, double *magnitude)
  {
    if (x.size() != y.size())
      throw std::invalid_argument(
        "compensated_dot: the vectors differ in size.");
    const unsigned int   n = x.size();
    const CompensatedDot dot =
      sum_over_blocks<CompensatedDot>(n_blocks(n), [&](const unsigned int b) {
        return CompensatedDot::of(x, y, block_range(b, n));
      });
    if (magnitude != nullptr)
      *magnitude = dot.gross;
    return dot.value();
  }



  Gravity::Gravity(std::shared_ptr<const MechanicalSystem> base,
                   const std::array<double, 3>            &acceleration,
                   const std::vector<unsigned int>        &weightless_points)
    : SystemDecorator(std::move(base))
    , g(acceleration)
  {
    shares_base_state      = true;
    const unsigned int dim = base_system->spatial_dimension();
    for (const double x : g)
      if (!std::isfinite(x))
        throw std::invalid_argument(
          "Gravity: the acceleration must be finite.");
    if (dim < 1 || dim > 3)
      throw std::invalid_argument("Gravity: the spatial dimension of <" +
                                  base_system->name() + "> is not 1, 2 or 3.");
    for (unsigned int c = dim; c < 3; ++c)
      if (g[c] != 0.)
        throw std::invalid_argument(
          "Gravity: the acceleration has a component beyond the spatial "
          "dimension of <" +
          base_system->name() + ">.");
    const Vector &inverse_mass = base_system->inverse_mass();
    if (inverse_mass.size() != base_system->n_dofs() ||
        base_system->n_dofs() % dim != 0)
      throw std::invalid_argument(
        "Gravity: the coordinates of <" + base_system->name() +
        "> are not point positions of its spatial dimension.");
    std::vector<bool> weightless(inverse_mass.size() / dim, false);
    for (const unsigned int p : weightless_points)
      {
        if (p >= weightless.size())
          throw std::invalid_argument(
            "Gravity: weightless point " + std::to_string(p) + " of <" +
            base_system->name() + "> does not exist.");
        weightless[p] = true;
      }
    w.reinit(inverse_mass.size());
    for (unsigned int i = 0; i < w.size(); ++i)
      {
        const double gc = g[i % dim];
        if (gc == 0. || weightless[i / dim])
          continue;
        if (!(inverse_mass[i] > 0.) || !std::isfinite(inverse_mass[i]))
          throw std::invalid_argument(
            "Gravity: coordinate " + std::to_string(i) + " of <" +
            base_system->name() +
            "> has no positive finite mass to give a weight.");
        w[i] = gc / inverse_mass[i];
      }
    // Gravity along one axis: the weights of the other coordinates are
    // zero, and the sums skip them.
    if (std::count(g.begin(), g.begin() + dim, 0.) == dim - 1)
      {
        step  = dim;
        phase = std::find_if(g.begin(),
                             g.end(),
                             [](const double x) { return x != 0.; }) -
                g.begin();
      }
  }



  const std::array<double, 3> &
  Gravity::acceleration() const
  {
    return g;
  }



  const Vector &
  Gravity::weights() const
  {
    return w;
  }



  double
  Gravity::gravitational_potential(const Vector &q) const
  {
    return -compensated_dot(w, q);
  }



  double
  Gravity::weighted_sum(const Vector &x, double *magnitude) const
  {
    const unsigned int   n   = x.size();
    const CompensatedDot dot = sum_over_coordinate_blocks<CompensatedDot>(
      *this, [&](const unsigned int b) {
        return CompensatedDot::of(w, x, block_range(b, n), step, phase);
      });
    if (magnitude != nullptr)
      *magnitude = dot.gross;
    return dot.value();
  }



  double
  Gravity::energy(const Vector &q) const
  {
    const double V = base_system->energy(q);
    // Collective where the state is shared: every rank sums, whatever V.
    const double W = weighted_sum(q);
    if (!std::isfinite(V))
      return V;
    return V - W;
  }



  void
  Gravity::gradient(const Vector &q, Vector &grad) const
  {
    base_system->gradient(q, grad);
    grad -= w;
  }



  void
  Gravity::kept_gradient(const Vector &q, Vector &grad) const
  {
    base_kept_gradient(q, grad);
    for_each_kept_range(*this, [&](const BlockRange range) {
      for (unsigned int i = range.begin; i < range.end; ++i)
        grad[i] -= w[i];
    });
  }



  std::unique_ptr<FreeFlight>
  Gravity::free_flight(const Vector &q, const Vector &v) const
  {
    double       magnitude_q = 0.;
    const double c0          = -weighted_sum(q, &magnitude_q);
    const double c1          = -weighted_sum(v);
    return std::make_unique<GravityFlight>(base_system->free_flight(q, v),
                                           c0,
                                           c1,
                                           magnitude_q);
  }



  std::vector<std::string>
  Gravity::observable_names() const
  {
    std::vector<std::string> names = base_system->observable_names();
    names.emplace_back("gravitational_potential");
    return names;
  }



  std::vector<double>
  Gravity::observables(const Vector &q, const Vector &v) const
  {
    std::vector<double> values = base_system->observables(q, v);
    values.push_back(gravitational_potential(q));
    return values;
  }
} // namespace estep
