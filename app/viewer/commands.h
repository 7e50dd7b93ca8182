#pragma once
// Keys and script verbs, each declared once by the tool that acts on it (STYLE.md habit 13,
// after Scotty3D's manager and imgui's console). A tool declares the keys it answers as
// rows, {key, help, action}. A verb is one registration, `verbs.add<Args>(name, usage, help,
// parse, run)`: its own small argument type, the parser that fills it from the words and
// the run that acts on it. A module's registrations are one function template in a GL-free
// header (tools/<tool>_verbs.h, global_verbs.h, bench_chart_verbs.h) that two readers
// instantiate: VerbCatalogue keeps name, usage, help and parse and drops the run unread, so
// the parser, its tests and the fuzz target have every verb without a window or a tool
// (script_verbs.h); ToolVerbs<Tool> binds the run to the tool and the ToolHost, which is
// how each tool's add_verbs() fills App's VerbTable. App only dispatches, by name. The
// in-viewer help, `accelviz --list keys|keys-summary|commands` and the tables of
// docs/viewer.md and README.md are made from the rows and the catalogue
// (tests/app/test_docs_tables.py compares them).
//
//   KeyPress, KeyBinding, dispatch_key()      keys
//   VerbArgs, shared argument types/parsers   a verb's words
//   Verb, VerbTable, VerbCatalogue, ToolVerbs the registrations and their two readers
//   ScriptHost                                what a run may ask of main()
//   keys_markdown(), verbs_markdown(), ...    the help and the docs' tables (mouse_markdown():
//                                             input.h's mouse rows)
#include <any>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>

#include "result.h"
#include "script.h"

namespace viz {

// ---------------------------------------------------------------------------------------
// Keys

/// A key press as the window reported it: GLFW's key code and modifier bits.
struct KeyPress {
  int key = 0;
  int mods = 0;
};

/// One key a tool answers. Partner keys (left and right) are rows of their own that share
/// `keys` and `help`: the help lists them once.
struct KeyBinding {
  int key = 0;       ///< GLFW_KEY_*
  std::string keys;  ///< how the help names the key and its partners: "left / right"
  std::string help;  ///< what they do: "one traversal step back / forward (shift: 10)"
  /// Acts on a press. False hands the press on to the next row of the same key (the
  /// playlist takes PgDn only while one is loaded; the construction has it otherwise).
  std::function<bool(const KeyPress&)> action;
};

/// A tool's rows under its name: the groups of the help's summary.
struct KeyGroup {
  const char* tool = "";
  std::vector<KeyBinding> rows;
};

/// Offers `press` to the rows of `groups` in order until one takes it; true when one did.
bool dispatch_key(const std::vector<KeyGroup>& groups, const KeyPress& press);

// ---------------------------------------------------------------------------------------
// Script verbs: the words

struct Verb;

/// The words after a verb, with the checks the verbs share.
class VerbArgs {
 public:
  VerbArgs(const Verb& verb, const std::vector<std::string>& words) : verb_(verb), words_(words) {}
  size_t size() const { return words_.size(); }
  const std::string& operator[](size_t i) const { return words_[i]; }
  const std::vector<std::string>& words() const { return words_; }
  const char* verb() const;
  const char* usage() const;
  /// "usage: " and the verb's usage.
  std::string usage_error() const;
  /// Words [first, first + out.size()) as finite numbers into `out`: "" or
  /// "'WORD' is not a finite number (USAGE)".
  std::string finite_values(size_t first, std::span<float> out) const;

 private:
  const Verb& verb_;
  const std::vector<std::string>& words_;
};

/// An integer, the whole word.
bool parse_script_int(const std::string& word, int* out);
/// A finite number (decimal or C99 hex float, as a rays file writes them).
bool parse_finite(const std::string& word, float* out);
/// "on" or "off".
bool parse_on_off(const std::string& word, bool* out);

/// The argument shapes many verbs share (a verb with another shape declares its own struct
/// beside its registration): none, one word, on|off, a player's move.
struct NoArgs {};
struct Word {
  std::string word;
};
struct OnOff {
  bool on = false;
};
enum class StepMode { Forward, Back, End, Hit, Start };
struct PlayerMove {
  StepMode mode = StepMode::Forward;
  int count = 0;  ///< Forward, Back: how many steps
};

/// Their parsers: no words ("'VERB' takes no arguments"), one word, on|off.
std::string parse_no_words(const VerbArgs& args, NoArgs& out);
std::string parse_one_word(const VerbArgs& args, Word& out);
std::string parse_on_off_word(const VerbArgs& args, OnOff& out);
/// A player's move, `N | end | back N | start`, and `hit` where `hit` is true (the
/// traversal's).
std::string parse_step_words(const VerbArgs& args, PlayerMove& out, bool hit);

// ---------------------------------------------------------------------------------------
// Script verbs: the registrations

class ScriptHost;
class ToolHost;

/// One verb of the script language, as a registration declared it.
struct Verb {
  const char* name = "";
  /// Its forms, " | " between them: "step N | step end | step back N"; usage errors say
  /// "usage: " and this.
  const char* usage = "";
  /// What it does, one sentence (the docs' table).
  const char* help = "";
  /// Reads the words into the verb's arguments (`args` gets its own type); returns the
  /// error message, or "" when they are right.
  std::function<std::string(const VerbArgs& words, std::any& args)> parse;
  /// Runs a command this verb parsed; errors are the message only (the caller adds
  /// "SCRIPT:LINE: "). Empty in the catalogue, which has no tools.
  std::function<accel::Status(const ScriptCommand& command, ScriptHost& script)> run;
};

/// The verbs in the order they were added (the docs' order), found by name; each name once.
class VerbTable {
 public:
  /// Adds `verb`; a name already there is a programming error (two modules claim it).
  void add(Verb verb);
  /// The verb called `name`, or nullptr.
  const Verb* find(std::string_view name) const;
  size_t size() const { return verbs_.size(); }
  const Verb& operator[](size_t i) const { return verbs_[i]; }
  std::vector<Verb>::const_iterator begin() const { return verbs_.begin(); }
  std::vector<Verb>::const_iterator end() const { return verbs_.end(); }

