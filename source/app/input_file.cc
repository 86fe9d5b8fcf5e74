#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <estep/app/input_file.h>
#include <estep/app/renamed_entries.h>
#include <estep/base/exception_text.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace estep
{
  namespace
  {
    constexpr unsigned int max_include_depth = 32;
    constexpr unsigned int max_json_depth    = 64;
    const std::string      byte_order_mark   = "\xEF\xBB\xBF";

    std::string
    read_text(const std::string &filename)
    {
      std::ifstream in(filename, std::ios::binary);
      if (!in)
        throw std::runtime_error("The input file <" + filename +
                                 "> cannot be opened.");
      std::ostringstream text;
      text << in.rdbuf();
      std::string result = text.str();
      if (result.compare(0, byte_order_mark.size(), byte_order_mark) == 0)
        result.erase(0, byte_order_mark.size());
      return result;
    }

    bool
    ends_with(const std::string &name, const std::string &extension)
    {
      return name.size() >= extension.size() &&
             name.compare(name.size() - extension.size(),
                          extension.size(),
                          extension) == 0;
    }

    /**
     * The position of the first byte of @p text that does not belong to
     * valid UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing above
     * U+10FFFF), or npos. The values an input sets are printed to
     * parameters.json, which must read back: JSON text is UTF-8.
     */
    std::size_t
    invalid_utf8_position(const std::string &text)
    {
      std::size_t i = 0;
      while (i < text.size())
        {
          const auto byte = [&](const std::size_t k) {
            return static_cast<unsigned char>(text[k]);
          };
          const unsigned char lead = byte(i);
          std::size_t         length;
          unsigned char       low = 0x80, high = 0xBF; // second byte's range
          if (lead < 0x80)
            length = 1;
          else if (lead >= 0xC2 && lead <= 0xDF)
            length = 2;
          else if (lead >= 0xE0 && lead <= 0xEF)
            {
              length = 3;
              if (lead == 0xE0)
                low = 0xA0;
              else if (lead == 0xED)
                high = 0x9F;
            }
          else if (lead >= 0xF0 && lead <= 0xF4)
            {
              length = 4;
              if (lead == 0xF0)
                low = 0x90;
              else if (lead == 0xF4)
                high = 0x8F;
            }
          else
            return i;
          if (i + length > text.size())
            return i;
          for (std::size_t k = 1; k < length; ++k)
            if (byte(i + k) < (k == 1 ? low : 0x80) ||
                byte(i + k) > (k == 1 ? high : 0xBF))
              return i;
          i += length;
        }
      return std::string::npos;
    }

    /** Throw if @p text (line @p number of @p filename) is not UTF-8. */
    void
    check_utf8(const std::string &text,
               const unsigned int number,
               const std::string &filename)
    {
      const std::size_t position = invalid_utf8_position(text);
      if (position != std::string::npos)
        throw std::runtime_error(
          "Line <" + std::to_string(number) + "> of file <" + filename +
          ">: not UTF-8 text (column " + std::to_string(position + 1) +
          "); estep reads its input files as UTF-8.");
    }

    /** The first word of @p line (lower case) and the rest, trimmed. */
    std::pair<std::string, std::string>
    keyword_and_rest(const std::string &line)
    {
      const auto  space = line.find_first_of(" \t");
      std::string word  = line.substr(0, space);
      for (char &c : word)
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      return {word,
              space == std::string::npos ?
                std::string() :
                dealii::Utilities::trim(line.substr(space))};
    }

    /** The error of an input file that sets no entry (emptied by mistake:
     * it would run the default problem). */
    std::runtime_error
    sets_no_entry(const std::string &filename)
    {
      return std::runtime_error(
        "The input file <" + filename +
        "> sets no entry: give at least one (estep --print-parameters "
        "prints them all with their defaults).");
    }

    /** Where scan_prm_file() is in a .prm file and its includes. */
    struct PrmScan
    {
      /** The files being read (canonical paths), the outermost first. */
      std::vector<std::string> chain;
      /** The subsection path at the current line. */
      std::vector<std::string> sections;
      /** The line that first set each entry (by full path) in each file. */
      std::map<std::pair<std::string, std::string>, unsigned int> set_on_line;
    };

    /**
     * Follow a .prm file as deal.II will read it, for what deal.II cannot
     * survive or report clearly: include lines (no cycle, bounded depth, the
     * file exists), entries of an earlier version of the input that have
     * moved (renamed_entry_message()), and an entry set twice in one file,
     * where deal.II would silently keep the later value (a file may set again
     * what a file it includes sets: that is how one file amends another).
     */
    void
    scan_prm_file(const std::string &filename, PrmScan &scan)
    {
      std::error_code   error;
      const std::string canonical =
        std::filesystem::weakly_canonical(filename, error).string();
      std::istringstream lines(read_text(filename));
      std::string        line;
      for (unsigned int number = 1; std::getline(lines, line); ++number)
        {
          line = line.substr(0, line.find('#'));
          check_utf8(line, number, filename);
          line                       = dealii::Utilities::trim(line);
          const auto [keyword, rest] = keyword_and_rest(line);
          const std::string where    = "Line <" + std::to_string(number) +
                                    "> of file <" + filename + ">: ";
          if (keyword == "subsection")
            scan.sections.push_back(rest);
          else if (keyword == "end" && !scan.sections.empty())
            scan.sections.pop_back();
          else if (keyword == "set")
            {
              std::string path;
              for (const std::string &section : scan.sections)
                path += section + "/";
              path += dealii::Utilities::trim(rest.substr(0, rest.find('=')));
              const std::string moved = renamed_entry_message(path);
              if (!moved.empty())
                throw std::runtime_error(where + moved);
              const auto [first, is_first] =
                scan.set_on_line.emplace(std::make_pair(canonical, path),
                                         number);
              if (!is_first)
                throw std::runtime_error(
                  where + path + " is set again (first on line " +
                  std::to_string(first->second) +
                  "); deal.II would keep the later value unseen. Set it once.");
            }
          else if (keyword == "include")
            {
              const std::string &target = rest;
              const std::string  target_canonical =
                std::filesystem::weakly_canonical(target, error).string();
              for (const std::string &open : scan.chain)
                if (open == target_canonical || target_canonical == canonical)
                  throw std::runtime_error(where + "including <" + target +
                                           "> forms a cycle of includes.");
              if (scan.chain.size() >= max_include_depth)
                throw std::runtime_error(where + "includes nest deeper than " +
                                         std::to_string(max_include_depth) +
                                         " files.");
              if (!std::filesystem::is_regular_file(target))
                throw std::runtime_error(where + "the included file <" +
                                         target +
                                         "> does not exist or is not a file.");
              scan.chain.push_back(target_canonical);
              scan_prm_file(target, scan);
              scan.chain.pop_back();
            }
        }
    }



    /** The deepest nesting of brackets outside strings. */
    unsigned int
    json_depth(const std::string &text)
    {
      unsigned int depth = 0, deepest = 0;
      bool         in_string = false, escaped = false;
      for (const char c : text)
        {
          if (in_string)
            {
              if (escaped)
                escaped = false;
              else if (c == '\\')
                escaped = true;
              else if (c == '"')
                in_string = false;
            }
          else if (c == '"')
            in_string = true;
          else if (c == '{' || c == '[')
            deepest = std::max(deepest, ++depth);
          else if ((c == '}' || c == ']') && depth > 0)
            --depth;
        }
      return deepest;
    }



    /** @p sections joined by '/', and @p name after them. */
    std::string
    entry_path(const std::vector<std::string> &sections,
               const std::string              &name)
    {
      std::string path;
      for (const std::string &section : sections)
        path += section + "/";
      return path + name;
    }

    /** Whether @p prm declares the entry @p name in the subsection
     * @p sections (setting it to its value, which changes nothing; only for
     * the message of an error). */
    bool
    is_declared_entry(dealii::ParameterHandler       &prm,
                      const std::vector<std::string> &sections,
                      const std::string              &name)
    {
      if (!sections.empty() && !prm.subsection_path_exists(sections))
        return false;
      for (const std::string &section : sections)
        prm.enter_subsection(section);
      bool declared = true;
      try
        {
          prm.set(name, prm.get(name));
        }
      catch (...)
        {
          declared = false;
        }
      for (unsigned int i = 0; i < sections.size(); ++i)
        prm.leave_subsection();
      return declared;
    }

    /**
     * Set the entries of the JSON object @p node, found at @p sections of
     * @p prm, as deal.II's reader would, but name each problem by the file
     * and the entry's full path: an entry or subsection that is not declared
     * (unless @p skip_undeclared), a value that does not match its pattern, an
     * array, or an entry of an earlier input layout. An entry is a string or
     * a number, or an object with a member "value" (the long form that
     * --print-parameters writes).
     */
    void
    read_json_object(dealii::ParameterHandler          &prm,
                     const boost::property_tree::ptree &node,
                     std::vector<std::string>          &sections,
                     const std::string                 &filename,
                     const bool                         skip_undeclared)
    {
      const std::string     where = "File <" + filename + ">: ";
      std::set<std::string> names;
      for (const auto &[name, child] : node)
        {
          const std::string path = entry_path(sections, name);
          if (!name.empty() && !names.insert(name).second)
            throw std::runtime_error(where + path +
                                     " is given twice in one object; give "
                                     "it once.");
          if (name.empty())
            throw std::runtime_error(
              where + (sections.empty() ? std::string("the file") : path) +
              " is a JSON array; a subsection is an object, an entry a "
              "string or a number.");
          if (const std::string moved = renamed_entry_message(path);
              !moved.empty())
            throw std::runtime_error(where + moved);
          sections.push_back(name);
          const bool is_section = prm.subsection_path_exists(sections);
          if (is_section && child.empty() && !child.data().empty())
            throw std::runtime_error(where + path +
                                     " is a subsection: its value must be "
                                     "an object of entries.");
          if (is_section)
            read_json_object(prm, child, sections, filename, skip_undeclared);
          sections.pop_back();
          if (is_section)
            continue;

          const auto long_form = child.get_child_optional("value");
          if (!child.empty() && child.begin()->first.empty())
            throw std::runtime_error(where + path +
                                     " is a JSON array; a subsection is an "
                                     "object, an entry a string or a number.");
          if (!child.empty() && !(long_form && long_form->empty()))
            {
              if (is_declared_entry(prm, sections, name))
                throw std::runtime_error(where + path +
                                         " is an entry: its value must be a "
                                         "string or a number.");
              if (skip_undeclared)
                continue;
              throw std::runtime_error(where + "there is no subsection <" +
                                       path +
                                       "> (see estep --print-parameters).");
            }
          const std::string value =
            child.empty() ? child.data() : long_form->data();
          for (const std::string &section : sections)
            prm.enter_subsection(section);
          std::string error;
          try
            {
              prm.set(name, value);
            }
          catch (const dealii::ParameterHandler::ExcEntryUndeclared &)
            {
              if (!skip_undeclared)
                error = "there is no entry <" + path +
                        "> (see estep --print-parameters).";
            }
          catch (const dealii::ExceptionBase &exception)
            {
              error = path + ": " + one_line_message(exception);
            }
          for (unsigned int i = 0; i < sections.size(); ++i)
            prm.leave_subsection();
          if (!error.empty())
            throw std::runtime_error(where + error);
        }
    }

    /** Read the JSON parameter file @p filename into @p prm. */
    void
    read_json_file(dealii::ParameterHandler &prm,
                   const std::string        &filename,
                   const bool                skip_undeclared)
    {
      const std::string text = read_text(filename);
      if (json_depth(text) > max_json_depth)
        throw std::runtime_error("The input file <" + filename +
                                 "> nests deeper than " +
                                 std::to_string(max_json_depth) +
                                 " levels: it is not a parameter file.");
      boost::property_tree::ptree tree;
      try
        {
          std::istringstream in(text);
          boost::property_tree::read_json(in, tree);
        }
      catch (const boost::property_tree::json_parser_error &error)
        {
          throw std::runtime_error(
            "Line <" + std::to_string(error.line()) + "> of file <" + filename +
            ">: not valid JSON: " + error.message() + ".");
        }
      if (tree.empty())
        throw sets_no_entry(filename);
      std::vector<std::string> sections;
      read_json_object(prm, tree, sections, filename, skip_undeclared);
    }
  } // namespace



  void
  read_input_file(dealii::ParameterHandler &prm,
                  const std::string        &filename,
                  const bool                skip_undeclared)
  {
    if (ends_with(filename, ".json"))
      {
        read_json_file(prm, filename, skip_undeclared);
        return;
      }
    if (ends_with(filename, ".xml"))
      {
        std::istringstream lines(read_text(filename));
        std::string        line;
        for (unsigned int number = 1; std::getline(lines, line); ++number)
          check_utf8(line, number, filename);
        try
          {
            prm.parse_input(filename, "", skip_undeclared);
          }
        catch (const boost::property_tree::file_parser_error &error)
          {
            throw std::runtime_error(
              "Line <" + std::to_string(error.line()) + "> of file <" +
              filename + ">: not valid XML: " + error.message() + ".");
          }
        return;
      }
    PrmScan scan;
    scan_prm_file(filename, scan);
    if (scan.set_on_line.empty())
      throw sets_no_entry(filename);
    std::istringstream text(read_text(filename));
    try
      {
        prm.parse_input(text, filename, "", skip_undeclared);
      }
    catch (const dealii::ParameterHandler::ExcNoSubsection &exception)
      {
        // deal.II 9.4 writes "Line <n> of file <name: There is no such
        // subsection to be entered: A.B", without the '>' and with the path
        // joined by dots, where estep names entries A/B.
        std::string message =
          std::regex_replace(one_line_message(exception),
                             std::regex("of file <([^>]*): There is no such"),
                             "of file <$1>: There is no such");
        const std::string entered = "subsection to be entered: ";
        if (const auto at = message.find(entered); at != std::string::npos)
          {
            std::string path = message.substr(at + entered.size());
            std::replace(path.begin(), path.end(), '.', '/');
            message = message.substr(0, at) + entered + path;
            std::smatch body;
            if (std::regex_match(path, body, std::regex("Scene/Body ([0-9]+)")))
              message += " (Scene/Number of bodies, which declares Body 1 to "
                         "Body N, is below " +
                         body[1].str() + ")";
          }
        throw std::runtime_error(message + '.');
      }
  }
} // namespace estep
