#include <deal.II/base/parameter_handler.h>

#include <estep/app/argon_cluster_problem.h>
#include <estep/app/colliding_balls_problem.h>
#include <estep/app/elastic_body_problem.h>
#include <estep/app/problem.h>

#include <stdexcept>

namespace estep
{
  void
  declare_problem_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Problem");
    prm.declare_entry(
      "System",
      "argon cluster",
      dealii::Patterns::Selection("argon cluster|elastic body|colliding balls"),
      "The mechanical system to integrate. Each system reads its own "
      "subsection of the same name.");
    prm.leave_subsection();
    ArgonClusterProblem::declare_parameters(prm);
    ElasticBodyProblem::declare_parameters(prm);
    CollidingBallsProblem::declare_parameters(prm);
  }



  Problem
  create_problem(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Problem");
    const std::string system = prm.get("System");
    prm.leave_subsection();
    if (system == "argon cluster")
      return ArgonClusterProblem::create(prm);
    if (system == "elastic body")
      return ElasticBodyProblem::create(prm);
    if (system == "colliding balls")
      return CollidingBallsProblem::create(prm);
    throw std::runtime_error("Problem/System: unknown system <" + system +
                             ">.");
  }
} // namespace estep
