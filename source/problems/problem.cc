#include <deal.II/base/parameter_handler.h>

#include <estep/materials/material_registry.h>
#include <estep/problems/problem.h>

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



  std::map<std::string, std::vector<std::string>>
  printed_subsections(const dealii::ParameterHandler &prm,
                      const std::string              &section)
  {
    std::ostringstream text;
    prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
    std::istringstream in(text.str());
    const std::string  indent  = section.empty() ? "" : "  ";
    const std::string  opening = indent + "subsection ";
    std::map<std::string, std::vector<std::string>> sections;
    std::vector<std::string>                       *current   = nullptr;
    bool                                            in_parent = section.empty();
    for (std::string line; std::getline(in, line);)
      if (!section.empty() && line == "subsection " + section)
        in_parent = true;
      else if (!section.empty() && line == "end")
        in_parent = false;
      else if (in_parent && current == nullptr && line.rfind(opening, 0) == 0)
        current = &sections[line.substr(opening.size())];
      else if (current != nullptr && line == indent + "end")
        current = nullptr;
      else if (current != nullptr)
        current->push_back(line);
    return sections;
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
    const auto sections_of = [](const auto &plugin) {
      dealii::ParameterHandler declared;
      if (plugin.declare_parameters != nullptr)
        plugin.declare_parameters(declared);
      return printed_subsections(declared);
    };
    const auto own   = sections_of(chosen);
    const auto given = printed_subsections(prm);
    // Per subsection the chosen problem does not read: the problems that do,
    // and whether it differs from the defaults of one of them.
    std::map<std::string, std::pair<std::vector<std::string>, bool>> others;
    for (const auto &other : problem_registry().plugins())
      for (const auto &[section, defaults] : sections_of(other))
        if (own.count(section) == 0 && given.count(section) > 0)
          {
            auto &[readers, set] = others[section];
            readers.push_back(other.name);
            set = set || given.at(section) != defaults;
          }
    for (const auto &[section, readers_and_set] : others)
      if (const auto &[readers, set] = readers_and_set; set)
        {
          std::string names = readers[0];
          for (std::size_t i = 1; i < readers.size(); ++i)
            names += (i + 1 == readers.size() ? " and " : ", ") + readers[i];
          throw std::runtime_error(section + ": Problem/System = " + name +
                                   " does not read this subsection (" + names +
                                   (readers.size() == 1 ? " does" : " do") +
                                   "); a setting there would be ignored.");
        }
    return chosen.create(prm);
  }
} // namespace estep
