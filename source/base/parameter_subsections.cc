#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <estep/base/parameter_subsections.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>
#include <stdexcept>

namespace estep
{
  namespace
  {
    std::string
    trimmed(const std::string &text)
    {
      const std::size_t begin = text.find_first_not_of(' ');
      if (begin == std::string::npos)
        return "";
      return text.substr(begin, text.find_last_not_of(' ') - begin + 1);
    }

    /** A printed line without its indentation, and an entry's without the
     * padding that aligns the '=' of a subsection. */
    std::string
    normalized(const std::string &line)
    {
      const std::string text   = trimmed(line);
      const std::size_t equals = text.find('=');
      if (text.rfind("set ", 0) != 0 || equals == std::string::npos)
        return text;
      return trimmed(text.substr(0, equals)) + " = " +
             trimmed(text.substr(equals + 1));
    }

    /**
     * Whether an entry of the subsection @p section of the current
     * subsection of @p prm has another value than in @p lines, the printed
     * lines of that subsection in a handler of the same declarations (see
     * printed_subsections()). Reads only that subsection's entries.
     */
    bool
    differs_from(dealii::ParameterHandler       &prm,
                 const std::string              &section,
                 const std::vector<std::string> &lines)
    {
      prm.enter_subsection(section);
      unsigned int depth   = 1;
      bool         differs = false;
      try
        {
          for (const std::string &line : lines)
            if (line.rfind("subsection ", 0) == 0)
              {
                prm.enter_subsection(trimmed(line.substr(11)));
                ++depth;
              }
            else if (line == "end")
              {
                prm.leave_subsection();
                --depth;
              }
            else if (const std::size_t equals = line.find(" = ");
                     line.rfind("set ", 0) == 0 && equals != std::string::npos)
              differs =
                differs || trimmed(prm.get(line.substr(4, equals - 4))) !=
                             line.substr(equals + 3);
        }
      catch (...)
        {
          for (; depth > 0; --depth)
            prm.leave_subsection();
          throw;
        }
      for (; depth > 0; --depth)
        prm.leave_subsection();
      return differs;
    }

    /** "a does", "a and b do", "a, b and c do". */
    std::string
    readers_text(const std::vector<std::string> &names)
    {
      std::string text;
      for (std::size_t i = 0; i < names.size(); ++i)
        text += (i == 0                ? "" :
                 i + 1 == names.size() ? " and " :
                                         ", ") +
                names[i];
      return text + (names.size() == 1 ? " does" : " do");
    }
  } // namespace



  std::map<std::string, std::vector<std::string>>
  printed_subsections(const dealii::ParameterHandler &prm,
                      const std::string              &path)
  {
    const std::vector<std::string> target =
      path.empty() ? std::vector<std::string>() :
                     dealii::Utilities::split_string_list(path, '/');
    std::ostringstream text;
    prm.print_parameters(text, dealii::ParameterHandler::ShortPRM);
    std::istringstream                              in(text.str());
    std::map<std::string, std::vector<std::string>> sections;
    // The subsections the line being read is in.
    std::vector<std::string> stack;
    const auto               inside_target = [&] {
      return stack.size() > target.size() &&
             std::equal(target.begin(), target.end(), stack.begin());
    };
    for (std::string line; std::getline(in, line);)
      {
        const std::string entry = normalized(line);
        if (entry.rfind("subsection ", 0) == 0)
          {
            if (inside_target())
              sections[stack[target.size()]].push_back(entry);
            stack.push_back(trimmed(entry.substr(11)));
          }
        else if (entry == "end")
          {
            if (!stack.empty())
              stack.pop_back();
            if (inside_target())
              sections[stack[target.size()]].push_back(entry);
          }
        else if (inside_target() && !entry.empty() && entry[0] != '#')
          sections[stack[target.size()]].push_back(entry);
      }
    return sections;
  }



  std::vector<UnreadSubsection>
  changed_unread_subsections(dealii::ParameterHandler             &prm,
                             const std::vector<PluginDeclaration> &plugins,
                             const std::vector<std::string>       &chosen)
  {
    // Each plugin's subsections with their defaults.
    std::vector<std::map<std::string, std::vector<std::string>>> declared;
    std::set<std::string>                                        read;
    for (const PluginDeclaration &plugin : plugins)
      {
        dealii::ParameterHandler own;
        if (plugin.declare_parameters != nullptr)
          plugin.declare_parameters(own);
        declared.push_back(printed_subsections(own));
        if (std::find(chosen.begin(), chosen.end(), plugin.name) !=
            chosen.end())
          for (const auto &section : declared.back())
            read.insert(section.first);
      }
    // Per subsection no chosen plugin reads: the plugins that do, and
    // whether it differs from the defaults of one of them.
    std::map<std::string, std::pair<std::vector<std::string>, bool>> others;
    for (std::size_t p = 0; p < plugins.size(); ++p)
      for (const auto &[section, defaults] : declared[p])
        if (read.count(section) == 0 && prm.subsection_path_exists({section}))
          {
            auto &[readers, changed] = others[section];
            readers.push_back(plugins[p].name);
            changed = changed || differs_from(prm, section, defaults);
          }
    std::vector<UnreadSubsection> unread;
    for (const auto &[section, readers_and_changed] : others)
      if (readers_and_changed.second)
        unread.push_back({section, readers_and_changed.first});
    return unread;
  }



  std::vector<std::string>
  entries_unread_by_type(const dealii::ParameterHandler     &prm,
                         const std::vector<TypedSubsection> &subsections)
  {
    std::stringstream json;
    prm.print_parameters(json, dealii::ParameterHandler::JSON);
    boost::property_tree::ptree tree;
    boost::property_tree::read_json(json, tree);
    const auto without_blanks = [](std::string text) {
      text.erase(std::remove_if(text.begin(),
                                text.end(),
                                [](const char c) {
                                  return std::isspace(
                                    static_cast<unsigned char>(c));
                                }),
                 text.end());
      return text;
    };
    // A subsection or entry, by the names of its parents (the tree's own
    // paths would split names at their dots).
    const auto find = [&](const std::string &path) {
      const boost::property_tree::ptree *node = &tree;
      for (const std::string &name :
           dealii::Utilities::split_string_list(path, '/'))
        {
          const auto child = node->find(name);
          if (child == node->not_found())
            throw std::logic_error("entries_unread_by_type: no " + path);
          node = &child->second;
        }
      return node;
    };
    std::vector<std::string> warnings;
    for (const auto &[path, readers, given_choice] : subsections)
      {
        const boost::property_tree::ptree *section = find(path);
        const std::string                  choice =
          given_choice.empty() ? path + "/Type" : given_choice;
        const std::string type = find(choice)->get<std::string>("value");
        for (const auto &[entry, types] : readers)
          {
            const auto child = section->find(entry);
            if (child == section->not_found() ||
                std::find(types.begin(), types.end(), type) != types.end() ||
                without_blanks(child->second.get<std::string>("value")) ==
                  without_blanks(
                    child->second.get<std::string>("default_value")))
              continue;
            warnings.push_back(path + "/" + entry + ": " + choice + " = " +
                               type + " does not read it (" +
                               readers_text(types) + "); it is ignored.");
          }
      }
    return warnings;
  }



  std::string
  unread_subsection_text(const std::string      &path,
                         const UnreadSubsection &unread,
                         const std::string      &choice)
  {
    return (path.empty() ? "" : path + "/") + unread.name + ": " + choice +
           " does not read this subsection (" + readers_text(unread.readers) +
           ")";
  }
} // namespace estep
