// The rows of keys and script verbs (commands.h): a key goes to the first row that takes
// it, the help and the docs' tables are made from the rows, and every verb's row is whole
// (its usage names it, each form starts with it, it has help and a parser).
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
  EXPECT_EQ(keys_summary_markdown(groups),
            "| tool | keys | what they do |\n|---|---|---|\n"
            "| construction | `,` / `.`, `PgDn` / `PgUp`, `down` | step back / forward; a \\| b |\n");
  const std::vector<ScriptVerb> verbs = {{"step", CommandKind::Step, "step N | step on|off", "move", parse_no_words}};
  EXPECT_EQ(verbs_markdown(verbs), "| command | what it does |\n|---|---|\n| `step N`, `step on\\|off` | move |\n");
}

TEST(Commands, EveryVerbRowIsWhole) {
  std::set<std::string> names;
  for (const ScriptVerb& v : script_verbs()) {
    const std::string verb = v.verb;
    EXPECT_TRUE(names.insert(verb).second) << verb << " declared twice";
    EXPECT_NE(v.parse, nullptr) << verb;
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
  const ScriptVerb verb{"tree", CommandKind::Tree, "tree on|off", "the tree", parse_on_off_word};
  ScriptCommand c;
  const std::vector<std::string> off = {"off"}, two = {"on", "off"}, none;
  EXPECT_EQ(parse_on_off_word(VerbArgs(verb, off), c), "");
  EXPECT_FALSE(c.on);
  EXPECT_EQ(parse_on_off_word(VerbArgs(verb, two), c), "usage: tree on|off");
  EXPECT_EQ(parse_no_words(VerbArgs(verb, two), c), "'tree' takes no arguments");
  EXPECT_EQ(parse_no_words(VerbArgs(verb, none), c), "");
  EXPECT_EQ(parse_one_word(VerbArgs(verb, off), c), "");
  EXPECT_EQ(c.name, "off");
}

}  // namespace
}  // namespace viz