 private:
  std::vector<Verb> verbs_;
};

/// A registration's parser as a Verb's: fills an `Args` and hands it over as std::any when
/// the words are right.
template <class Args, class Parse>
std::function<std::string(const VerbArgs&, std::any&)> parse_into(Parse parse) {
  return [parse](const VerbArgs& words, std::any& args) -> std::string {
    Args typed{};
    std::string error = parse(words, typed);
    if (error.empty()) args = std::move(typed);
    return error;
  };
}

/// The parse-only reader of the registrations: keeps name, usage, help and parse, drops
/// the run unread (its body, which names the tool, is never compiled here). script_verbs()
/// fills the catalogue with it.
class VerbCatalogue {
 public:
  explicit VerbCatalogue(VerbTable& table) : table_(table) {}
  template <class Args, class Parse, class Run>
  void add(const char* name, const char* usage, const char* help, Parse parse, const Run&) {
    table_.add({name, usage, help, parse_into<Args>(parse), {}});
  }

 private:
  VerbTable& table_;
};

/// The tools' reader of the registrations: each verb's run bound to `tool` and `host`. A
/// run is `(Tool& tool, ToolHost& host, const Args& args, ScriptHost& script) -> Status`
/// (a test binds a host of its own).
template <class Tool, class Host = ToolHost>
class ToolVerbs {
 public:
  ToolVerbs(VerbTable& table, Tool& tool, Host& host) : table_(table), tool_(tool), host_(host) {}
  template <class Args, class Parse, class Run>
  void add(const char* name, const char* usage, const char* help, Parse parse, Run run) {
    table_.add({name, usage, help, parse_into<Args>(parse),
                [&tool = tool_, &host = host_, run](const ScriptCommand& command, ScriptHost& script) {
                  return run(tool, host, command.get<Args>(), script);
                }});
  }

 private:
  VerbTable& table_;
  Tool& tool_;
  Host& host_;
};

// ---------------------------------------------------------------------------------------
// Script verbs: what a run may ask of main()

/// What the script runner needs from main(): rendering and the window.
class ScriptHost {
 public:
  virtual ~ScriptHost() = default;
  /// Resizes the window (and waits until the framebuffer has the new size).
  virtual accel::Status resize(int width, int height) = 0;
  /// Renders `frames` complete frames (update, draw, ImGui).
  virtual void render(int frames) = 0;
  /// Renders and writes the finished frame to `path` (PNG).
  virtual accel::Status screenshot(const std::string& path) = 0;
  /// Renders `frames` frames, waiting for the GPU after each; returns the mean milliseconds.
  virtual double measure_frames(int frames) = 0;
  /// Framebuffer size in pixels.
  virtual glm::ivec2 framebuffer_size() const = 0;
  /// The OpenGL renderer (GL_RENDERER), e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  virtual std::string gl_renderer() const = 0;
};

/// Prints one line of a script's answer (print-hit, print-stats, ...) to stdout, flushed:
/// the tests read it while the viewer runs on.
void print_script_line(const std::string& line);

// ---------------------------------------------------------------------------------------
// Help and docs, made from the rows

/// One line per key label, "LABEL: help", in the rows' order (the in-viewer help).
std::vector<std::string> keys_help_lines(const std::vector<KeyGroup>& groups);
/// docs/viewer.md's keys table: "| key | what it does |", one row per key label.
std::string keys_markdown(const std::vector<KeyGroup>& groups);
/// README.md's keys table: the mouse in the 3D view (input.h's rows), then one row per tool,
/// its keys and what they do.
std::string keys_summary_markdown(const std::vector<KeyGroup>& groups);
/// docs/viewer.md's script table: "| command | what it does |", one row per verb, its forms
/// as code.
std::string verbs_markdown(const VerbTable& verbs);
/// docs/viewer.md's mouse table: "| mouse | 3D view | blackboard (2D mode) |", one row per
/// MouseRow (input.h), "—" where the action does nothing in that mode.
std::string mouse_markdown();

}  // namespace viz
