// changed_unread_subsections(): the subsections of the plugins not chosen
// whose values differ from their defaults, read from the current subsection
// of the handler, which it leaves where it was.
#include <deal.II/base/parameter_handler.h>

#include <estep/base/parameter_subsections.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace
{
  using dealii::ParameterHandler;
  using dealii::Patterns::Anything;

  void
  declare_alpha(ParameterHandler &prm)
  {
    prm.enter_subsection("Alpha");
    prm.declare_entry("Size", "1", Anything());
    prm.enter_subsection("Inner");
    prm.declare_entry("Depth", "2", Anything());
    prm.leave_subsection();
    prm.leave_subsection();
    prm.enter_subsection("Shared");
    prm.declare_entry("Alpha only", "0", Anything());
    prm.leave_subsection();
  }

  void
  declare_beta(ParameterHandler &prm)
  {
    prm.enter_subsection("Beta");
    prm.declare_entry("Speed", "3", Anything());
    prm.leave_subsection();
    prm.enter_subsection("Shared");
    prm.declare_entry("Beta only", "0", Anything());
    prm.leave_subsection();
  }

  void
  declare_gamma(ParameterHandler &prm)
  {
    prm.enter_subsection("Gamma");
    prm.declare_entry("Mode", "x", Anything());
    prm.leave_subsection();
  }

  const std::vector<estep::PluginDeclaration> plugins = {
    {"alpha", declare_alpha},
    {"beta", declare_beta},
    {"gamma", declare_gamma}};

  /** The plugins' subsections inside "Extension", next to an entry of its
   * own, and the handler entered there. */
  struct Handler
  {
    ParameterHandler prm;
    Handler()
    {
      prm.enter_subsection("Extension");
      prm.declare_entry("Own", "own", Anything());
      for (const auto &plugin : plugins)
        plugin.declare_parameters(prm);
    }
    /** Set @p entry ("Alpha/Inner/Depth") relative to "Extension". */
    void
    set(const std::string &entry, const std::string &value)
    {
      const auto path = dealii::Utilities::split_string_list(entry, '/');
      for (std::size_t i = 0; i + 1 < path.size(); ++i)
        prm.enter_subsection(path[i]);
      prm.set(path.back(), value);
      for (std::size_t i = 0; i + 1 < path.size(); ++i)
        prm.leave_subsection();
    }
  };

  std::vector<std::string>
  names(const std::vector<estep::UnreadSubsection> &unread)
  {
    std::vector<std::string> result;
    for (const auto &u : unread)
      result.push_back(u.name);
    return result;
  }
} // namespace

TEST(ChangedUnreadSubsections, DefaultsAreNotReported)
{
  Handler h;
  EXPECT_TRUE(
    estep::changed_unread_subsections(h.prm, plugins, {"gamma"}).empty());
}

TEST(ChangedUnreadSubsections, ANestedChangeIsReportedAndTheHandlerStays)
{
  Handler h;
  h.set("Alpha/Inner/Depth", "5");
  const auto unread =
    estep::changed_unread_subsections(h.prm, plugins, {"gamma"});
  ASSERT_EQ(names(unread), std::vector<std::string>{"Alpha"});
  EXPECT_EQ(unread[0].readers, std::vector<std::string>{"alpha"});
  // Still in "Extension": its own entry and the plugins' subsections are
  // there, and leaving it reaches the top level.
  EXPECT_EQ(h.prm.get("Own"), "own");
  EXPECT_TRUE(h.prm.subsection_path_exists({"Alpha", "Inner"}));
  h.prm.leave_subsection();
  EXPECT_TRUE(h.prm.subsection_path_exists({"Extension"}));
}

TEST(ChangedUnreadSubsections, ASubsectionTheChosenPluginReadsIsNotReported)
{
  Handler h;
  h.set("Alpha/Size", "7");
  h.set("Beta/Speed", "4");
  EXPECT_EQ(names(estep::changed_unread_subsections(h.prm, plugins, {"alpha"})),
            std::vector<std::string>{"Beta"});
  EXPECT_TRUE(
    estep::changed_unread_subsections(h.prm, plugins, {"alpha", "beta"})
      .empty());
}

TEST(ChangedUnreadSubsections, ASharedSubsectionIsComparedPerPlugin)
{
  // Each plugin declares part of "Shared": at their defaults, none differs
  // from its own plugin's defaults, although the subsection as a whole
  // differs from either plugin's.
  Handler h;
  EXPECT_TRUE(
    estep::changed_unread_subsections(h.prm, plugins, {"gamma"}).empty());
  h.set("Shared/Beta only", "1");
  const auto unread =
    estep::changed_unread_subsections(h.prm, plugins, {"gamma"});
  ASSERT_EQ(names(unread), std::vector<std::string>{"Shared"});
  EXPECT_EQ(unread[0].readers, (std::vector<std::string>{"alpha", "beta"}));
}

TEST(ChangedUnreadSubsections, ValuesAreComparedWithoutTheirOuterBlanks)
{
  Handler h;
  h.set("Beta/Speed", "3 ");
  EXPECT_TRUE(
    estep::changed_unread_subsections(h.prm, plugins, {"gamma"}).empty());
}
