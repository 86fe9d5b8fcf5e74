#ifndef estep_base_parameter_subsections_h
#define estep_base_parameter_subsections_h

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace estep
{
  /**
   * The entries of each subsection of @p prm directly inside the subsection
   * @p path ("Scene/Body 1", '/'-separated; empty: the top level), by name,
   * each as one line "set Name = value" (nested subsections as their
   * "subsection ..." and "end" lines and their entries). Two handlers of the
   * same declarations give a subsection the same lines exactly when its
   * entries have the same values.
   */
  std::map<std::string, std::vector<std::string>>
  printed_subsections(const dealii::ParameterHandler &prm,
                      const std::string              &path = "");

  /** A plugin's name and the function that declares its parameters,
   * relative to the subsection of its extension point (may be nullptr). */
  struct PluginDeclaration
  {
    std::string name;
    void (*declare_parameters)(dealii::ParameterHandler &);
  };

  /** A subsection that the chosen plugins do not read, and the plugins that
   * do. */
  struct UnreadSubsection
  {
    std::string              name;
    std::vector<std::string> readers;
  };

  /**
   * The subsections of the current subsection of @p prm that none of the
   * plugins named in @p chosen declares, that another of @p plugins declares,
   * and whose values differ from that plugin's defaults: settings that the
   * run ignores. (An entry set to its default value cannot be told apart.)
   * Reads only the entries of those subsections (and leaves @p prm where it
   * was), so that a scene can ask once per body at a cost that does not grow
   * with the number of bodies.
   */
  std::vector<UnreadSubsection>
  changed_unread_subsections(dealii::ParameterHandler             &prm,
                             const std::vector<PluginDeclaration> &plugins,
                             const std::vector<std::string>       &chosen);

  /** The entries of a subsection that only some values of the entry that
   * chooses among them (its `Type`, say) read, each with those values. */
  using TypeReaders =
    std::vector<std::pair<std::string, std::vector<std::string>>>;

  /** A subsection (its '/'-separated path), its TypeReaders, and the
   * '/'-separated path of the entry that chooses (empty: path/Type). */
  struct TypedSubsection
  {
    std::string path;
    TypeReaders readers;
    std::string choice = {};
  };

  /**
   * Warnings for the entries that the choice of their subsection does not
   * read: in each of @p subsections, each entry of its readers whose value
   * differs, blanks aside, from its declared default while the choosing
   * entry has another value, in a sentence "path/entry: path/Type = value
   * does not read it (box does); it is ignored." An entry the subsection
   * does not declare is skipped.
   */
  std::vector<std::string>
  entries_unread_by_type(const dealii::ParameterHandler     &prm,
                         const std::vector<TypedSubsection> &subsections);

  /**
   * "path/name: choice does not read this subsection (reader does)" for the
   * subsection @p unread inside @p path, with @p choice the entry and value
   * that chose the plugins ("Time integration/Method = explicit newmark").
   */
  std::string
  unread_subsection_text(const std::string      &path,
                         const UnreadSubsection &unread,
                         const std::string      &choice);
} // namespace estep

#endif
