#include <deal.II/base/parameter_handler.h>

#include <estep/base/distributed_blocks.h>
#include <estep/base/parallel_blocks.h>
#include <estep/base/parameter_subsections.h>
#include <estep/time_integration/energy_stepping.h>
#include <estep/time_integration/integrator_registry.h>
#include <estep/time_integration/joint_reflection.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    /** The first search window of a run (before any flight of positive
     * length), in units of time: small, since the search doubles its
     * windows (about 20 more enclosures for a first step of order 1). */
    constexpr double first_window_of_a_run = 0x1p-20;
  } // namespace



  EnergyStepping::EnergyStepping(const MechanicalSystem &system,
                                 const double            energy_step,
                                 const double            terrace_offset)
    : TimeIntegrator(system)
    , h(energy_step)
    , c(terrace_offset)
  {
    if (!(energy_step > 0.) || !std::isfinite(energy_step))
      throw std::invalid_argument(
        "The energy step must be positive and finite.");
    if (!(terrace_offset >= 0. && terrace_offset < 1.))
      throw std::invalid_argument("The terrace offset must lie in [0, 1).");
  }



  void
  EnergyStepping::use_sampled_search(const SamplingSettings &settings,
                                     const bool              audit_flights)
  {
    sampling = settings;
    audit    = audit_flights;
  }



  std::string
  EnergyStepping::name() const
  {
    return sampling ? "energy stepping (sampled crossings)" : "energy stepping";
  }



  Crossing
  EnergyStepping::search(const FreeFlight &flight, const CrossingQuery &query)
  {
    if (!sampling)
      return find_first_crossing(flight, query, search_statistics);
    const Crossing sampled = find_first_crossing_by_sampling(flight,
                                                             query,
                                                             *sampling,
                                                             search_statistics);
    if (audit)
      {
        SearchStatistics unused;
        const Crossing   certified = find_first_crossing(flight, query, unused);
        const double     found     = sampled.direction != 0 ?
                                       sampled.s :
                                       std::numeric_limits<double>::infinity();
        if (certified.direction != 0 &&
            certified.s < found - 1e-8 * std::abs(found))
          ++n_stepped_over;
      }
    return sampled;
  }



  void
  EnergyStepping::initialize(const double  t0,
                             const Vector &q0,
                             const Vector &v0)
  {
    t = t_previous = t0;
    q = q_start = q0;
    v = v_flight    = v0;
    const double V0 = system.energy(q0);
    if (!std::isfinite(V0))
      throw std::runtime_error(
        "The initial configuration is inadmissible: its potential energy is not finite.");
    // The terrace index V / h must be an integer a double holds exactly
    // (and a long long at all).
    if (!(std::abs(V0 / h) < 9007199254740992.))
      {
        std::ostringstream message;
        message << "Time integration/Energy stepping/Energy step: h = " << h
                << " is too small for the initial potential energy V = " << V0
                << ": V / h exceeds 2^53, and the terraces would lie below "
                   "the round-off of V; take h of at least |V| / 2^53 (and, "
                   "for a search that can advance, far more).";
        throw std::runtime_error(message.str());
      }
    level = static_cast<long long>(std::floor(V0 / h - c));
    // Round-off of V0 / h - c may leave V0 just below its level.
    if (V0 < level_height(level))
      --level;
    level_flight = level;
    departure    = Departure::interior;
    last_flight  = 0.;
    gradient_buffer.reinit(q0.size());
    force_mass_norm = measure_force_mass_norm();
    stay = longest_stay = StayAtLevel{t0, t0, 0};
    E_h0                = terraced_energy();
    energy_scale        = std::abs(kinetic_energy(system, v0)) + std::abs(V0);
  }



  void
  EnergyStepping::save_state(StateWriter &out) const
  {
    TimeIntegrator::save_state(out);
    out.put(E_h0);
    out.put(energy_scale);
    out.put(level);
    out.put(static_cast<int>(departure));
    out.put(last_flight);
    out.put_vector(q_start);
    out.put_vector(v_flight);
    out.put(level_flight);
    for (const std::uint64_t n : {search_statistics.n_value_evaluations,
                                  search_statistics.n_enclosures,
                                  search_statistics.n_locate_evaluations,
                                  search_statistics.max_intervals_in_one_search,
                                  n_climbs,
                                  n_descents,
                                  n_reflections,
                                  n_constraint_events,
                                  n_gradients,
                                  n_stepped_over})
      out.put(n);
    for (const StayAtLevel &s : {stay, longest_stay})
      {
        out.put(s.from);
        out.put(s.to);
        out.put(s.reflections);
      }
  }



  void
  EnergyStepping::load_state(StateReader &in)
  {
    TimeIntegrator::load_state(in);
    E_h0         = in.get<double>();
    energy_scale = in.get<double>();
    level        = in.get<long long>();
    departure    = static_cast<Departure>(in.get<int>());
    last_flight  = in.get<double>();
    in.get_vector(q_start);
    in.get_vector(v_flight);
    level_flight = in.get<long long>();
    for (std::uint64_t *n : {&search_statistics.n_value_evaluations,
                             &search_statistics.n_enclosures,
                             &search_statistics.n_locate_evaluations,
                             &search_statistics.max_intervals_in_one_search,
                             &n_climbs,
                             &n_descents,
                             &n_reflections,
                             &n_constraint_events,
                             &n_gradients,
                             &n_stepped_over})
      *n = in.get<std::uint64_t>();
    for (StayAtLevel *s : {&stay, &longest_stay})
      {
        s->from        = in.get<double>();
        s->to          = in.get<double>();
        s->reflections = in.get<std::uint64_t>();
      }
    gradient_buffer.reinit(q.size());
    force_mass_norm = measure_force_mass_norm();
  }



  void
  EnergyStepping::step(const double t_limit)
  {
    const double horizon = t_limit - t;
    if (!(horizon > 0.))
      return;

    CrossingQuery query;
    query.horizon = horizon;
    // Twice the last flight of positive length; before the first, a small
    // window that the search doubles: never the horizon, so that the
    // states before the end time do not depend on it.
    query.first_window =
      (last_flight > 0.) ? 2. * last_flight : first_window_of_a_run;
    Crossing                       crossing;
    double                         s_level = horizon;
    std::optional<ConstraintEvent> contact;
    // A constraint event at s = 0 (another contact touching and approaching
    // at this instant) is resolved here, before the flight: reflect and
    // search again, so that simultaneous contacts make no zero-length steps.
    // The reflection leaves q where it is, so the flight still departs from
    // the level it sat on; if the new velocity carries it back through that
    // level at once (a crossing at s = 0), the jump there is made at this
    // instant too. Contacts that hold each other (touching pairs that
    // reflections one pair at a time keep turning towards each other) are
    // reflected off all at once (joint_reflection_normal()); a contact still
    // touching and approaching after the cap of reflections stalls the run
    // there, with a message saying so.
    for (unsigned int k = 0;; ++k)
      {
        query.lower_level = level_height(level);
        query.upper_level = level_height(level + 1);
        query.departure   = departure;
        try
          {
            crossing = search(*system.free_flight(q, v), query);
          }
        catch (const SearchStalled &stalled)
          {
            std::ostringstream message;
            message << "Energy stepping stalled at t = " << t << " with the "
                    << "energy step h = " << h << ": " << stalled.what() << ".";
            throw StalledRun(message.str());
          }
        s_level = crossing.direction != 0 ? crossing.s : horizon;
        contact = system.first_constraint_event(q, v, s_level);
        if (k == max_simultaneous_events)
          {
            if (!contact || contact->s > 0.)
              break;
            std::ostringstream message;
            message << "Energy stepping stalled at t = " << t << ": after "
                    << max_simultaneous_events << " reflections at this "
                    << "instant (the first " << reflections_one_pair_at_a_time
                    << " off one contact pair at a time, the others off all "
                    << "touching pairs at once), a pair still touches and "
                    << "approaches.";
            throw StalledRun(message.str());
          }
        if (contact && contact->s == 0.)
          {
            if (k < reflections_one_pair_at_a_time)
              reflect(contact->normal);
            else
              {
                // Contacts that hold each other: part them all at once.
                const Vector joint =
                  joint_reflection_normal(system.touching_constraints(q),
                                          v,
                                          system.inverse_mass());
                reflect(joint.linfty_norm() > 0. ? joint : contact->normal);
              }
            ++n_constraint_events;
            continue;
          }
        if (!contact && k > 0 && crossing.direction != 0 && crossing.s == 0.)
          {
            const std::uint64_t n_jumps = n_climbs + n_descents + n_reflections;
            jump_at_level(crossing.direction);
            // (A touch without a jump leaves the search's answer as it was.)
            if (n_climbs + n_descents + n_reflections > n_jumps)
              continue;
          }
        break;
      }

    // The flight.
    t_previous     = t;
    level_flight   = level;
    const double s = contact ? contact->s : s_level;
    for_each_kept_range(system, [&](const BlockRange kept) {
      for (unsigned int i = kept.begin; i < kept.end; ++i)
        {
          q_start[i]  = q[i];
          v_flight[i] = v[i];
          q[i] += s * v[i];
        }
    });
    t = (s == horizon) ? t_limit : t + s;
    if (s > 0.)
      last_flight = s;
    count_step();

    if (contact)
      {
        reflect(contact->normal);
        ++n_constraint_events;
        departure = Departure::interior;
      }
    else if (crossing.direction != 0)
      jump_at_level(crossing.direction);
    else
      departure = Departure::interior;

    if (!all_finite(system, {&v}))
      {
        std::ostringstream message;
        message << "The velocity became non-finite at t = " << t << ".";
        throw UnstableRun(message.str());
      }
  }



  void
  EnergyStepping::complete_state()
  {
    for (Vector *x : {&q, &v, &q_start, &v_flight})
      system.complete_state(*x);
  }



  double
  EnergyStepping::measure_force_mass_norm()
  {
    system.kept_gradient(q, gradient_buffer);
    return slope_and_mass_norm(gradient_buffer).second;
  }



  void
  EnergyStepping::jump_at_level(const int direction)
  {
    system.kept_gradient(q, gradient_buffer);
    ++n_gradients;
    const auto [a, m] = slope_and_mass_norm(gradient_buffer);
    if (!std::isfinite(a) || !std::isfinite(m))
      {
        // The flight ended on a level where, to round-off, the configuration
        // is no longer admissible (a cell at the edge of inversion).
        std::ostringstream message;
        message << "The configuration became inadmissible at t = " << t
                << ": its potential energy is " << system.energy(q)
                << " and its gradient is not finite (an element inverted or "
                   "degenerated, e.g. a material too soft for the loads on "
                   "it).";
        throw UnstableRun(message.str());
      }

    double lambda = 0.;
    if (direction > 0)
      {
        if (a <= 0. || m == 0.)
          {
            // Touching the upper level without moving up through it: nothing to
            // do.
            departure = Departure::from_upper_level;
            return;
          }
        const double discriminant = a * a - 2. * h * m;
        if (discriminant >= 0.)
          {
            lambda = (-a + std::sqrt(discriminant)) / m;
            ++level;
            ++n_climbs;
            stay      = StayAtLevel{t, t, 0};
            departure = Departure::from_lower_level;
          }
        else
          {
            lambda = -2. * a / m;
            ++n_reflections;
            stay.to = t;
            if (++stay.reflections > longest_stay.reflections)
              longest_stay = stay;
            departure = Departure::from_upper_level;
          }
      }
    else
      {
        if (a >= 0. || m == 0.)
          {
            departure = Departure::from_lower_level;
            return;
          }
        lambda = (-a - std::sqrt(a * a + 2. * h * m)) / m;
        --level;
        ++n_descents;
        stay      = StayAtLevel{t, t, 0};
        departure = Departure::from_upper_level;
      }

    add_impulse(lambda, gradient_buffer);
  }



  void
  EnergyStepping::reflect(const Vector &normal)
  {
    const auto [a, m] = slope_and_mass_norm(normal);
    if (m == 0.)
      return;
    add_impulse(-2. * a / m, normal);
  }



  std::pair<double, double>
  EnergyStepping::slope_and_mass_norm(const Vector &g) const
  {
    // Block by block (of degrees of freedom), the partial sums added in
    // block order: the same bits on any number of threads.
    struct Sums
    {
      double a, m;
      Sums &
      operator+=(const Sums &other)
      {
        a += other.a;
        m += other.m;
        return *this;
      }
    };
    const Vector &inverse_mass = system.inverse_mass();
    const Sums    sums =
      sum_over_coordinate_blocks<Sums>(system, [&](const unsigned int b) {
        const BlockRange dofs = block_range(b, v.size());
        Sums             block{0., 0.};
        for (unsigned int i = dofs.begin; i < dofs.end; ++i)
          {
            block.a += g[i] * v[i];
            block.m += g[i] * g[i] * inverse_mass[i];
          }
        return block;
      });
    return {sums.a, sums.m};
  }



  void
  EnergyStepping::add_impulse(const double lambda, const Vector &g)
  {
    const Vector &inverse_mass = system.inverse_mass();
    for_each_kept_range(system, [&](const BlockRange kept) {
      for (unsigned int i = kept.begin; i < kept.end; ++i)
        v[i] += lambda * inverse_mass[i] * g[i];
    });
  }



  Snapshot
  EnergyStepping::dense_output(const double time) const
  {
    Snapshot snapshot                  = dense_state(time);
    snapshot.kinetic_energy            = kinetic_energy(system, snapshot.v);
    snapshot.potential_energy          = system.energy(snapshot.q);
    snapshot.terraced_potential_energy = level_height(level_flight);
    return snapshot;
  }



  bool
  EnergyStepping::follows_constraint_events() const
  {
    return true;
  }



  Snapshot
  EnergyStepping::dense_state(const double time) const
  {
    Snapshot snapshot;
    snapshot.t = time;
    if (time == t)
      // The end of the flight exactly as the step computed it (time -
      // t_previous may round differently from the flight's length: a point
      // that the step stopped in front of an obstacle would seem behind it).
      snapshot.q = q;
    else
      {
        snapshot.q = q_start;
        snapshot.q.add(time - t_previous, v_flight);
      }
    snapshot.v = v_flight;
    system.complete_state(snapshot.q);
    system.complete_state(snapshot.v);
    snapshot.kinetic_energy = snapshot.potential_energy =
      snapshot.terraced_potential_energy =
        std::numeric_limits<double>::quiet_NaN();
    return snapshot;
  }



  double
  EnergyStepping::terraced_energy() const
  {
    return kinetic_energy(system, v) + level_height(level);
  }



  std::vector<Counter>
  EnergyStepping::counters() const
  {
    std::vector<Counter> counts = {
      {"steps", steps},
      {"climbs", n_climbs},
      {"descents", n_descents},
      {"reflections", n_reflections},
      {"constraint events", n_constraint_events},
      // Levels reached without a jump: the flight touched the level and
      // turned back (its slope through it was zero up to round-off).
      {"touches without a jump",
       n_gradients - n_climbs - n_descents - n_reflections},
      {"energy evaluations", search_statistics.n_value_evaluations},
      {"enclosures", search_statistics.n_enclosures},
      {"locating evaluations", search_statistics.n_locate_evaluations},
      {"most intervals in one search",
       search_statistics.max_intervals_in_one_search},
      {"gradient evaluations", n_gradients}};
    if (audit)
      counts.emplace_back("crossings stepped over (audit)", n_stepped_over);
    return counts;
  }



  void
  EnergyStepping::add_energies_to_summary(JsonObject &energies) const
  {
    energies.add("energy step", h)
      .add("terrace offset", c)
      .add("initial terraced energy", E_h0)
      .add("final terraced energy", terraced_energy())
      .add("terraced energy drift",
           relative_drift(E_h0, terraced_energy(), energy_scale));
    if (longest_stay.reflections > 0)
      energies.add("longest stay at one level",
                   JsonObject()
                     .add("from", longest_stay.from)
                     .add("to", longest_stay.to)
                     .add("reflections", longest_stay.reflections));
  }



  std::vector<std::string>
  EnergyStepping::warnings() const
  {
    std::vector<std::string> found = TimeIntegrator::warnings();
    if (h > energy_scale)
      {
        std::ostringstream text;
        text << "Time integration/Energy stepping/Energy step: h = " << h
             << " exceeds the initial energy scale |T| + |V| = " << energy_scale
             << " of the system: its terraces are coarser than the motion and "
                "the results say little.";
        found.push_back(text.str());
      }
    if (const double penalty = system.penalty_energy_scale(); h > penalty)
      {
        std::ostringstream text;
        text << "Time integration/Energy stepping/Energy step: h = " << h
             << " exceeds the energy " << penalty
             << " that the contact penalty stores in an intersection one "
                "boundary edge deep (Contact/Penalty parameter): a flight "
                "may carry bodies through each other within one step, "
                "unseen; take a smaller penalty parameter or energy step.";
        found.push_back(text.str());
      }
    // No level crossed: between levels the terraced potential exerts no
    // force, and the run was one straight flight at the initial velocity.
    // Worth a word when the forces at the start, acting from rest for as
    // long, would have given more than a level's worth of kinetic energy.
    if (const double span = t - stay.from;
        n_climbs + n_descents + n_reflections + n_constraint_events == 0 &&
        0.5 * force_mass_norm * span * span > h)
      {
        std::ostringstream text;
        text << "Energy stepping: the system crossed no level from t = "
             << stay.from << " to " << t << ", and "
             << (v.linfty_norm() == 0. ?
                   "stayed exactly where it was, at rest" :
                   "flew straight at its initial velocity")
             << ", whatever the forces on it: between levels the terraced "
                "potential exerts none. From rest, the forces at the start "
                "would have given it a kinetic energy of "
             << 0.5 * force_mass_norm * span * span
             << " in that time, more than the energy step h = " << h
             << ". Its velocity runs along a level of V (zero, or sideways "
                "under gravity): give it a component along the forces, "
                "however small.";
        found.push_back(text.str());
      }
    // Only reflections, not one climb or descent: the motion is held between
    // two levels (doc/scenes.md). Else mostly reflections: the motion keeps
    // bouncing off the level above instead of climbing and descending through
    // the terraces. Either way, where the levels lie decides it
    // (doc/spinning_cube.md).
    const std::uint64_t crossings = n_climbs + n_descents + n_reflections;
    if (n_climbs + n_descents == 0 &&
        n_reflections >= min_reflections_for_held_warning)
      {
        std::ostringstream text;
        text << "Time integration/Energy stepping/Energy step: all "
             << n_reflections
             << " level crossings were reflections, none climbed or "
                "descended: the motion is held between two levels, h = "
             << h
             << " apart, and exchanges no energy across them; where the "
                "levels lie (Terrace offset) decides what it does. A smaller "
                "energy step follows the motion.";
        found.push_back(text.str());
      }
    else if (crossings >= min_crossings_for_reflection_warning &&
             static_cast<double>(n_reflections) >
               reflection_warning_share * static_cast<double>(crossings))
      {
        std::ostringstream text;
        text << "Time integration/Energy stepping/Energy step: "
             << n_reflections << " of the " << crossings
             << " level crossings were reflections (more than "
             << 100. * reflection_warning_share
             << " %): the motion keeps reflecting off a level, and at this "
                "energy step it depends on where the levels lie (Terrace "
                "offset); a smaller energy step gives a result that does not.";
        found.push_back(text.str());
      }
    return found;
  }



  std::string
  EnergyStepping::conserved_energy() const
  {
    return "T + L h";
  }



  namespace
  {
    void
    declare_energy_stepping_parameters(dealii::ParameterHandler &prm)
    {
      const double max = dealii::Patterns::Double::max_double_value;
      prm.enter_subsection("Energy stepping");
      prm.declare_entry(
        "Energy step",
        "1e-3",
        dealii::Patterns::Double(0., max),
        "Energy step h (energy units of the system); must be positive. "
        "The time steps follow from it.");
      prm.declare_entry(
        "Terrace offset",
        "0",
        dealii::Patterns::Double(0., 1.),
        "Where the levels lie, as a fraction c of the energy step: at (k + "
        "c) h for every integer k. This is the additive constant of V that "
        "the method leaves free; 0 puts the levels at the integer multiples "
        "of h. Must be smaller than 1.");
      prm.declare_entry(
        "Crossing search",
        "certified",
        dealii::Patterns::Selection("certified|sampled"),
        "How the next level crossing of a flight is found. certified: a "
        "search on rigorous enclosures of V along the flight that never "
        "misses a crossing (the default). sampled: the reference text's "
        "way, kept as a comparison: V sampled at Samples per window equally "
        "spaced points of windows doubling from twice the previous step, "
        "the first bracket bisected (Bisection steps); it steps over "
        "crossings that come back between two samples (grazing ones).");
      const SamplingSettings sampling;
      prm.declare_entry(
        "Samples per window",
        std::to_string(sampling.samples_per_window),
        dealii::Patterns::Integer(1, 1000000),
        "Sampled search only (a warning otherwise): samples of V per "
        "search window.");
      prm.declare_entry(
        "Bisection steps",
        std::to_string(sampling.bisection_steps),
        dealii::Patterns::Integer(1, 1000),
        "Sampled search only (a warning otherwise): the most bisections "
        "locating a bracketed "
        "crossing (fewer once the bracket reaches the round-off of the "
        "time).");
      prm.declare_entry(
        "Audit sampled search",
        "false",
        dealii::Patterns::Bool(),
        "Sampled search only (an error otherwise): search every flight "
        "with the certified search "
        "too and count in summary.json the crossings the sampled search "
        "stepped over (crossings stepped over (audit)); the run follows the "
        "sampled answers. Costs about one certified search per step more.");
      prm.leave_subsection();
    }

    std::unique_ptr<TimeIntegrator>
    create_energy_stepping(dealii::ParameterHandler &prm,
                           const MechanicalSystem   &system)
    {
      prm.enter_subsection("Energy stepping");
      const double     h       = prm.get_double("Energy step");
      const double     c       = prm.get_double("Terrace offset");
      const bool       sampled = prm.get("Crossing search") == "sampled";
      SamplingSettings sampling;
      sampling.samples_per_window = prm.get_integer("Samples per window");
      sampling.bisection_steps    = prm.get_integer("Bisection steps");
      const bool audit            = prm.get_bool("Audit sampled search");
      prm.leave_subsection();
      if (!(h > 0.))
        throw std::runtime_error(
          "Time integration/Energy stepping/Energy step: must be positive.");
      if (!(c < 1.))
        throw std::runtime_error("Time integration/Energy stepping/Terrace "
                                 "offset: must be smaller than 1.");
      if (audit && !sampled)
        throw std::runtime_error(
          "Time integration/Energy stepping/Audit sampled search: audits the "
          "sampled search; set Crossing search = sampled.");
      auto integrator = std::make_unique<EnergyStepping>(system, h, c);
      const std::string section = "Time integration/Energy stepping";
      integrator->record_unread_settings(
        entries_unread_by_type(prm,
                               {{section,
                                 {{"Samples per window", {"sampled"}},
                                  {"Bisection steps", {"sampled"}}},
                                 section + "/Crossing search"}}));
      if (sampled)
        integrator->use_sampled_search(sampling, audit);
      return integrator;
    }
  } // namespace
} // namespace estep

ESTEP_REGISTER_INTEGRATOR(
  "energy stepping",
  "the exact flow of the terraced potential (k + c) h, k = floor(V/h - c): "
  "straight flights between level crossings found by a certified search, "
  "momentum jumps at the crossings (subsection Energy stepping).",
  estep::declare_energy_stepping_parameters,
  estep::create_energy_stepping)
