#ifndef estep_time_integration_energy_stepping_h
#define estep_time_integration_energy_stepping_h

#include <estep/time_integration/first_crossing_search.h>
#include <estep/time_integration/sampled_crossing_search.h>
#include <estep/time_integration/time_integrator.h>

#include <optional>
#include <utility>

namespace estep
{
  /**
   * Energy-stepping (Gonzalez, Schmidt and Ortiz, 2010): the exact motion of
   * the terraced potential V_h(q) = h (floor(V(q) / h - c) + c), whose levels
   * lie at (L + c) h. The terrace offset c in [0, 1) is the additive constant
   * of V that the method leaves free (0 in the reference text).
   *
   * Between events the motion is free flight, q(t) = q_k + (t - t_k) v_k. The
   * next event is the first level crossing found by find_first_crossing()
   * (certified: no crossing is missed) or the first constraint event of the
   * system, whichever comes first. At a level crossing q*, with n = grad V(q*),
   * a = n . v and m = n^T M^-1 n:
   * - climbing by dV = +h when a^2 >= 2 h m: v += lambda M^-1 n with
   *   lambda = (-a + sqrt(a^2 - 2 h m)) / m, and L += 1;
   * - otherwise reflecting: lambda = -2 a / m, L unchanged;
   * - descending by dV = -h: lambda = (-a - sqrt(a^2 + 2 h m)) / m, and L -= 1.
   * At a constraint event the velocity reflects on the constraint normal; a
   * further event at the same instant (another contact touching and
   * approaching) is reflected on at once and the flight searched again, so
   * that simultaneous contacts make no zero-length steps. Such a reflection
   * does not move q: the flight still departs from the level it sat on, and
   * if the new velocity carries it back through that level at once, the jump
   * there is made at the same instant as well. The
   * terrace index L is an integer carried from event to event, never recomputed
   * from V.
   *
   * Exactly conserved, up to round-off: E_h = 1/2 v^T M v + (L + c) h, and the
   * linear and angular momenta of systems whose V is invariant under
   * translations and rotations.
   */
  class EnergyStepping : public TimeIntegrator
  {
  public:
    /**
     * @param energy_step The energy step h > 0 (energy units of the system).
     * @param terrace_offset The offset c in [0, 1) of the levels (L + c) h.
     */
    EnergyStepping(const MechanicalSystem &system,
                   const double            energy_step,
                   const double            terrace_offset = 0.);

    /**
     * Find crossings by sampling (find_first_crossing_by_sampling(), the
     * reference text's way, which can step over grazing crossings) instead
     * of the certified search. With @p audit, every flight is searched by the
     * certified search as well, and the crossings the sampled search stepped
     * over are counted (the run follows the sampled answers).
     */
    void
    use_sampled_search(const SamplingSettings &settings, const bool audit);

    std::string
    name() const override;

    /** Set the state; the terrace index becomes floor(V(q0) / h - c) once,
     * here. */
    void
    initialize(const double t0, const Vector &q0, const Vector &v0) override;

    /** Free flight to the next event and the momentum jump there, or free
     * flight to t_limit if no event comes before it. */
    void
    step(const double t_limit) override;

    /** On several MPI ranks that share the system's state, a step updates
     * only the coordinates this rank keeps (kept_coordinates()); dense
     * output and this fill in the others. */
    void
    complete_state() override;

    /** Exact: free-flight interpolation on the last flight. */
    Snapshot
    dense_output(const double t) const override;

    Snapshot
    dense_state(const double t) const override;

    /** True: a step ends at the first constraint event and reflects. */
    bool
    follows_constraint_events() const override;

    std::vector<Counter>
    counters() const override;

    /** Energy step, terrace offset, the terraced energy at the start and
     * the end with its drift, and the longest stay at one level with
     * reflections. */
    void
    add_energies_to_summary(JsonObject &energies) const override;

    /**
     * A warning when h exceeds the initial |T| + |V|, one when it exceeds the
     * system's penalty_energy_scale() (a penalty too soft for the terraces to
     * see an element-deep intersection), and one when the run so far has
     * mostly reflected: of at least min_crossings_for_reflection_warning
     * level crossings, more than the share reflection_warning_share were
     * reflections. The result then depends on the terrace offset
     * (doc/spinning_cube.md). In its place, when no crossing has climbed or
     * descended and at least min_reflections_for_held_warning have reflected,
     * one saying that the motion is held between two levels (doc/scenes.md).
     * And one when the run crossed no level at all although its forces at
     * the start, acting from rest over that time, would have given it more
     * than an energy step of kinetic energy: a flight along a level of V
     * (released at rest, or moving sideways under gravity).
     */
    std::vector<std::string>
    warnings() const override;

