#pragma once
// Keys and script verbs as rows (STYLE.md habit 13, after Scotty3D's manager and imgui's
// console): each tool declares the keys it answers, {key, help, action}, and its script
// verbs, whose GL-free half {verb, usage, help, parse} lives in a *_verbs.cpp file of the
// logic library (so the parser and its tests need no window) and whose run half {kind, run}
// lives in the tool. App concatenates the rows, keeps only the global ones, and dispatches;
// the in-viewer help, `accelviz --list keys|keys-summary|commands` and the tables of
// docs/viewer.md and README.md are made from the rows (tests/app/test_docs_tables.py
// compares them).
//
//   KeyPress, KeyBinding, dispatch_key()      keys
//   ScriptVerb, VerbArgs, shared parsers      the GL-free half of a script verb
//   ScriptHost, VerbRun                       the run half
//   keys_markdown(), verbs_markdown(), ...    the help and the docs' tables (mouse_markdown():
//                                             input.h's mouse rows)
#include <functional>
#include <string>
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
// Script verbs: the GL-free half

class VerbArgs;

/// One verb of the script language: what the parser, the usage errors and the docs know of
/// it. Each module lists its verbs in its *_verbs.cpp (script_verbs.h names them).
struct ScriptVerb {
  const char* verb = "";
  /// The command it makes (the parser sets it before `parse`, which may choose another:
  /// `record stop` is RecordStop).
  CommandKind kind = CommandKind::Size;
  /// Its forms, " | " between them: "step N | step end | step back N"; usage errors say
  /// "usage: " and this.
  const char* usage = "";
  /// What it does, one sentence (the docs' table).
  const char* help = "";
  /// Fills the command from its words; returns the error message, or "" when they are right.
  std::string (*parse)(const VerbArgs& args, ScriptCommand& command) = nullptr;
};

/// The words after a verb, with the checks the verbs share.
class VerbArgs {
 public:
  VerbArgs(const ScriptVerb& verb, const std::vector<std::string>& words) : verb_(verb), words_(words) {}
  size_t size() const { return words_.size(); }
  const std::string& operator[](size_t i) const { return words_[i]; }
  const std::vector<std::string>& words() const { return words_; }
  const char* verb() const { return verb_.verb; }
  const char* usage() const { return verb_.usage; }
  /// "usage: " and the verb's usage.
  std::string usage_error() const;
  /// Words [first, first + count) as finite numbers into command.values[0 .. count): "" or
  /// "'WORD' is not a finite number (USAGE)".
  std::string finite_values(size_t first, size_t count, ScriptCommand& command) const;

 private:
  const ScriptVerb& verb_;
  const std::vector<std::string>& words_;
};

/// An integer, the whole word.
bool parse_script_int(const std::string& word, int* out);
/// A finite number (decimal or C99 hex float, as a rays file writes them).
bool parse_finite(const std::string& word, float* out);
/// "on" or "off".
bool parse_on_off(const std::string& word, bool* out);

/// Parsers shared by many verbs: no words ("'VERB' takes no arguments"), one word (into
/// command.name), on|off (into command.on).
std::string parse_no_words(const VerbArgs& args, ScriptCommand& command);
std::string parse_one_word(const VerbArgs& args, ScriptCommand& command);
std::string parse_on_off_word(const VerbArgs& args, ScriptCommand& command);
/// A player's move, `N | end | back N | start`, and `hit` where `hit` is true (the
/// traversal's): command.step and command.ints[0].
std::string parse_step_words(const VerbArgs& args, ScriptCommand& command, bool hit);

// ---------------------------------------------------------------------------------------
// Script verbs: the run half

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

/// How a tool runs the commands of one kind. Errors are the message only (the caller adds
/// "SCRIPT:LINE: ").
struct VerbRun {
  CommandKind kind = CommandKind::Size;
  std::function<accel::Status(const ScriptCommand& command, ScriptHost& host)> run;
};

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
std::string verbs_markdown(const std::vector<ScriptVerb>& verbs);
/// docs/viewer.md's mouse table: "| mouse | 3D view | blackboard (2D mode) |", one row per
/// MouseRow (input.h), "—" where the action does nothing in that mode.
std::string mouse_markdown();

}  // namespace viz
