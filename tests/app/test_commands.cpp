// The rows of keys and the script verbs' registrations (commands.h): a key goes to the
// first row that takes it, the help and the docs' tables are made from the rows and the
// catalogue, every verb is whole (its usage names it, each form starts with it, it has help
// and a parser), a registration read by the catalogue has no run and bound to a tool runs
// on it with its typed arguments, and a name is declared once.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "commands.h"
#include "script_verbs.h"

namespace viz {
namespace {

KeyBinding row(int key, const char* keys, const char* help, std::string* log, bool takes) {
  return {key, keys, help, [=](const KeyPress& k) {
            *log += std::string(keys) + (k.mods ? "+shift" : "") + ";";
            return takes;
          }};
}

TEST(Commands, AKeyGoesToTheFirstRowThatTakesIt) {
  std::string log;
  const std::vector<KeyGroup> groups = {
      {"playlist", {row(1, "PgDn", "next state", &log, false)}},  // declines: no playlist loaded
      {"construction", {row(1, "PgDn", "last step", &log, true), row(2, "x", "other", &log, true)}},
  };
  EXPECT_TRUE(dispatch_key(groups, {1, 1}));
  EXPECT_EQ(log, "PgDn+shift;PgDn+shift;");  // offered to both, taken by the second
  log.clear();
  EXPECT_FALSE(dispatch_key(groups, {3, 0}));  // nobody's key
  EXPECT_EQ(log, "");
}

TEST(Commands, HelpAndTablesComeFromTheRows) {
  std::string log;
  const std::vector<KeyGroup> groups = {
      {"construction",
       {row(1, ", / .", "step back / forward", &log, true), row(2, ", / .", "step back / forward", &log, true),
        row(3, "PgDn / PgUp, down", "a | b", &log, true)}},
  };
  // Partner keys share one line; each key is code, the comma and the period too.
  EXPECT_EQ(keys_help_lines(groups),
            (std::vector<std::string>{", / .: step back / forward", "PgDn / PgUp, down: a | b"}));
  EXPECT_EQ(keys_markdown(groups),
            "| key | what it does |\n|---|---|\n"
            "| `,` / `.` | step back / forward |\n"
            "| `PgDn` / `PgUp`, `down` | a \\| b |\n");
  // The README's summary: the mouse in the 3D view first (input.h's rows), then the tools.
  const std::string summary = keys_summary_markdown(groups);
  EXPECT_TRUE(summary.starts_with("| tool | keys | what they do |\n|---|---|---|\n| mouse (3D view) | left drag, "))
      << summary;
  EXPECT_NE(summary.find("| orbit the camera; shoot the debug ray through that pixel;"), std::string::npos) << summary;
  EXPECT_TRUE(summary.ends_with("\n| construction | `,` / `.`, `PgDn` / `PgUp`, `down` | step back / forward; a \\| b |\n"))
      << summary;
  VerbTable verbs;
  verbs.add({"step", "step N | step on|off", "move", {}, {}});
  EXPECT_EQ(verbs_markdown(verbs), "| command | what it does |\n|---|---|\n| `step N`, `step on\\|off` | move |\n");
}

TEST(Commands, EveryVerbRowIsWhole) {
  std::set<std::string> names;
  for (const Verb& v : script_verbs()) {
    const std::string verb = v.name;
    EXPECT_TRUE(names.insert(verb).second) << verb << " declared twice";
    EXPECT_TRUE(v.parse) << verb;
    EXPECT_FALSE(v.run) << verb << ": the catalogue has no tools";
    EXPECT_FALSE(std::string(v.help).empty()) << verb;
    // Each form of the usage starts with the verb: the usage error and the docs show them.
    const std::string usage = v.usage;
    for (size_t start = 0;;) {
      EXPECT_EQ(usage.compare(start, verb.size(), verb), 0) << verb << ": " << usage;
      const size_t bar = usage.find(" | ", start);
      if (bar == std::string::npos) break;
      start = bar + 3;
    }
  }
  EXPECT_GE(names.size(), 50u);
}

TEST(Commands, SharedParsers) {
  const Verb verb{"tree", "tree on|off", "the tree", {}, {}};
  OnOff on_off{true};
  NoArgs none_args;
  Word word;
  const std::vector<std::string> off = {"off"}, two = {"on", "off"}, none;
  EXPECT_EQ(parse_on_off_word(VerbArgs(verb, off), on_off), "");
  EXPECT_FALSE(on_off.on);
  EXPECT_EQ(parse_on_off_word(VerbArgs(verb, two), on_off), "usage: tree on|off");
  EXPECT_EQ(parse_no_words(VerbArgs(verb, two), none_args), "'tree' takes no arguments");
  EXPECT_EQ(parse_no_words(VerbArgs(verb, none), none_args), "");
  EXPECT_EQ(parse_one_word(VerbArgs(verb, off), word), "");
  EXPECT_EQ(word.word, "off");
  float values[2] = {};
  const std::vector<std::string> numbers = {"1.5", "0x1p-1", "x"};
  EXPECT_EQ(VerbArgs(verb, numbers).finite_values(0, values), "");
  EXPECT_EQ(values[1], 0.5f);
  EXPECT_EQ(VerbArgs(verb, numbers).finite_values(1, values), "'x' is not a finite number (tree on|off)");
}

// A registration as the modules write one (tools/*_verbs.h): a typed argument struct, its
// parser, and a run on the tool.
struct CounterArgs {
  int by = 0;
};
struct Counter {
  int count = 0;
};

template <class Verbs>
void counter_verbs(Verbs& verbs) {
  verbs.template add<CounterArgs>(
      "count", "count N", "add N to the counter",
      [](const VerbArgs& a, CounterArgs& s) -> std::string {
        return a.size() == 1 && parse_script_int(a[0], &s.by) ? "" : a.usage_error();
      },
      [](auto& counter, auto&, const CounterArgs& s, ScriptHost&) -> accel::Status {
        counter.count += s.by;
        return {};
      });
}

TEST(Commands, ARegistrationIsParsedByTheCatalogueAndRunByTheTool) {
  VerbTable catalogue;
  VerbCatalogue parse_only(catalogue);
  counter_verbs(parse_only);
  ASSERT_EQ(catalogue.size(), 1u);
  EXPECT_FALSE(catalogue[0].run);
  ScriptCommand command;
  const std::vector<std::string> seven = {"7"}, bad = {"seven"};
  EXPECT_EQ(catalogue[0].parse(VerbArgs(catalogue[0], bad), command.args), "usage: count N");
  EXPECT_FALSE(command.args.has_value());
  EXPECT_EQ(catalogue[0].parse(VerbArgs(catalogue[0], seven), command.args), "");
  EXPECT_EQ(command.get<CounterArgs>().by, 7);

  // Bound to a tool: the same parse, and the run acts on the tool (its host, App's stand-in,
  // unused).
  VerbTable table;
  Counter counter;
  struct NoHost {
  } host;
  ToolVerbs<Counter, NoHost> bound(table, counter, host);
  counter_verbs(bound);
  ASSERT_TRUE(table.find("count") && table.find("count")->run);
  EXPECT_EQ(table.find("nope"), nullptr);
  struct NoWindow : ScriptHost {
    accel::Status resize(int, int) override { return {}; }
    void render(int) override {}
    accel::Status screenshot(const std::string&) override { return {}; }
    double measure_frames(int) override { return 0.0; }
    glm::ivec2 framebuffer_size() const override { return {1, 1}; }
    std::string gl_renderer() const override { return ""; }
  } script;
  EXPECT_TRUE(table.find("count")->run(command, script));
  EXPECT_TRUE(table.find("count")->run(command, script));
  EXPECT_EQ(counter.count, 14);
}

TEST(CommandsDeathTest, AVerbIsDeclaredOnce) {
  VerbTable table;
  table.add({"count", "count N", "add N", {}, {}});
  EXPECT_DEATH(table.add({"count", "count", "another count", {}, {}}), "internal check failed");
}

}  // namespace
}  // namespace viz
