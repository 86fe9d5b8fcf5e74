#include <estep/base/distributed_blocks.h>
#include <estep/base/ghost_exchange.h>
#include <estep/base/parallel_blocks.h>
#include <estep/composite/contact_system.h>
#include <estep/contact/first_contact.h>
#include <estep/contact/penalty_contact.h>
#include <estep/contact/penalty_flight.h>
#include <estep/contact/point_in_surface.h>
#include <estep/contact/triangle_intersection.h>
#include <estep/fem/elastic_body.h>
#include <estep/fem/elastic_free_flight.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    constexpr double epsilon  = std::numeric_limits<double>::epsilon();

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
     * work(b) for every body b < @p n_bodies. On one process the bodies run
     * side by side on the threads: each body's evaluation touches only its
     * own data, and every caller combines the bodies' results in body order
     * afterwards, so the bits do not depend on the threads. On several
     * processes in body order, one after the other: each body's loops end in
     * collective calls, which every process must make in the same order.
     */
    void
    for_each_body(const unsigned int                       n_bodies,
                  const std::function<void(unsigned int)> &work)
    {
      if (rank_count() > 1)
        {
          for (unsigned int b = 0; b < n_bodies; ++b)
            work(b);
          return;
        }
      for_each_block(n_bodies, work);
    }

    /** part(b) of every body b < @p n_bodies, computed by for_each_body(), in
     * body order. */
    template <typename T, typename Part>
    std::vector<T>
    body_parts(const unsigned int n_bodies, const Part &part)
    {
      std::vector<T> parts(n_bodies);
      for_each_body(n_bodies,
                    [&](const unsigned int b) { parts[b] = part(b); });
      return parts;
    }

    /** The free flight of a ContactSystem: the bodies' flights plus the
     * penalty flight. */
    class ContactFreeFlight : public FreeFlight
    {
    public:
      ContactFreeFlight(const ContactSystem           &system,
                        const contact::PenaltyContact *penalty,
                        const Vector                  &q,
                        const Vector                  &v)
        : bodies(system.n_bodies())
      {
        for_each_body(bodies.size(), [&](const unsigned int b) {
          bodies[b] = system.body(b).make_free_flight(system.extract(q, b),
                                                      system.extract(v, b));
        });
        if (penalty != nullptr)
          penalty_flight = std::make_unique<contact::PenaltyFlight>(*penalty,
                                                                    q.data(),
                                                                    v.data(),
                                                                    q.size());
      }

      double
      value(const double s) const override
      {
        double total = 0.;
        for (const double value :
             body_parts<double>(bodies.size(), [&](const unsigned int b) {
               return bodies[b]->value(s);
             }))
          total += value;
        if (!std::isfinite(total))
          return infinity;
        if (penalty_flight)
          total += penalty_flight->value(s);
        return total;
      }

      LineValue
      value_and_derivative(const double s) const override
      {
        LineValue total = {0., 0.};
        for (const LineValue &l :
             body_parts<LineValue>(bodies.size(), [&](const unsigned int b) {
               return bodies[b]->value_and_derivative(s);
             }))
          {
            total.value += l.value;
            total.derivative += l.derivative;
          }
        if (!std::isfinite(total.value))
          return {infinity, total.derivative};
        if (penalty_flight)
          {
            const auto [value, slope] = penalty_flight->value_and_derivative(s);
            total.value += value;
            total.derivative += slope;
          }
        return total;
      }

      /**
       * One second-order form of the whole V about the centre of [a, b]: the
       * values and slopes of the parts at the centre are added before any
       * interval is formed (where the slopes of the parts are large and of
       * opposite signs, a sum of separate enclosures is wide), then their
       * curvature and slope offset intervals. The bodies enter with the
       * first-order form of their enclosures
       * (LineTaylorForm::from_enclosure()). The result is intersected with the
       * sum of the parts' own enclosures, which is tighter where no slopes
       * cancel (the bodies' enclosures keep the sign of their curvature).
       *
       * The enclosure also reports what the search's convexity rules and its
       * location of crossings use: the sum of the parts' bounds on f'' (the
       * bodies' enclosures' curvature, the penalty form's C where it has no
       * kink; unbounded if a part has none), and V and V' at the centre as
       * value_and_derivative() computes them (the bodies' samples there,
       * which their enclosures took at the same centre, plus the penalty's
       * value and slope).
       */
      LineEnclosure
      enclose(const double a, const double b) const override
      {
        LineTaylorForm form      = LineTaylorForm::about_centre_of(a, b);
        const double   m         = form.centre;
        LineEnclosure  sum       = {{0., 0.}, {0., 0.}};
        Interval       curvature = {0., 0.};
        LineValue      at_m      = {0., 0.};
        // Each body's enclosure and its value at the centre, then their sum
        // in body order.
        std::vector<LineEnclosure> parts(bodies.size());
        std::vector<LineValue>     at_centres(bodies.size());
        for_each_body(bodies.size(), [&](const unsigned int k) {
          parts[k]      = bodies[k]->enclose(a, b);
          at_centres[k] = parts[k].sample_point == m ?
                            parts[k].sample :
                            bodies[k]->value_and_derivative(m);
        });
        for (unsigned int k = 0; k < bodies.size(); ++k)
          {
            const auto          &f         = bodies[k];
            const LineEnclosure &e         = parts[k];
            const LineValue     &at_centre = at_centres[k];
            sum.value += e.value;
            sum.derivative += e.derivative;
            curvature += e.curvature;
            at_m.value += at_centre.value;
            at_m.derivative += at_centre.derivative;
            // The round-off of a body's values: its tolerance at s = 0 plus
            // 64 epsilon of the value (the margin of its own enclosures).
            form += LineTaylorForm::from_enclosure(
              form.centre,
              form.radius,
              at_centre,
              e,
              f->value_tolerance() + 64. * epsilon * std::abs(at_centre.value));
          }
        if (!std::isfinite(at_m.value))
          at_m.value = infinity;
        if (penalty_flight)
          {
            const LineTaylorForm p = penalty_flight->taylor_form(a, b);
            const LineEnclosure  e = p.enclosure();
            sum.value += e.value;
            sum.derivative += e.derivative;
            curvature += e.curvature;
            form += p;
            // Without candidate pairs on [a, b] the penalty is 0 at m.
            if (std::isfinite(at_m.value) &&
                penalty_flight->n_candidate_pairs() > 0)
              {
                const auto [value, slope] =
                  penalty_flight->value_and_derivative(m);
                at_m.value += value;
                at_m.derivative += slope;
              }
          }
        const LineEnclosure combined = form.enclosure();
        LineEnclosure       enclosure;
        enclosure.value = intersection(combined.value, sum.value);
        enclosure.derivative =
          intersection(combined.derivative, sum.derivative);
        if (std::isfinite(curvature.lower) && std::isfinite(curvature.upper))
          enclosure.curvature = curvature;
        if (m >= a && m <= b)
          {
            enclosure.sample_point = m;
            enclosure.sample       = at_m;
          }
        return enclosure;
      }

      /** The sum of the parts' round-off bounds at the start. */
      double
      value_tolerance() const override
      {
        double tolerance = 0.;
        for (const auto &f : bodies)
          tolerance += f->value_tolerance();
        if (penalty_flight)
          tolerance += penalty_flight->value_tolerance();
        return tolerance;
      }

      double
      admissible_limit() const override
      {
        double limit = infinity;
        for (const double l :
             body_parts<double>(bodies.size(), [&](const unsigned int b) {
               return bodies[b]->admissible_limit();
             }))
          limit = std::min(limit, l);
        return limit;
      }

    private:
      std::vector<std::unique_ptr<ElasticFreeFlight>> bodies;
      std::unique_ptr<contact::PenaltyFlight>         penalty_flight;
    };
  } // namespace



  ContactSystem::ContactSystem(
    std::vector<std::shared_ptr<const ElasticBody>> bodies_in,
    const ContactParameters                        &parameters,
    const std::string                              &name)
    : ContactSystem(std::move(bodies_in), {}, parameters, name)
  {}



  ContactSystem::ContactSystem(
    std::vector<std::shared_ptr<const ElasticBody>> bodies_in,
    std::vector<StaticSurface>                      surfaces_in,
    const ContactParameters                        &parameters,
    const std::string                              &name)
    : system_name(name)
    , bodies(std::move(bodies_in))
    , surfaces(std::move(surfaces_in))
    , contact_parameters(parameters)
  {
    if (bodies.empty())
      throw std::invalid_argument("ContactSystem: no bodies");
    unsigned int n_points = 0;
    for (const auto &body : bodies)
      {
        if (!body)
          throw std::invalid_argument("ContactSystem: a body is missing");
        offsets.push_back(n_points);
        n_points += body->n_vertices();
      }
    for (const StaticSurface &surface : surfaces)
      {
        surface.check();
        offsets.push_back(n_points);
        n_points += surface.n_points();
      }
    offsets.push_back(n_points);

    // Surface points: inverse mass 1 (they are meant to be held fixed).
    inv_mass.reinit(3 * n_points);
    for (unsigned int i = 3 * n_body_points(); i < inv_mass.size(); ++i)
      inv_mass[i] = 1.;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const Vector &m = bodies[b]->inverse_mass();
        for (unsigned int i = 0; i < m.size(); ++i)
          inv_mass[3 * offsets[b] + i] = m[i];
      }

    // Boundary triangles in global point numbers.
    double shortest_edge = std::numeric_limits<double>::infinity();
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const ElasticBody     &body = *bodies[b];
        const Vector           X    = body.reference_configuration();
        std::set<unsigned int> points;
        double                 longest = 0.;
        body_triangles.emplace_back();
        for (const auto &t : body.cell_data().boundary_triangle)
          {
            contact::TriangleIndices global;
            for (unsigned int k = 0; k < 3; ++k)
              {
                global[k] = offsets[b] + t[k];
                points.insert(global[k]);
                const contact::Point3 x0 = contact::point_at(X.data(), t[k]);
                const contact::Point3 x1 =
                  contact::point_at(X.data(), t[(k + 1) % 3]);
                const contact::Point3 edge = contact::minus(x1, x0);
                longest = std::max(longest, contact::dot(edge, edge));
                shortest_edge =
                  std::min(shortest_edge, contact::dot(edge, edge));
              }
            body_triangles.back().push_back(triangles.size());
            triangles.push_back(global);
            triangle_body.push_back(b);
          }
        boundary_points.emplace_back(points.begin(), points.end());
        longest_boundary_edge.push_back(std::sqrt(longest));
      }
    shortest_edge = std::sqrt(shortest_edge);
    // Primitives closer than the tolerance touch: one near an edge's length
    // would make contacts of bodies still apart, again and again.
    if (has_constraints() &&
        !(contact_parameters.ccd_tolerance <= 1e-3 * shortest_edge))
      {
        std::ostringstream message;
        message << "Contact/Collision tolerance = "
                << contact_parameters.ccd_tolerance
                << " is not small against the shortest boundary edge of the "
                   "bodies, "
                << shortest_edge << ": primitives closer than it count as "
                << "touching; give at most " << 1e-3 * shortest_edge
                << " (a thousandth of that edge).";
        throw std::runtime_error(message.str());
      }
    // The collision detection resolves its tolerance only where round-off
    // is smaller: a surface or body beyond that is refused before the run.
    if (has_constraints())
      {
        const double limit =
          contact::ccd_coordinate_limit(contact_parameters.ccd_tolerance);
        const auto largest = [](const auto &coordinates) {
          double m = 0.;
          for (const double x : coordinates)
            m = std::max(m, std::abs(x));
          return m;
        };
        for (unsigned int i = 0; i < bodies.size() + surfaces.size(); ++i)
          {
            const double m = i < bodies.size() ?
                               largest(bodies[i]->reference_configuration()) :
                               largest(surfaces[i - bodies.size()].points);
            if (m > limit)
              {
                std::ostringstream message;
                message << "Contact/Collision tolerance = "
                        << contact_parameters.ccd_tolerance << ": "
                        << (i < bodies.size() ?
                              "body " + std::to_string(i + 1) :
                              "obstacle " + surfaces[i - bodies.size()].name)
                        << " has coordinates as large as " << m
                        << ", where the collision detection's round-off "
                           "exceeds half this tolerance and it cannot tell "
                           "contact from separation; it needs coordinates "
                           "within 2^45 times the tolerance ("
                        << limit << "): bring the geometry closer to the "
                        << "origin or give a tolerance of at least "
                        << m / 0x1p45 << ".";
                throw std::runtime_error(message.str());
              }
          }
      }
    const unsigned int n_body_triangles = triangles.size();
    for (unsigned int s = 0; s < surfaces.size(); ++s)
      for (const auto &t : surfaces[s].triangles)
        {
          const unsigned int first = surface_point_offset(s);
          triangles.push_back({{first + t[0], first + t[1], first + t[2]}});
          triangle_body.push_back(bodies.size() + s);
        }
    // Exclusion groups: without self-contact, one per body; all surfaces
    // together form one more (with self-contact, every body triangle has a
    // group of its own). None at all with self-contact and no surfaces.
    if (!contact_parameters.self_contact)
      {
        exclusion_groups = triangle_body;
        for (unsigned int t = n_body_triangles; t < triangles.size(); ++t)
          exclusion_groups[t] = bodies.size();
      }
    else if (!surfaces.empty())
      {
        exclusion_groups.resize(triangles.size());
        for (unsigned int t = 0; t < triangles.size(); ++t)
          exclusion_groups[t] = std::min(t, n_body_triangles);
      }
    for (auto *tree : {&ccd_tree, &intersection_tree})
      {
        *tree = contact::BoundingVolumeHierarchy(triangles, exclusion_groups);
        tree->set_rebuild_interval(64);
      }

    if (contact_parameters.mode == ContactParameters::Mode::penalty)
      {
        if (!(contact_parameters.penalty_parameter > 0.))
          throw std::invalid_argument(
            "ContactSystem: the penalty parameter must be positive");
        penalty = std::make_unique<contact::PenaltyContact>(
          triangles, contact_parameters.penalty_parameter);
        penalty->set_exclusion_groups(exclusion_groups);
      }
    if (!(contact_parameters.ccd_tolerance > 0.))
      throw std::invalid_argument(
        "ContactSystem: the collision tolerance must be positive");
    scratch_q.resize(bodies.size());
    scratch_g.resize(bodies.size());
  }



  ContactSystem::~ContactSystem() = default;



  std::string
  ContactSystem::name() const
  {
    return system_name;
  }



  unsigned int
  ContactSystem::spatial_dimension() const
  {
    return 3;
  }



  unsigned int
  ContactSystem::n_dofs() const
  {
    return 3 * offsets.back();
  }



  const Vector &
  ContactSystem::inverse_mass() const
  {
    return inv_mass;
  }



  double
  ContactSystem::energy(const Vector &q) const
  {
    double total = 0.;
    for (const double energy :
         body_parts<double>(bodies.size(), [&](const unsigned int b) {
           scratch_q[b] = extract(q, b);
           return bodies[b]->energy(scratch_q[b]);
         }))
      total += energy;
    if (!std::isfinite(total))
      return infinity;
    return total + contact_energy(q);
  }



  void
  ContactSystem::gradient(const Vector &q, Vector &g) const
  {
    g.reinit(q.size());
    for_each_body(bodies.size(), [&](const unsigned int b) {
      scratch_q[b] = extract(q, b);
      bodies[b]->gradient(scratch_q[b], scratch_g[b]);
      for (unsigned int i = 0; i < scratch_g[b].size(); ++i)
        g[3 * offsets[b] + i] = scratch_g[b][i];
    });
    if (penalty)
      penalty->add_gradient(q.data(), q.size(), g.data());
  }



  struct ContactSystem::SharedState
  {
    unsigned int                                 ranks = 0;
    std::vector<BlockRange>                      kept;
    std::vector<dealii::types::global_dof_index> owned;
    std::vector<std::size_t>                     body_start;
    std::unique_ptr<GhostExchange>               exchange;
    std::vector<double>                          own_gradient;
  };



  ContactSystem::SharedState &
  ContactSystem::current_shared_state() const
  {
    if (shared_state && shared_state->ranks == rank_count())
      return *shared_state;
    shared_state         = std::make_unique<SharedState>();
    SharedState &shared  = *shared_state;
    shared.ranks         = rank_count();
    const unsigned int n = n_dofs();
    std::vector<char>  read(n, 0);
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const std::size_t        first     = 3 * std::size_t(offsets[b]);
        const std::vector<char> &body_read = bodies[b]->coordinates_read();
        std::copy(body_read.begin(), body_read.end(), read.begin() + first);
        shared.body_start.push_back(shared.owned.size());
        for (const auto i : bodies[b]->own_coordinates())
          shared.owned.push_back(first + i);
        for (const unsigned int p : boundary_points[b])
          std::fill_n(read.begin() + 3 * p, 3, 1);
      }
    shared.body_start.push_back(shared.owned.size());
    // The surfaces' points: no body's, their gradient the contact's alone,
    // which every rank computes.
    std::fill(read.begin() + 3 * n_body_points(), read.end(), 1);
    shared.kept = kept_coordinate_ranges(std::move(read));
    shared.own_gradient.resize(shared.owned.size());
    return shared;
  }



  const std::vector<BlockRange> *
  ContactSystem::kept_coordinates() const
  {
    return rank_count() > 1 ? &current_shared_state().kept : nullptr;
  }



  void
  ContactSystem::kept_gradient(const Vector &q, Vector &g) const
  {
    if (rank_count() == 1)
      {
        gradient(q, g);
        return;
      }
    SharedState &shared = current_shared_state();
    if (g.size() != q.size())
      g.reinit(q.size());
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        scratch_q[b] = extract(q, b);
        const double *mine =
          bodies[b]->gradient_of_own_points(scratch_q[b], scratch_g[b]);
        std::copy(mine,
                  mine + (shared.body_start[b + 1] - shared.body_start[b]),
                  shared.own_gradient.begin() + shared.body_start[b]);
      }
    for (std::size_t j = 0; j < shared.owned.size(); ++j)
      g[shared.owned[j]] = shared.own_gradient[j];
    // The surfaces' points are no body's: every rank computes their
    // gradient, the contact's alone.
    std::fill(g.begin() + 3 * n_body_points(), g.end(), 0.);
    if (shared.exchange == nullptr)
      shared.exchange = std::make_unique<GhostExchange>(shared.owned,
                                                        shared.kept,
                                                        3 * n_body_points());
    shared.exchange->send(shared.own_gradient.data(), g.data());
    if (penalty)
      penalty->add_gradient(q.data(), q.size(), g.data());
  }



  void
  ContactSystem::complete_state(Vector &x) const
  {
    if (rank_count() == 1)
      return;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        Vector part = extract(x, b);
        bodies[b]->complete_state(part);
        std::copy(part.begin(), part.end(), x.begin() + 3 * offsets[b]);
      }
  }



  std::unique_ptr<FreeFlight>
  ContactSystem::free_flight(const Vector &q, const Vector &v) const
  {
    return std::make_unique<ContactFreeFlight>(*this, penalty.get(), q, v);
  }



  bool
  ContactSystem::has_constraints() const
  {
    return contact_parameters.mode == ContactParameters::Mode::impenetrability;
  }



  std::optional<ConstraintEvent>
  ContactSystem::first_constraint_event(const Vector &q,
                                        const Vector &v,
                                        const double  s_max) const
  {
    if (contact_parameters.mode != ContactParameters::Mode::impenetrability)
      return std::nullopt;
    contact::CcdSettings settings;
    settings.tolerance = contact_parameters.ccd_tolerance;
    const auto c       = contact::find_first_contact(
      ccd_tree, q.data(), v.data(), q.size(), s_max, settings);
    if (!c)
      return std::nullopt;
    ConstraintEvent event;
    event.s = c->s;
    event.normal.reinit(q.size());
    for (unsigned int k = 0; k < 4; ++k)
      for (unsigned int d = 0; d < 3; ++d)
        event.normal[3 * c->points[k] + d] += c->weights[k] * c->normal[d];
    return event;
  }



  std::vector<SparseNormal>
  ContactSystem::touching_constraints(const Vector &q) const
  {
    std::vector<SparseNormal> normals;
    if (contact_parameters.mode != ContactParameters::Mode::impenetrability)
      return normals;
    contact::CcdSettings settings;
    settings.tolerance = contact_parameters.ccd_tolerance;
    for (const contact::FirstContact &c :
         contact::touching_contacts(ccd_tree, q.data(), q.size(), settings))
      {
        // The four points of a pair are distinct (pairs that share a vertex
        // never touch).
        SparseNormal &normal = normals.emplace_back();
        for (unsigned int k = 0; k < 4; ++k)
          for (unsigned int d = 0; d < 3; ++d)
            normal.emplace_back(3 * c.points[k] + d,
                                c.weights[k] * c.normal[d]);
      }
    return normals;
  }



  std::vector<std::string>
  ContactSystem::observable_names() const
  {
    std::vector<std::string> names;
    const auto               add = [&names](const std::string &suffix) {
      for (const char *quantity : {"V", "Omega"})
        for (const char *axis : {"_x", "_y", "_z"})
          names.push_back(quantity + suffix + axis);
    };
    for (unsigned int b = 0; b < bodies.size(); ++b)
      add(std::to_string(b + 1));
    add("");
    names.emplace_back("intersecting_pairs");
    for (const auto &body : bodies)
      for (const std::string &name : body->observable_names())
        names.push_back(name);
    return names;
  }



  std::vector<double>
  ContactSystem::observables(const Vector &q, const Vector &v) const
  {
    std::vector<double> values;
    const auto          add = [&values](const RigidBodyMotion &m) {
      values.insert(values.end(), m.velocity.begin(), m.velocity.end());
      values.insert(values.end(), m.angular.begin(), m.angular.end());
    };
    for (unsigned int b = 0; b < bodies.size(); ++b)
      add(body_motion(q, v, b));
    add(system_motion(q, v));
    values.push_back(n_intersecting_pairs(q));
    for (unsigned int b = 0; b < bodies.size(); ++b)
      if (!bodies[b]->observable_names().empty())
        {
          const std::vector<double> own =
            bodies[b]->observables(extract(q, b), extract(v, b));
          values.insert(values.end(), own.begin(), own.end());
        }
    return values;
  }



  unsigned int
  ContactSystem::n_bodies() const
  {
    return bodies.size();
  }



  const ElasticBody &
  ContactSystem::body(const unsigned int b) const
  {
    return *bodies.at(b);
  }



  unsigned int
  ContactSystem::point_offset(const unsigned int b) const
  {
    return offsets.at(b);
  }



  unsigned int
  ContactSystem::body_of_point(const unsigned int point) const
  {
    return std::upper_bound(offsets.begin(),
                            offsets.begin() + bodies.size(),
                            point) -
           offsets.begin() - 1;
  }



  unsigned int
  ContactSystem::n_body_points() const
  {
    return offsets[bodies.size()];
  }



  unsigned int
  ContactSystem::n_surfaces() const
  {
    return surfaces.size();
  }



  const StaticSurface &
  ContactSystem::surface(const unsigned int s) const
  {
    return surfaces.at(s);
  }



  unsigned int
  ContactSystem::surface_point_offset(const unsigned int s) const
  {
    if (s >= surfaces.size())
      throw std::out_of_range("ContactSystem::surface_point_offset: no "
                              "surface " +
                              std::to_string(s));
    return offsets[bodies.size() + s];
  }



  std::vector<unsigned int>
  ContactSystem::surface_points() const
  {
    std::vector<unsigned int> points;
    for (unsigned int i = n_body_points(); i < offsets.back(); ++i)
      points.push_back(i);
    return points;
  }



  Vector
  ContactSystem::concatenate(const std::vector<Vector> &per_body) const
  {
    Vector x = concatenate_velocities(per_body);
    for (unsigned int s = 0; s < surfaces.size(); ++s)
      for (unsigned int i = 0; i < surfaces[s].points.size(); ++i)
        x[3 * surface_point_offset(s) + i] = surfaces[s].points[i];
    return x;
  }



  Vector
  ContactSystem::concatenate_velocities(
    const std::vector<Vector> &per_body) const
  {
    if (per_body.size() != bodies.size())
      throw std::invalid_argument("ContactSystem::concatenate: one vector per "
                                  "body expected");
    Vector x(n_dofs());
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        if (per_body[b].size() != bodies[b]->n_dofs())
          throw std::invalid_argument(
            "ContactSystem::concatenate: wrong size for body " +
            std::to_string(b));
        for (unsigned int i = 0; i < per_body[b].size(); ++i)
          x[3 * offsets[b] + i] = per_body[b][i];
      }
    return x;
  }



  void
  ContactSystem::body_state(const Vector      &q,
                            const Vector      &v,
                            const unsigned int b,
                            Vector            &q_b,
                            Vector            &v_b) const
  {
    q_b = extract(q, b);
    v_b = extract(v, b);
  }



  Vector
  ContactSystem::extract(const Vector &x, const unsigned int b) const
  {
    Vector part(bodies.at(b)->n_dofs());
    for (unsigned int i = 0; i < part.size(); ++i)
      part[i] = x[3 * offsets[b] + i];
    return part;
  }



  const std::vector<contact::TriangleIndices> &
  ContactSystem::boundary_triangles() const
  {
    return triangles;
  }



  const std::vector<unsigned int> &
  ContactSystem::triangle_bodies() const
  {
    return triangle_body;
  }



  const ContactParameters &
  ContactSystem::parameters() const
  {
    return contact_parameters;
  }



  double
  ContactSystem::contact_energy(const Vector &q) const
  {
    return penalty ? penalty->energy(q.data(), q.size()) : 0.;
  }



  std::vector<std::pair<unsigned int, unsigned int>>
  ContactSystem::intersecting_pairs(const Vector &q) const
  {
    intersection_tree.refit(q.data(), q.size());
    std::vector<std::pair<unsigned int, unsigned int>> candidates, pairs;
    intersection_tree.find_pairs(candidates);
    std::sort(candidates.begin(), candidates.end());
    for (const auto &[i, j] : candidates)
      {
        if (contact::triangles_intersect(
              contact::triangle_at(q.data(), triangles[i]),
              contact::triangle_at(q.data(), triangles[j])))
          pairs.emplace_back(i, j);
      }
    return pairs;
  }



  unsigned int
  ContactSystem::n_intersecting_pairs(const Vector &q) const
  {
    return intersecting_pairs(q).size();
  }



  std::vector<ContactSystem::Meeting>
  ContactSystem::meeting_bodies(const Vector &q) const
  {
    std::map<std::pair<unsigned int, unsigned int>, bool> crossing;
    for (auto [i, j] : intersecting_pairs(q))
      {
        // A surface's triangle second: it bounds no body.
        if (triangle_body[i] >= bodies.size())
          std::swap(i, j);
        crossing[std::minmax(triangle_body[i], triangle_body[j])] |=
          contact::triangles_cross(contact::triangle_at(q.data(), triangles[i]),
                                   contact::triangle_at(q.data(), triangles[j]),
                                   triangle_body[j] < bodies.size());
      }
    std::vector<Meeting> meetings;
    for (const auto &[pair, crosses] : crossing)
      meetings.push_back({pair.first, pair.second, crosses});
    return meetings;
  }



  std::optional<std::pair<unsigned int, unsigned int>>
  ContactSystem::nested_bodies(const Vector &q) const
  {
    // The connected pieces of each body's and surface's boundary: the
    // classes of the vertices joined by triangle edges. Without crossing
    // boundaries, either all of a piece lies inside a body or none of it
    // does, apart from points on the body's boundary.
    const unsigned int        n_vertices = q.size() / 3;
    std::vector<unsigned int> parent(n_vertices);
    std::iota(parent.begin(), parent.end(), 0u);
    const auto root = [&](unsigned int p) {
      while (parent[p] != p)
        p = parent[p] = parent[parent[p]];
      return p;
    };
    for (const auto &triangle : triangles)
      for (const unsigned int corner : {triangle[1], triangle[2]})
        parent[root(corner)] = root(triangle[0]);
    struct Piece
    {
      unsigned int              owner;
      std::vector<unsigned int> vertices;
    };
    std::vector<Piece>        pieces;
    std::vector<unsigned int> piece_at_root(
      n_vertices, std::numeric_limits<unsigned int>::max());
    std::vector<bool> listed(n_vertices, false);
    for (unsigned int i = 0; i < triangles.size(); ++i)
      for (const unsigned int corner : triangles[i])
        if (!listed[corner])
          {
            listed[corner]      = true;
            unsigned int &piece = piece_at_root[root(corner)];
            if (piece == std::numeric_limits<unsigned int>::max())
              {
                piece = pieces.size();
                pieces.push_back({triangle_body[i], {}});
              }
            pieces[piece].vertices.push_back(corner);
          }
    // A point outside the box of a body's boundary is outside the body.
    const std::vector<contact::BoundingBox> boxes = body_boxes(q.data());
    for (unsigned int outer = 0; outer < bodies.size(); ++outer)
      {
        // Closer to the boundary than this, a vertex touches it.
        const contact::Point3 diagonal =
          contact::minus(boxes[outer].upper, boxes[outer].lower);
        const double on_boundary =
          1e-9 * std::sqrt(contact::dot(diagonal, diagonal));
        for (const Piece &piece : pieces)
          if (piece.owner != outer)
            for (const unsigned int vertex : piece.vertices)
              {
                const contact::Point3 p = contact::point_at(q.data(), vertex);
                if (!boxes[outer].contains(p))
                  break;
                const contact::PointAndSurface where = contact::locate_point(
                  p, q.data(), triangles, body_triangles[outer], on_boundary);
                if (where.distance <= on_boundary)
                  continue;
                if (where.winding_number > 0.5)
                  return std::make_pair(piece.owner, outer);
                break;
              }
      }
    return std::nullopt;
  }



  RigidBodyMotion
  ContactSystem::body_motion(const Vector      &q,
                             const Vector      &v,
                             const unsigned int b) const
  {
    return rigid_body_motion(
      inv_mass, q, v, offsets.at(b), offsets.at(b + 1) - offsets.at(b));
  }



  RigidBodyMotion
  ContactSystem::system_motion(const Vector &q, const Vector &v) const
  {
    return rigid_body_motion(inv_mass, q, v, 0, n_body_points());
  }



  double
  ContactSystem::penetration_limit(const unsigned int b1,
                                   const unsigned int b2) const
  {
    return std::max(longest_boundary_edge.at(b1), longest_boundary_edge.at(b2));
  }



  std::optional<ContactSystem::Penetration>
  ContactSystem::deep_penetration(const Vector &q) const
  {
    const double                           *x     = q.data();
    const std::vector<contact::BoundingBox> boxes = body_boxes(x);
    // The bodies whose boxes overlap, both ways, in the order of a loop
    // over every pair: no point of a body whose box misses another's is
    // inside it.
    std::vector<std::pair<unsigned int, unsigned int>> candidates;
    for (const auto &[a, b] : contact::overlapping_pairs(boxes))
      {
        candidates.emplace_back(a, b);
        candidates.emplace_back(b, a);
      }
    std::sort(candidates.begin(), candidates.end());
    for (const auto &[entered, entering] : candidates)
      {
        // The box of the body that might be entered, shrunk by the limit:
        // a point outside it is not that deep inside the body. No point of
        // a body whose box misses it is.
        const double         limit = penetration_limit(entered, entering);
        contact::BoundingBox deep  = boxes[entered];
        bool                 empty = false;
        for (unsigned int c = 0; c < 3; ++c)
          {
            deep.lower[c] += limit;
            deep.upper[c] -= limit;
            empty = empty || !(deep.lower[c] <= deep.upper[c]);
          }
        if (empty || !deep.overlaps(boxes[entering]))
          continue;
        for (const unsigned int i : boundary_points[entering])
          {
            const contact::Point3 p = contact::point_at(x, i);
            if (!deep.contains(p))
              continue;
            const contact::PointAndSurface where = contact::locate_point(
              p, x, triangles, body_triangles[entered], limit);
            if (where.distance > limit && where.winding_number > 0.5)
              return Penetration{entering, entered, i, where.distance, limit};
          }
      }
    return std::nullopt;
  }



  std::vector<contact::BoundingBox>
  ContactSystem::body_boxes(const double *x) const
  {
    std::vector<contact::BoundingBox> boxes(bodies.size(),
                                            contact::BoundingBox::empty());
    for (unsigned int b = 0; b < bodies.size(); ++b)
      for (const unsigned int i : boundary_points[b])
        boxes[b].add(contact::point_at(x, i));
    return boxes;
  }



  std::string
  ContactSystem::penetration(const Vector &q) const
  {
    const auto found = deep_penetration(q);
    if (!found)
      return "";
    std::ostringstream text;
    text << "a boundary point of body " << found->body + 1 << " (point "
         << found->point - offsets[found->body] << ") lies " << found->depth
         << " inside body " << found->other_body + 1
         << ", deeper than the longest boundary edge " << found->limit
         << " of the two meshes";
    if (contact_parameters.mode == ContactParameters::Mode::penalty)
      text << "; the penalty (Contact/Penalty parameter = "
           << contact_parameters.penalty_parameter
           << ", smaller is stiffer) is too soft to keep them apart";
    text << ".";
    return text.str();
  }



  double
  ContactSystem::penalty_energy_scale() const
  {
    if (contact_parameters.mode != ContactParameters::Mode::penalty)
      return std::numeric_limits<double>::infinity();
    const double longest = *std::max_element(longest_boundary_edge.begin(),
                                             longest_boundary_edge.end());
    return longest * longest / (2. * contact_parameters.penalty_parameter);
  }
} // namespace estep
