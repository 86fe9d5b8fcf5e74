#ifndef estep_base_plugin_registry_h
#define estep_base_plugin_registry_h

#include <estep/base/parameter_subsections.h>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace dealii
{
  class ParameterHandler;
}

namespace estep
{
  /**
   * Problems with plugin registrations, collected while libraries initialise
   * (where nothing may throw) and reported by the application afterwards: a
   * name registered twice, for instance.
   */
  std::vector<std::string> &
  plugin_registration_errors();

  /** How many plugin registrations have been attempted, in every registry,
   * valid or not: a library loaded at run time that adds none is no plugin
   * library. */
  std::size_t &
  plugin_registration_count();

  /**
   * The plugins of one extension point of estep (problems, materials, time
   * integrators, postprocessors), as in ASPECT: each plugin has a name, a
   * description, a function that declares its parameters and a factory. The
   * extension points' headers (e.g. estep/materials/material_registry.h) each
   * hold one registry and a registration macro that a plugin's source file
   * ends with; a shared library loaded at run time adds its plugins the same
   * way. The Selection patterns, --help and --print-parameters are built from
   * the registries, so a new plugin needs no edit elsewhere.
   *
   * @tparam Factory the signature of the plugins' create function.
   */
  template <typename Factory>
  class PluginRegistry
  {
  public:
    struct Plugin
    {
      std::string name;
      std::string description;
      /** Declares the plugin's parameters, relative to the subsection in which
       * the extension point declares its plugins (may be nullptr). */
      void (*declare_parameters)(dealii::ParameterHandler &);
      std::function<Factory> create;
    };

    /** @p kind names a plugin of this registry in messages ("material"). */
    explicit PluginRegistry(std::string kind)
      : kind(std::move(kind))
    {}

    /**
     * Add a plugin. Meant for static initialisation: it never throws; a name
     * that is empty, contains '|' or ',' or is taken already is recorded in
     * plugin_registration_errors() and the plugin is not added. Returns true
     * (for the registration macros).
     */
    bool
    add(Plugin plugin) noexcept
    {
      ++plugin_registration_count();
      try
        {
          const std::string &name = plugin.name;
          if (name.empty() || name.find_first_of("|,") != std::string::npos)
            plugin_registration_errors().push_back(
              "A " + kind + " plugin has the invalid name <" + name +
              "> (empty, or with '|' or ',').");
          else if (find(name) != nullptr)
            plugin_registration_errors().push_back(
              "Two " + kind + " plugins are registered under the name <" +
              name + ">.");
          else
            {
              const auto position =
                std::lower_bound(entries.begin(),
                                 entries.end(),
                                 name,
                                 [](const Plugin &p, const std::string &n) {
                                   return p.name < n;
                                 });
              entries.insert(position, std::move(plugin));
            }
        }
      catch (...)
        {}
      return true;
    }

    /** The plugin named @p name, or nullptr. */
    const Plugin *
    find(const std::string &name) const
    {
      for (const Plugin &plugin : entries)
        if (plugin.name == name)
          return &plugin;
      return nullptr;
    }

    /**
     * The plugin named @p name; throws std::runtime_error naming @p entry
     * (the parameter that asked for it) and the valid names otherwise.
     */
    const Plugin &
    get(const std::string &name, const std::string &entry) const
    {
      if (const Plugin *plugin = find(name))
        return *plugin;
      throw std::runtime_error(entry + ": there is no " + kind + " <" + name +
                               ">; the " + kind + "s are: " + names(", ") +
                               ".");
    }

    /** The names in alphabetical order, joined by @p separator ("|" gives a
     * Patterns::Selection). */
    std::string
    names(const std::string &separator = "|") const
    {
      std::string text;
      for (const Plugin &plugin : entries)
        text += (text.empty() ? "" : separator) + plugin.name;
      return text;
    }

    /** One line per plugin, "- name: description", for documentation. */
    std::string
    descriptions() const
    {
      std::string text;
      for (const Plugin &plugin : entries)
        text += "\n- " + plugin.name + ": " + plugin.description;
      return text;
    }

    /** Call every plugin's declare_parameters (one that several plugins
     * share, once). */
    void
    declare_parameters(dealii::ParameterHandler &prm) const
    {
      std::vector<void (*)(dealii::ParameterHandler &)> done;
      for (const Plugin &plugin : entries)
        if (plugin.declare_parameters != nullptr &&
            std::find(done.begin(), done.end(), plugin.declare_parameters) ==
              done.end())
          {
            plugin.declare_parameters(prm);
            done.push_back(plugin.declare_parameters);
          }
    }

    const std::vector<Plugin> &
    plugins() const
    {
      return entries;
    }

    /** Each plugin's name and parameter declaration (for
     * changed_unread_subsections()). */
    std::vector<PluginDeclaration>
    declarations() const
    {
      std::vector<PluginDeclaration> result;
      for (const Plugin &plugin : entries)
        result.push_back({plugin.name, plugin.declare_parameters});
      return result;
    }

  private:
    std::string         kind;
    std::vector<Plugin> entries;
  };
} // namespace estep

#define estep_plugin_concatenate_(a, b) a##b
#define estep_plugin_concatenate(a, b) estep_plugin_concatenate_(a, b)

/**
 * Register a plugin with @p registry (an expression giving a PluginRegistry)
 * at static initialisation; the remaining arguments are the fields of its
 * Plugin: name, description, declare_parameters, create. The extension points'
 * macros (ESTEP_REGISTER_MATERIAL, ...) expand to this.
 */
#define ESTEP_REGISTER_PLUGIN(registry, ...)                           \
  namespace                                                            \
  {                                                                    \
    const bool estep_plugin_concatenate(estep_registered_, __LINE__) = \
      (registry).add({__VA_ARGS__});                                   \
  }

#endif
