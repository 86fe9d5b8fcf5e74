#include <deal.II/base/parameter_handler.h>

#include <estep/base/distributed_blocks.h>
#include <estep/fem/elastic_body.h>
#include <estep/materials/material_registry.h>
#include <estep/problems/problem.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace estep
{
  PluginRegistry<ProblemFactory> &
  problem_registry()
  {
    static PluginRegistry<ProblemFactory> registry("problem");
    return registry;
  }



  void
  declare_problem_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Problem");
    prm.declare_entry(
      "System",
      "argon cluster",
      dealii::Patterns::Selection(problem_registry().names()),
      "The mechanical system to integrate, one of the registered problems; "
      "each reads its own subsection:" +
        problem_registry().descriptions());
    prm.leave_subsection();
    declare_material_subsection(prm);
    problem_registry().declare_parameters(prm);
  }



  void
  declare_material_subsection(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    declare_material_parameters(prm);
    prm.leave_subsection();
  }



  TypeReaders
  initial_velocity_type_readers()
  {
    return {{"Translational velocity", {"rigid motion"}},
            {"Angular velocity", {"rigid motion"}},
            {"Rotation centre", {"rigid motion"}},
            {"Function expression", {"function"}},
            {"Variable names", {"function"}},
            {"Function constants", {"function"}}};
  }



  std::string
  tracked_point_warning(const ElasticBody           &body,
                        const std::string           &entry,
                        const std::array<double, 3> &X)
  {
    const auto [lower, upper] = body.reference_bounding_box();
    double side = 0., outside = 0.;
    for (unsigned int c = 0; c < 3; ++c)
      {
        side = std::max(side, upper[c] - lower[c]);
        outside +=
          std::pow(std::max({lower[c] - X[c], X[c] - upper[c], 0.}), 2);
      }
    outside = std::sqrt(outside);
    if (!(outside > 0.25 * side))
      return "";
    std::ostringstream text;
    text << entry << ": the point " << X[0] << ", " << X[1] << ", " << X[2]
         << " lies " << outside << " outside the body's bounding box (sides up "
         << "to " << side << "); the body's point nearest to it is tracked.";
    return text.str();
  }



  Problem
  create_problem(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Problem");
    const std::string name = prm.get("System");
    prm.leave_subsection();
    const auto &chosen = problem_registry().get(name, "Problem/System");

    // The subsections that only the other problems declare keep their
    // defaults: a setting there would be ignored.
    for (const UnreadSubsection &unread : changed_unread_subsections(
           prm, problem_registry().declarations(), {name}))
      throw std::runtime_error(
        unread_subsection_text("", unread, "Problem/System = " + name) +
        "; a setting there would be ignored.");
    Problem problem = chosen.create(prm);
    problem.name    = name;
    // On several MPI ranks, the coordinates of the state each keeps current
    // where the system shares it (MechanicalSystem::kept_coordinates()).
    if (rank_count() > 1)
      if (const std::vector<BlockRange> *kept =
            problem.system->kept_coordinates())
        {
          double count = 0.;
          for (const BlockRange range : *kept)
            count += range.end - range.begin;
          problem.description.add("coordinates kept by each process",
                                  values_of_every_rank(count));
        }
    return problem;
  }
} // namespace estep
