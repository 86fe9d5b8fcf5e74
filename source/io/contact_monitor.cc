#include <deal.II/base/parameter_handler.h>

#include <estep/composite/contact_system.h>
#include <estep/composite/scene.h>
#include <estep/io/contact_monitor.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace estep
{
  namespace
  {
    /** The integrator's count of constraint events (0 if it has none). */
    std::uint64_t
    constraint_events(const TimeIntegrator &integrator)
    {
      for (const Counter &counter : integrator.counters())
        if (counter.first == "constraint events")
          return counter.second;
      return 0;
    }

    JsonObject
    motion_json(const RigidBodyMotion &motion)
    {
      return JsonObject()
        .add("V",
             std::vector<double>(motion.velocity.begin(),
                                 motion.velocity.end()))
        .add("Omega",
             std::vector<double>(motion.angular.begin(), motion.angular.end()));
    }
  } // namespace



  ContactMonitor::ContactMonitor(const ContactSystem  &system,
                                 const TimeIntegrator &integrator,
                                 const Vector         &q0,
                                 const Vector         &v0)
    : ContactMonitor(
        system,
        integrator,
        q0,
        v0,
        [](const Vector &q, const Vector &v, Vector &qc, Vector &vc) {
          qc = q;
          vc = v;
        },
        true)
  {}



  ContactMonitor::ContactMonitor(
    const ContactSystem                        &system,
    const TimeIntegrator                       &integrator,
    const Vector                               &q,
    const Vector                               &v,
    StateMap                                    to_contact,
    const bool                                  bodies_alone,
    std::function<unsigned int(const Vector &)> obstacle_count)
    : system(system)
    , integrator(integrator)
    , to_contact(std::move(to_contact))
    , two_bodies_alone(bodies_alone && system.n_bodies() == 2)
    , obstacle_count(std::move(obstacle_count))
  {
    this->to_contact(q, v, q0, v0);
  }



  void
  ContactMonitor::current_state(Vector &q, Vector &v) const
  {
    to_contact(integrator.position(), integrator.velocity(), q, v);
  }



  void
  ContactMonitor::add_to_summary(JsonObject &out) const
  {
    Vector q, v;
    current_state(q, v);
    out.add("contact", summary(q0, v0, q, v));
  }



  std::string
  ContactMonitor::final_report() const
  {
    Vector q, v;
    current_state(q, v);
    return report(q0, v0, q, v);
  }



  void
  ContactMonitor::save_state(StateWriter &out) const
  {
    out.put(largest_obstacle_count);
    out.put(largest_pair_count);
    out.put(steps_with_pairs);
    out.put(constraint_events_seen);
    out.put(in_contact);
    out.put(n_contact_instants);
    out.put(first_contact);
    out.put(last_contact);
    out.put(step_before_first_contact);
    out.put(step_after_last_contact);
  }



  void
  ContactMonitor::resume(StateReader &in)
  {
    largest_obstacle_count    = in.get<unsigned int>();
    largest_pair_count        = in.get<unsigned int>();
    steps_with_pairs          = in.get<std::uint64_t>();
    constraint_events_seen    = in.get<std::uint64_t>();
    in_contact                = in.get<bool>();
    n_contact_instants        = in.get<std::uint64_t>();
    first_contact             = in.get<double>();
    last_contact              = in.get<double>();
    step_before_first_contact = in.get<double>();
    step_after_last_contact   = in.get<double>();
  }



  void
  ContactMonitor::after_step(const TimeIntegrator &integrator)
  {
    Vector q, v;
    current_state(q, v);
    const unsigned int  pairs  = system.n_intersecting_pairs(q);
    const std::uint64_t events = constraint_events(integrator);
    const unsigned int  inside =
      obstacle_count ? obstacle_count(integrator.position()) : 0;
    largest_obstacle_count = std::max(largest_obstacle_count, inside);
    const bool contact =
      pairs > 0 || inside > 0 || events > constraint_events_seen;
    constraint_events_seen = events;
    largest_pair_count     = std::max(largest_pair_count, pairs);
    steps_with_pairs += (pairs > 0);

    const double t = integrator.time(), step = t - integrator.previous_time();
    if (contact)
      {
        if (n_contact_instants == 0)
          {
            first_contact             = t;
            step_before_first_contact = step;
          }
        ++n_contact_instants;
        last_contact            = t;
        step_after_last_contact = 0.;
      }
    else if (in_contact)
      step_after_last_contact = step;
    in_contact = contact;
  }



  double
  ContactMonitor::contact_duration() const
  {
    return last_contact - first_contact;
  }



  double
  ContactMonitor::contact_duration_resolution() const
  {
    return std::max(step_before_first_contact, step_after_last_contact);
  }



  double
  ContactMonitor::restitution(const Vector &q0,
                              const Vector &v0,
                              const Vector &q1,
                              const Vector &v1) const
  {
    const auto relative_kinetic_energy = [this](const Vector &q,
                                                const Vector &v) {
      const RigidBodyMotion whole  = system.system_motion(q, v);
      double                energy = 0.;
      for (unsigned int b = 0; b < system.n_bodies(); ++b)
        {
          const RigidBodyMotion body = system.body_motion(q, v, b);
          for (unsigned int c = 0; c < 3; ++c)
            energy += 0.5 * body.mass *
                      std::pow(body.velocity[c] - whole.velocity[c], 2);
        }
      return energy;
    };
    const double before = relative_kinetic_energy(q0, v0);
    if (!(before > 0.))
      return std::numeric_limits<double>::quiet_NaN();
    return std::sqrt(relative_kinetic_energy(q1, v1) / before);
  }



  bool
  ContactMonitor::contact_over() const
  {
    // Apart for at least as long as in contact: a penalty contact has step
    // ends without intersecting faces in its midst.
    return n_contact_instants > 0 && !in_contact &&
           integrator.time() - last_contact >= contact_duration();
  }



  double
  ContactMonitor::collision_restitution(const Vector &q0,
                                        const Vector &v0,
                                        const Vector &q1,
                                        const Vector &v1) const
  {
    if (!two_bodies_alone || !contact_over())
      return std::numeric_limits<double>::quiet_NaN();
    return restitution(q0, v0, q1, v1);
  }



  JsonObject
  ContactMonitor::summary(const Vector &q0,
                          const Vector &v0,
                          const Vector &q1,
                          const Vector &v1) const
  {
    JsonObject result;
    result.add("largest number of intersecting face pairs", largest_pair_count)
      .add("largest number of points behind obstacles", largest_obstacle_count)
      .add("steps ending with intersecting face pairs", steps_with_pairs)
      .add("contact instants", n_contact_instants);
    if (n_contact_instants > 0)
      result.add("first contact instant", first_contact)
        .add("last contact instant", last_contact)
        .add("contact duration", contact_duration())
        .add("contact duration resolution", contact_duration_resolution());
    const double e = collision_restitution(q0, v0, q1, v1);
    if (std::isfinite(e))
      result.add("coefficient of restitution", e);
    JsonObject final_motion;
    for (unsigned int b = 0; b < system.n_bodies(); ++b)
      final_motion.add("body " + std::to_string(b + 1),
                       motion_json(system.body_motion(q1, v1, b)));
    final_motion.add("system", motion_json(system.system_motion(q1, v1)));
    result.add("final rigid motion", final_motion);
    return result;
  }



  std::string
  ContactMonitor::report(const Vector &q0,
                         const Vector &v0,
                         const Vector &q1,
                         const Vector &v1) const
  {
    std::ostringstream out;
    out.precision(4);
    if (n_contact_instants == 0)
      out << "no contact";
    else
      {
        out << "contact from t = " << first_contact << " to " << last_contact
            << " (duration " << contact_duration();
        // (Under impenetrability the instants are the constraint events
        // themselves.)
        if (!system.has_constraints() &&
            contact_duration_resolution() > contact_duration())
          out << ", unresolved: the steps around it are as long as "
              << contact_duration_resolution();
        out << ", " << n_contact_instants << " step ends in contact"
            << (contact_over() ? "" : ", perhaps not over") << ")";
      }
    const double e = collision_restitution(q0, v0, q1, v1);
    if (std::isfinite(e))
      out << ", coefficient of restitution " << e;
    out << ", at most " << largest_pair_count
        << " intersecting face pairs at a step end";
    return out.str();
  }



  namespace
  {
    std::unique_ptr<Postprocessor>
    create_contact_monitor(dealii::ParameterHandler &,
                           const PostprocessorContext &run)
    {
      const MechanicalSystem &system = run.integrator.mechanical_system();
      if (const auto *contact = dynamic_cast<const ContactSystem *>(&system))
        return std::make_unique<ContactMonitor>(*contact,
                                                run.integrator,
                                                run.q0,
                                                run.v0);
      if (const auto *scene = dynamic_cast<const Scene *>(&system);
          scene != nullptr && scene->contact_system() != nullptr)
        return std::make_unique<ContactMonitor>(
          *scene->contact_system(),
          run.integrator,
          run.q0,
          run.v0,
          scene->state_map(),
          scene->bodies_only_meet_each_other(),
          [scene](const Vector &q) { return scene->n_points_in_obstacles(q); });
      return nullptr;
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_POSTPROCESSOR(
  "contact monitor",
  "contact statistics of a system with contact (pairs, duration, "
  "restitution, constraint events) in summary.json and a line at the end; "
  "nothing for a system without contact.",
  nullptr,
  estep::create_contact_monitor)
