#include <deal.II/base/parameter_handler.h>

#include <estep/materials/material_registry.h>
#include <estep/problems/problem.h>

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
    prm.enter_subsection("Material");
    declare_material_parameters(prm);
    prm.leave_subsection();
    problem_registry().declare_parameters(prm);
  }



  Problem
  create_problem(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Problem");
    const std::string name = prm.get("System");
    prm.leave_subsection();
    return problem_registry().get(name, "Problem/System").create(prm);
  }
} // namespace estep