    static constexpr std::uint64_t min_crossings_for_reflection_warning = 100;
    static constexpr double        reflection_warning_share             = 0.9;
    static constexpr std::uint64_t min_reflections_for_held_warning     = 10;

    /** Also the terrace index, the departure, the last flight and the
     * counters. */
    void
    save_state(StateWriter &out) const override;

    void
    load_state(StateReader &in) override;

    /** The terraced energy, "T + L h". */
    std::string
    conserved_energy() const override;

    /** The current terrace index L ((L + c) h <= V < (L + 1 + c) h up to the
     * root tolerance). */
    long long
    terrace_index() const
    {
      return level;
    }

    /** The energy step h. */
    double
    energy_step() const
    {
      return h;
    }

    /** The height (L + c) h of level L. */
    double
    level_height(const long long L) const
    {
      return (static_cast<double>(L) + c) * h;
    }

    /** E_h = T + (L + c) h, the exactly conserved energy. */
    double
    terraced_energy() const;

    /** E_h at the start of the run. */
    double
    initial_terraced_energy() const
    {
      return E_h0;
    }

  private:
    /** Apply the momentum jump at the current point for a crossing in @p
     * direction. */
    void
    jump_at_level(const int direction);

    /** The most events (constraint reflections and the level jumps they
     * cause) resolved at one instant before a step; a contact still touching
     * and approaching after them stalls the run (StalledRun). */
    static constexpr unsigned int max_simultaneous_events = 1000;

    /** The reflections at one instant off the contact pair that
     * first_constraint_event() reports; after them, each reflection is off
     * all the constraints touching (MechanicalSystem::touching_constraints()
     * and joint_reflection_normal()). */
    static constexpr unsigned int reflections_one_pair_at_a_time = 64;

    /** Reflect the velocity on a constraint @p normal. */
    void
    reflect(const Vector &normal);

    /** a = g . v and m = g . M^-1 g, summed over fixed blocks of degrees of
     * freedom in block order. */
    std::pair<double, double>
    slope_and_mass_norm(const Vector &g) const;

    /** f . M^-1 f of the forces at q (one gradient, not counted: set-up). */
    double
    measure_force_mass_norm();

    /** v += lambda M^-1 g. */
    void
    add_impulse(const double lambda, const Vector &g);

    const double h;
    const double c;
    double       E_h0 = 0.;
    /** |T| + |V| at the start: the scale of the energies. */
    double energy_scale = 0.;
    /** f . M^-1 f of the forces f = -grad V where the run started (or was
     * resumed): from rest, such forces give a kinetic energy of (1/2) this
     * s^2 in a time s. */
    double    force_mass_norm = 0.;
    long long level           = 0;
    Departure departure       = Departure::interior;
    /** The last flight of positive length (0 before the first): twice it is
     * the next search's first window. */
    double last_flight = 0.;

    // The last flight: it started at (t_previous, q_start) with velocity
    // v_flight on level level_flight.
    Vector    q_start, v_flight;
    long long level_flight = 0;

    mutable Vector   gradient_buffer;
    SearchStatistics search_statistics;
    /** The sampled search, if chosen, and its audit. */
    std::optional<SamplingSettings> sampling;
    bool                            audit          = false;
    std::uint64_t                   n_stepped_over = 0;
    /** The next event of the flight (q, v) as the chosen search finds it. */
    Crossing
                  search(const FreeFlight &flight, const CrossingQuery &query);
    std::uint64_t n_climbs = 0, n_descents = 0, n_reflections = 0,
                  n_constraint_events = 0, n_gradients = 0;

    /**
     * A stay at one level: the time of the last climb or descent (or of the
     * start) and the reflections since. The longest stay with reflections so
     * far, in reflections, goes to the summary: a motion held between two
     * levels for a stretch of the run (doc/scenes.md).
     */
    struct StayAtLevel
    {
      double        from = 0., to = 0.;
      std::uint64_t reflections = 0;
    };
    StayAtLevel stay, longest_stay;
  };
} // namespace estep

#endif
