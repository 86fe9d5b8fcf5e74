#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <estep/io/postprocessor.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace estep
{
  void
  Postprocessor::start()
  {}



  void
  Postprocessor::save_state(StateWriter &) const
  {}



  void
  Postprocessor::resume(StateReader &)
  {
    start();
  }



  void
  Postprocessor::finish(const TimeLoopResult &)
  {}



  void
  Postprocessor::add_to_summary(JsonObject &) const
  {}



  bool
  Postprocessor::runs_on_every_rank() const
  {
    return false;
  }



  std::string
  Postprocessor::final_report() const
  {
    return "";
  }



  std::vector<std::size_t>
  start_order(const std::vector<std::unique_ptr<Postprocessor>> &postprocessors)
  {
    std::vector<std::size_t> order(postprocessors.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_partition(order.begin(), order.end(), [&](const std::size_t i) {
      return postprocessors[i]->runs_on_every_rank();
    });
    return order;
  }



  PluginRegistry<PostprocessorFactory> &
  postprocessor_registry()
  {
    static PluginRegistry<PostprocessorFactory> registry("postprocessor");
    return registry;
  }



  void
  declare_postprocessor_parameters(dealii::ParameterHandler &prm)
  {
    prm.declare_entry(
      "List",
      "history, step histogram, progress, contact monitor",
      dealii::Patterns::MultipleSelection(postprocessor_registry().names()),
      "The postprocessors of the run, separated by commas; each reads its "
      "own subsection:" +
        postprocessor_registry().descriptions());
    postprocessor_registry().declare_parameters(prm);
  }



  std::vector<std::string>
  ignored_postprocessor_settings(dealii::ParameterHandler &prm)
  {
    const std::string        list = prm.get("List");
    std::vector<std::string> warnings;
    for (const UnreadSubsection &unread :
         changed_unread_subsections(prm,
                                    postprocessor_registry().declarations(),
                                    dealii::Utilities::split_string_list(list,
                                                                         ',')))
      warnings.push_back("Postprocessors/" + unread.name +
                         ": set, but Postprocessors/List = " + list +
                         " does not name " + unread.readers[0] +
                         ", which reads it; its settings are ignored.");
    return warnings;
  }



  std::vector<std::unique_ptr<Postprocessor>>
  create_postprocessors(dealii::ParameterHandler   &prm,
                        const PostprocessorContext &context)
  {
    std::vector<std::string>                    names;
    std::vector<std::unique_ptr<Postprocessor>> postprocessors;
    for (const std::string &name :
         dealii::Utilities::split_string_list(prm.get("List"), ','))
      {
        if (std::find(names.begin(), names.end(), name) != names.end())
          throw std::runtime_error("Postprocessors/List: <" + name +
                                   "> is listed twice.");
        names.push_back(name);
        auto postprocessor = postprocessor_registry()
                               .get(name, "Postprocessors/List")
                               .create(prm, context);
        if (postprocessor)
          postprocessors.push_back(std::move(postprocessor));
      }
    return postprocessors;
  }
} // namespace estep
