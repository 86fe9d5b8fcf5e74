#include <estep/app/renamed_entries.h>

#include <utility>

namespace estep
{
  std::string
  renamed_entry_message(const std::string &path)
  {
    // The entries that version 0.1 of the input read elsewhere.
    static const std::pair<const char *, const char *> renamed[] = {
      {"Time integration/Energy step",
       "Time integration/Energy stepping/Energy step"},
      {"Time integration/Terrace offset",
       "Time integration/Energy stepping/Terrace offset"},
      {"Time integration/Time step",
       "Time integration/Explicit Newmark/Time step (explicit newmark) or "
       "Time integration/Implicit integrators/Time step (the implicit "
       "methods)"},
      {"Elastic body/Material/Model", "Material/Model"},
      {"Elastic body/Material/Lambda", "Material/Neo-Hookean/Lambda"},
      {"Elastic body/Material/Mu", "Material/Neo-Hookean/Mu"},
      {"Elastic body/Material/Density", "Material/Density"},
      {"Colliding balls/Lambda", "Material/Neo-Hookean/Lambda"},
      {"Colliding balls/Mu", "Material/Neo-Hookean/Mu"},
      {"Colliding balls/Density", "Material/Density"},
      {"Output/Field output interval",
       "Postprocessors/Field output/Interval, with field output in "
       "Postprocessors/List"},
      {"Output/Field output format", "Postprocessors/Field output/Format"},
      {"Output/H1 norm", "the item h1 norm of Postprocessors/List"},
      {"Output/Progress",
       "Postprocessors/Progress/Mode (leave progress out of "
       "Postprocessors/List for none)"},
      {"Output/Progress interval", "Postprocessors/Progress/Interval"}};
    for (const auto &[old_path, new_path] : renamed)
      if (path == old_path)
        return path + " is now " + new_path + ".";
    const std::string implicit = "Implicit integrators/";
    if (path.compare(0, implicit.size(), implicit) == 0)
      return path + " is now Time integration/" + path + ".";
    return "";
  }
} // namespace estep
