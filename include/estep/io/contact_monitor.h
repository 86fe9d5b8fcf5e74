#ifndef estep_io_contact_monitor_h
#define estep_io_contact_monitor_h

#include <estep/base/json_writer.h>
#include <estep/io/postprocessor.h>

#include <cstdint>
#include <functional>
#include <string>

namespace estep
{
  class ContactSystem;

  /**
   * Watches the contact of a ContactSystem at every step of a run and reports
   * what a collision experiment measures:
   * - the largest number of intersecting pairs of boundary faces at any step
   *   end (the exact test of ContactSystem::n_intersecting_pairs());
   * - when the bodies are in contact: a step end is a contact instant if faces
   *   intersect there (penalty contact) or if the step ended in a constraint
   *   event (exact impenetrability). The contact duration is the time from
   *   the first to the last contact instant; its resolution is the longer of
   *   the step that reached the first instant and the step that followed the
   *   last one;
   * - the coefficient of restitution from the centre-of-mass kinetic energies
   *   (see restitution()).
   */
  class ContactMonitor : public Postprocessor
  {
  public:
    /** The monitor of @p system integrated by @p integrator from (@p q0, @p
     * v0). */
    ContactMonitor(const ContactSystem  &system,
                   const TimeIntegrator &integrator,
                   const Vector         &q0,
                   const Vector         &v0);

    /** The map from a state of the integrated system to one of @p system
     * (when the integrated system is a scene made of it). */
    using StateMap = std::function<
      void(const Vector &q, const Vector &v, Vector &q_c, Vector &v_c)>;

    /** The monitor of @p system inside the integrated system, whose states
     * @p to_contact maps to states of @p system; @p bodies_alone says
     * whether nothing but the bodies exchanges momentum with them (no
     * supports, no obstacles). */
    ContactMonitor(
      const ContactSystem                        &system,
      const TimeIntegrator                       &integrator,
      const Vector                               &q0,
      const Vector                               &v0,
      StateMap                                    to_contact,
      bool                                        bodies_alone,
      std::function<unsigned int(const Vector &)> obstacle_count = nullptr);

    void
    after_step(const TimeIntegrator &integrator) override;

    /** The counts, extremes and contact instants so far. */
    void
    save_state(StateWriter &out) const override;

    void
    resume(StateReader &in) override;

    /** Adds "contact": summary() from the initial to the current state. */
    void
    add_to_summary(JsonObject &summary) const override;

    /** report() from the initial to the current state. */
    std::string
    final_report() const override;

    /**
     * The coefficient of restitution e of a collision from the state (q0, v0)
     * before and (q1, v1) after it: e^2 = T_rel(1) / T_rel(0), with T_rel the
     * kinetic energy of the bodies' centre-of-mass velocities relative to the
     * system's centre of mass. For two equal bodies, one of them at rest, this
     * is the reference text's T_f / T_0 = (1 + e^2) / 2 with T the
     * centre-of-mass kinetic energies. NaN if the bodies do not move relative
     * to each other at the start.
     */
    double
    restitution(const Vector &q0,
                const Vector &v0,
                const Vector &q1,
                const Vector &v1) const;

    /** Whether a collision is over: the bodies have been in contact, and
     * apart since for at least as long as the contact lasted. */
    bool
    contact_over() const;

    /** restitution() once a collision of two bodies alone is over
     * (contact_over()). NaN otherwise: before a first contact, or while one
     * may still go on, there is no collision to measure; with one body, or
     * more than two, or with supports or obstacles, restitution() measures
     * no collision's restitution. */
    double
    collision_restitution(const Vector &q0,
                          const Vector &v0,
                          const Vector &q1,
                          const Vector &v1) const;

    /**
     * The summary of the run: the counts and times above, the restitution
     * between (q0, v0) and (q1, v1) once a collision is over
     * (collision_restitution(); left out otherwise) and the final rigid
     * motion of every body and of the system.
     */
    JsonObject
    summary(const Vector &q0,
            const Vector &v0,
            const Vector &q1,
            const Vector &v1) const;

    /** One line for the terminal with the contact duration, the restitution
     * and the largest count of intersecting pairs. */
    std::string
    report(const Vector &q0,
           const Vector &v0,
           const Vector &q1,
           const Vector &v1) const;

    /** Time from the first to the last contact instant (0 without contact). */
    double
    contact_duration() const;

    /** The longer of the step that reached the first contact instant and the
     * step after the last: how far the contact's start and end may lie from
     * those instants. */
    double
    contact_duration_resolution() const;

  private:
    /** The current state of the integrator, in the coordinates of system. */
    void
    current_state(Vector &q, Vector &v) const;

    const ContactSystem  &system;
    const TimeIntegrator &integrator;
    StateMap              to_contact;
    /** Two bodies that nothing else holds or touches: a collision whose
     * restitution() the monitor reports. */
    bool two_bodies_alone;
    /** Points of the integrated system's state inside obstacles (or
     * nullptr). */
    std::function<unsigned int(const Vector &)> obstacle_count;
    unsigned int                                largest_obstacle_count = 0;
    Vector                                      q0, v0;
    unsigned int                                largest_pair_count     = 0;
    std::uint64_t                               steps_with_pairs       = 0;
    std::uint64_t                               constraint_events_seen = 0;
    /** Whether the previous step end was a contact instant. */
    bool          in_contact                = false;
    std::uint64_t n_contact_instants        = 0;
    double        first_contact             = 0.;
    double        last_contact              = 0.;
    double        step_before_first_contact = 0.;
    double        step_after_last_contact   = 0.;
  };
} // namespace estep

#endif
