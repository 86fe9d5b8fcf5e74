#include <estep/base/config.h>
#include <estep/base/distributed_blocks.h>
#include <estep/base/lanes.h>
#include <estep/io/run_summary.h>

#include <sys/resource.h>

#include <algorithm>
#include <cmath>

namespace estep
{
  namespace
  {
    /** The largest resident memory of this process so far, in MiB. */
    double
    peak_memory_mib()
    {
      rusage usage;
      getrusage(RUSAGE_SELF, &usage);
      return usage.ru_maxrss / 1024.; // Linux reports KiB
    }

    JsonObject
    momenta_json(const Momenta &m)
    {
      return JsonObject()
        .add("linear", std::vector<double>(m.linear, m.linear + 3))
        .add("angular", std::vector<double>(m.angular, m.angular + 3));
    }

    double
    largest_difference(const double *a, const double *b)
    {
      double largest = 0.;
      for (unsigned int c = 0; c < 3; ++c)
        largest = std::max(largest, std::abs(b[c] - a[c]));
      return largest;
    }
  } // namespace



  JsonObject
  status_summary(const RunRecord   &run,
                 const std::string &status,
                 const std::string &message)
  {
    JsonObject summary;
    summary.add("estep version", ESTEP_VERSION)
      .add("status", status)
      .add("message", message)
      .add("system", run.problem.name)
      .add("method", run.integrator.name())
      .add("start time", run.start_time)
      .add("end time", run.end_time);
    if (run.resumed_from_time)
      summary.add("resumed from time", *run.resumed_from_time);
    return summary;
  }



  JsonObject
  run_summary(const RunRecord &run, const TimeLoopResult &result)
  {
    const MechanicalSystem &system     = *run.problem.system;
    const TimeIntegrator   &integrator = run.integrator;
    const Vector           &q0 = run.problem.q0, &v0 = run.problem.v0;
    const Vector &q = integrator.position(), &v = integrator.velocity();

    JsonObject summary =
      status_summary(run, to_string(result.status), result.message);
    std::vector<std::string> warnings = integrator.warnings();
    warnings.insert(warnings.end(),
                    result.warnings.begin(),
                    result.warnings.end());
    warnings.insert(warnings.end(),
                    run.input_warnings.begin(),
                    run.input_warnings.end());
    summary.add("warnings", warnings);
    summary.add("problem", run.problem.description)
      .add("degrees of freedom", system.n_dofs())
      .add("final time", result.final_time)
      .add("wall seconds", result.wall_seconds)
      .add("threads", thread_count())
      .add("MPI processes", rank_count())
      .add("cell kernels", lane_kernel_target())
      .add("peak memory [MiB]", peak_memory_mib());

    JsonObject counters;
    for (const auto &[name, count] : integrator.counters())
      counters.add(name, count);
    summary.add("counters", counters);
    const double elapsed = result.final_time - run.start_time;
    summary
      .add("mean step",
           integrator.n_steps() ? elapsed / integrator.n_steps() : 0.)
      .add("min step", integrator.min_step())
      .add("max step", integrator.max_step());

    const double T0 = kinetic_energy(system, v0), V0 = system.energy(q0);
    const double T1 = kinetic_energy(system, v), V1 = system.energy(q);
    JsonObject   energies;
    energies.add("initial kinetic", T0)
      .add("initial potential", V0)
      .add("final kinetic", T1)
      .add("final potential", V1)
      .add("total energy drift",
           relative_drift(T0 + V0, T1 + V1, std::abs(T0) + std::abs(V0)))
      .add("largest energy drift", result.largest_energy_drift)
      .add("largest energy drift time", result.largest_energy_drift_time);
    integrator.add_energies_to_summary(energies);
    summary.add("energies", energies);

    const Momenta momenta0 = compute_momenta(system, q0, v0);
    const Momenta momenta1 = compute_momenta(system, q, v);
    summary.add("initial momenta", momenta_json(momenta0))
      .add("final momenta", momenta_json(momenta1))
      .add("linear momentum drift",
           largest_difference(momenta0.linear, momenta1.linear))
      .add("angular momentum drift",
           largest_difference(momenta0.angular, momenta1.angular));

    for (const auto &postprocessor : run.postprocessors)
      postprocessor->add_to_summary(summary);
    return summary;
  }
} // namespace estep
