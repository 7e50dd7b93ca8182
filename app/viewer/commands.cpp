#include "commands.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "check.h"
#include "input.h"
#include "rays_io.h"

namespace viz {
namespace {

/// `text` inside a Markdown table cell: a '|' would end the cell.
std::string table_cell(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (ch == '|') out += '\\';
    out += ch;
  }
  return out;
}

/// "`left` / `right`, `down`": each key of a label as code. A separator (" / " or ", ")
/// never starts a key, so ", / ." is the comma and the period.
std::string keys_as_code(const std::string& label) {
  std::string out = "`";
  size_t key_start = 0;
  for (size_t i = 0; i < label.size(); ++i) {
    const size_t sep = label.compare(i, 3, " / ") == 0 ? 3 : label.compare(i, 2, ", ") == 0 ? 2 : 0;
    if (sep && i > key_start) {
      out += "`";
      out += label.substr(i, sep);
      out += "`";
      i += sep - 1;
      key_start = i + 1;
    } else {
      out += label[i];
    }
  }
  return table_cell(out + "`");
}

/// Calls `row` once per key label (the first row of a label: partners share its help).
template <class Fn>
void for_each_label(const std::vector<KeyBinding>& rows, Fn row) {
  std::vector<std::string> seen;
  for (const KeyBinding& b : rows) {
    if (std::find(seen.begin(), seen.end(), b.keys) != seen.end()) continue;
    seen.push_back(b.keys);
    row(b);
  }
}

}  // namespace

bool dispatch_key(const std::vector<KeyGroup>& groups, const KeyPress& press) {
  for (const KeyGroup& g : groups)
    for (const KeyBinding& b : g.rows)
      if (b.key == press.key && b.action(press)) return true;
  return false;
}

// ---------------------------------------------------------------------------------------
// The verbs' words

const char* VerbArgs::verb() const { return verb_.name; }
const char* VerbArgs::usage() const { return verb_.usage; }

std::string VerbArgs::usage_error() const { return std::string("usage: ") + verb_.usage; }

std::string VerbArgs::finite_values(size_t first, std::span<float> out) const {
  for (size_t i = 0; i < out.size(); ++i) {
    if (!parse_finite(words_[first + i], &out[i]))
      return "'" + words_[first + i] + "' is not a finite number (" + verb_.usage + ")";
  }
  return "";
}

bool parse_script_int(const std::string& word, int* out) {
  const char* end = word.data() + word.size();
  auto [ptr, ec] = std::from_chars(word.data(), end, *out);
  return !word.empty() && ec == std::errc() && ptr == end;
}

bool parse_finite(const std::string& word, float* out) {
  return accel::parse_ray_number(word, out) && std::isfinite(*out);
}

bool parse_on_off(const std::string& word, bool* out) {
  if (word == "on")
    *out = true;
  else if (word == "off")
    *out = false;
  else
    return false;
  return true;
}

std::string parse_no_words(const VerbArgs& args, NoArgs&) {
  if (args.size() == 0) return "";
  // Piece by piece: GCC 12 warns (-Wrestrict, wrongly) about "'" + std::string.
  std::string message = "'";
  message += args.verb();
  message += "' takes no arguments";
  return message;
}

std::string parse_one_word(const VerbArgs& args, Word& out) {
  if (args.size() != 1) return args.usage_error();
  out.word = args[0];
  return "";
}

std::string parse_on_off_word(const VerbArgs& args, OnOff& out) {
  if (args.size() != 1 || !parse_on_off(args[0], &out.on)) return args.usage_error();
  return "";
}

void print_script_line(const std::string& line) {
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

void VerbTable::add(Verb verb) {
  ACCEL_CHECK(!find(verb.name));  // one module declares each verb
  verbs_.push_back(std::move(verb));
}

const Verb* VerbTable::find(std::string_view name) const {
  for (const Verb& v : verbs_)
    if (name == v.name) return &v;
  return nullptr;
}

std::string parse_step_words(const VerbArgs& args, PlayerMove& out, bool hit) {
  const size_t n = args.size();
  int& count = out.count;
  if (n == 1 && args[0] == "end")
    out.mode = StepMode::End;
  else if (n == 1 && args[0] == "start")
    out.mode = StepMode::Start;
  else if (hit && n == 1 && args[0] == "hit")
    out.mode = StepMode::Hit;
  else if (n == 1 && parse_script_int(args[0], &count) && count >= 0)
    out.mode = StepMode::Forward;
  else if (n == 2 && args[0] == "back" && parse_script_int(args[1], &count) && count >= 0)
    out.mode = StepMode::Back;
  else
    return args.usage_error();
  return "";
}

// ---------------------------------------------------------------------------------------
// Help and docs

std::vector<std::string> keys_help_lines(const std::vector<KeyGroup>& groups) {
  std::vector<std::string> lines;
  for (const KeyGroup& g : groups)
    for_each_label(g.rows, [&](const KeyBinding& b) { lines.push_back(b.keys + ": " + b.help); });
  return lines;
}

std::string keys_markdown(const std::vector<KeyGroup>& groups) {
  std::string table = "| key | what it does |\n|---|---|\n";
  for (const KeyGroup& g : groups)
    for_each_label(g.rows, [&](const KeyBinding& b) {
      table += "| " + keys_as_code(b.keys) + " | " + table_cell(b.help) + " |\n";
    });
  return table;
}

std::string keys_summary_markdown(const std::vector<KeyGroup>& groups) {
  std::string table = "| tool | keys | what they do |\n|---|---|---|\n";
  // The mouse in the 3D view first (input.h's rows; the blackboard's are in docs/viewer.md).
  std::string mice, meanings;
  for (const MouseRow& row : mouse_rows()) {
    if (!*row.in_3d) continue;
    mice += (mice.empty() ? "" : ", ") + table_cell(row.mouse);
    meanings += (meanings.empty() ? "" : "; ") + table_cell(row.in_3d);
  }
  table += "| mouse (3D view) | " + mice + " | " + meanings + " |\n";
  for (const KeyGroup& g : groups) {
    std::string keys, helps;
    for_each_label(g.rows, [&](const KeyBinding& b) {
      keys += (keys.empty() ? "" : ", ") + keys_as_code(b.keys);
      helps += (helps.empty() ? "" : "; ") + table_cell(b.help);
    });
    table += "| " + std::string(g.tool) + " | " + keys + " | " + helps + " |\n";
  }
  return table;
}

std::string verbs_markdown(const VerbTable& verbs) {
  std::string table = "| command | what it does |\n|---|---|\n";
  for (const Verb& v : verbs) {
    // The forms of the usage, each as code: "step N | step end" -> `step N`, `step end`.
    std::string forms;
    const std::string usage = v.usage;
    size_t start = 0;
    while (start <= usage.size()) {
      const size_t bar = usage.find(" | ", start);
      const size_t end = bar == std::string::npos ? usage.size() : bar;
      forms += (forms.empty() ? "`" : ", `") + table_cell(usage.substr(start, end - start)) + "`";
      if (bar == std::string::npos) break;
      start = bar + 3;
    }
    table += "| " + forms + " | " + table_cell(v.help) + " |\n";
  }
  return table;
}

std::string mouse_markdown() {
  std::string table = "| mouse | 3D view | blackboard (2D mode) |\n|---|---|---|\n";
  auto cell = [](const char* what) { return *what ? table_cell(what) : std::string("\u2014"); };
  for (const MouseRow& row : mouse_rows())
    table += "| " + table_cell(row.mouse) + " | " + cell(row.in_3d) + " | " + cell(row.in_2d) + " |\n";
  return table;
}

}  // namespace viz
