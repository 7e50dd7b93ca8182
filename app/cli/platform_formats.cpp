#include "platform_formats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "text_format.h"

// Index
//   [SECTION] Reading a submission's report
//   [SECTION] The summary
//   [SECTION] The tests
//   [SECTION] Gradescope
//   [SECTION] PrairieLearn

namespace cli {

using accel::fixed;

namespace {

using nlohmann::json;

constexpr char32_t kReplacement = 0xFFFD;
/// The summary stays readable on both platforms' pages; a compile error of hundreds of
/// template lines says no more than its first few.
constexpr size_t kSummaryBytes = 4096, kTestOutputBytes = 4096, kCompileErrorBytes = 3000, kOutputExcerptBytes = 1024;

struct CodePoint {
  char32_t value;
  size_t length;  ///< bytes it took; 1 for an invalid byte, which decodes to U+FFFD
};

/// RFC 3629: overlong forms, surrogates and values past U+10FFFF are invalid, each byte of
/// them decoding to U+FFFD, so no byte sequence can hide a '<' or a control character.
CodePoint decode_utf8(std::string_view s, size_t i) {
  const auto b0 = static_cast<unsigned char>(s[i]);
  if (b0 < 0x80) return {b0, 1};
  size_t length = 0;
  char32_t cp = 0, smallest = 0;
  if ((b0 & 0xE0) == 0xC0) {
    length = 2, cp = b0 & 0x1F, smallest = 0x80;
  } else if ((b0 & 0xF0) == 0xE0) {
    length = 3, cp = b0 & 0x0F, smallest = 0x800;
  } else if ((b0 & 0xF8) == 0xF0) {
    length = 4, cp = b0 & 0x07, smallest = 0x10000;
  } else {
    return {kReplacement, 1};
  }
  if (i + length > s.size()) return {kReplacement, 1};
  for (size_t k = 1; k < length; ++k) {
    const auto b = static_cast<unsigned char>(s[i + k]);
    if ((b & 0xC0) != 0x80) return {kReplacement, 1};
    cp = (cp << 6) | (b & 0x3F);
  }
  if (cp < smallest || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return {kReplacement, 1};
  return {cp, length};
}

size_t encode_utf8(char32_t cp, char* out) {
  if (cp < 0x80) {
    out[0] = char(cp);
    return 1;
  }
  if (cp < 0x800) {
    out[0] = char(0xC0 | (cp >> 6)), out[1] = char(0x80 | (cp & 0x3F));
    return 2;
  }
  if (cp < 0x10000) {
    out[0] = char(0xE0 | (cp >> 12)), out[1] = char(0x80 | ((cp >> 6) & 0x3F)), out[2] = char(0x80 | (cp & 0x3F));
    return 3;
  }
  out[0] = char(0xF0 | (cp >> 18)), out[1] = char(0x80 | ((cp >> 12) & 0x3F));
  out[2] = char(0x80 | ((cp >> 6) & 0x3F)), out[3] = char(0x80 | (cp & 0x3F));
  return 4;
}

/// Control characters (C0, DEL, C1) could rewrite a terminal or a spreadsheet cell; the
/// bidirectional overrides could make one student's name read as another's.
bool shown(char32_t cp) {
  if (cp == '\n' || cp == '\t') return true;
  if (cp < 0x20 || (cp >= 0x7F && cp <= 0x9F)) return false;
  return !(cp >= 0x202A && cp <= 0x202E) && !(cp >= 0x2066 && cp <= 0x2069);
}

/// Past an ANSI control sequence (ESC [ parameters final) starting at `i`: a student's colored
/// output reads as text once its escapes are gone, where dropping ESC alone leaves "[31m".
size_t after_csi(std::string_view s, size_t i) {
  for (size_t k = i + 2; k < s.size() && k < i + 32; ++k)
    if (s[k] >= 0x40 && s[k] <= 0x7E) return k + 1;
  return i + 1;  // not a sequence after all: drop the ESC only
}

/// The entry of an object, or nullptr (never throws, whatever `j` is).
const json* entry(const json& j, const char* key) {
  if (!j.is_object()) return nullptr;
  const auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

uint64_t sum_over_categories(const json& structure, const char* key) {
  uint64_t sum = 0;
  for (const json& c : list_of(structure, "categories")) sum += key ? count_of(c, key) : category_wrong(c);
  return sum;
}

/// `text` cut to `max_bytes` with a note saying so, the note included in the bound.
std::string bounded(const std::string& text, size_t max_bytes) {
  static constexpr std::string_view kNote = "\n... (cut)";
  bool cut = false;
  std::string out = clean_text(text, max_bytes, &cut);
  if (!cut) return out;
  out = clean_text(out, max_bytes > kNote.size() ? max_bytes - kNote.size() : 0);
  return out += kNote;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

// [SECTION] Reading a submission's report

std::string clean_text(std::string_view text, size_t max_bytes, bool* cut) {
  std::string out;
  out.reserve(std::min(text.size(), max_bytes));
  bool stopped = false;
  for (size_t i = 0; i < text.size();) {
    if (text[i] == '\x1b' && i + 1 < text.size() && text[i + 1] == '[') {
      i = after_csi(text, i);
      continue;
    }
    const CodePoint cp = decode_utf8(text, i);
    i += cp.length;
    if (!shown(cp.value)) continue;
    char buf[4];
    const size_t n = encode_utf8(cp.value, buf);
    if (out.size() + n > max_bytes) {
      stopped = true;
      break;
    }
    out.append(buf, n);
  }
  if (cut) *cut = stopped;
  return out;
}

std::string text_of(const json& j, const char* key, const std::string& fallback) {
  const json* v = entry(j, key);
  return v && v->is_string() ? clean_text(v->get_ref<const std::string&>()) : fallback;
}

double number_of(const json& j, const char* key, double fallback) {
  const json* v = entry(j, key);
  if (!v || !v->is_number()) return fallback;
  const double d = v->get<double>();
  return std::isfinite(d) ? d : fallback;
}

uint64_t count_of(const json& j, const char* key, uint64_t fallback) {
  const json* v = entry(j, key);
  if (!v) return fallback;
  if (v->is_number_unsigned()) return v->get<uint64_t>();
  if (v->is_number_integer()) return v->get<int64_t>() >= 0 ? uint64_t(v->get<int64_t>()) : fallback;
  if (v->is_number_float()) {
    const double d = v->get<double>();
    return d >= 0.0 && d < 1.8e19 ? uint64_t(d) : fallback;  // NaN fails both tests
  }
  return fallback;
}

bool flag_of(const json& j, const char* key, bool fallback) {
  const json* v = entry(j, key);
  return v && v->is_boolean() ? v->get<bool>() : fallback;
}

const json& list_of(const json& j, const char* key) {
  static const json kEmpty = json::array();  // immutable: no state shared between calls
  const json* v = entry(j, key);
  return v && v->is_array() ? *v : kEmpty;
}

const json& object_of(const json& j, const char* key) {
  static const json kEmpty = json::object();
  const json* v = entry(j, key);
  return v && v->is_object() ? *v : kEmpty;
}

std::string grouped(uint64_t n) {
  const std::string digits = std::to_string(n);
  std::string out;
  for (size_t k = 0; k < digits.size(); ++k) {
    if (k && (digits.size() - k) % 3 == 0) out += ',';
    out += digits[k];
  }
  return out;
}

uint64_t category_wrong(const json& category) {
  const json& wrong = object_of(category, "wrong");
  uint64_t sum = 0;
  for (const auto& item : wrong.items()) sum += count_of(wrong, item.key().c_str());
  return sum;
}

uint64_t structure_rays(const json& structure) {
  return count_of(structure, "rays", sum_over_categories(structure, "rays"));
}

uint64_t structure_wrong(const json& structure) {
  return count_of(structure, "wrong", sum_over_categories(structure, nullptr));
}

bool invariant_failed(const json& invariant) {
  return flag_of(invariant, "applies", true) && count_of(invariant, "failed") > 0;
}

double speed_vs_builtin(const json& speed) {
  const double builtin = number_of(speed, "builtin_mrays_per_s");
  return builtin > 0.0 ? number_of(speed, "mrays_per_s") / builtin : 0.0;
}

bool structure_passed(const json& structure) {
  return flag_of(structure, "passed") && text_of(structure, "failure").empty();
}

bool submission_passed(const json& student) {
  if (!flag_of(object_of(student, "compile"), "ok", true)) return false;
  const json& structures = list_of(student, "structures");
  if (structures.empty()) return false;
  for (const json& s : structures)
    if (!structure_passed(s)) return false;
  return flag_of(student, "passed", true);  // grade-class may fail a submission for a reason of its own
}

// [SECTION] The summary

namespace {

/// "my_kdtree: FAILED — 1,234 wrong answers of 300,000; trap: ...; invariant broken: ...",
/// then the failure and the faults on lines of their own.
std::string structure_summary(const json& s) {
  const bool passed = structure_passed(s);
  const uint64_t rays = structure_rays(s), wrong = structure_wrong(s);
  std::string line = text_of(s, "structure", "?") + (passed ? ": PASSED — " : ": FAILED — ");
  if (passed)
    line += "all " + grouped(rays) + " answers right";
  else if (wrong)
    line += grouped(wrong) + " wrong answers of " + grouped(rays);
  else
    line += rays ? "no wrong answer in " + grouped(rays) + " rays" : std::string("no ray checked");
  for (const json& w : list_of(s, "wrong_rays"))
    if (const std::string trap = text_of(w, "trap"); !trap.empty()) {
      line += "; trap: " + trap;
      break;
    }
  for (const json& i : list_of(s, "invariants"))
    if (invariant_failed(i)) line += "; invariant broken: " + text_of(i, "name", "?");
  const json& speed = object_of(s, "speed");
  if (flag_of(speed, "timed"))
    line += "; " + fixed(number_of(speed, "mrays_per_s"), "%.3g") + " Mrays/s (" +
            fixed(speed_vs_builtin(speed), "%.2f") + "x the built-in's)";
  if (const std::string failure = text_of(s, "failure"); !failure.empty()) line += "\n  " + failure;
  for (const json& f : list_of(s, "faults"))
    if (f.is_string()) line += "\n  fault: " + clean_text(f.get_ref<const std::string&>());
  return line + "\n";
}

}  // namespace

std::string submission_summary(const json& student) {
  const json& compile = object_of(student, "compile");
  if (!flag_of(compile, "ok", true))
    return bounded("compile error:\n" + text_of(compile, "error", "(no message)"), kSummaryBytes);
  std::string text;
  for (const json& s : list_of(student, "structures")) text += structure_summary(s);
  if (text.empty()) text = "no structure was found in the submission\n";
  return bounded(text, kSummaryBytes);
}

// [SECTION] The tests

namespace {

/// One test of the platforms' lists, worth 1 point.
struct Test {
  std::string name;
  bool passed = false;
  std::string output;   ///< the details, several lines
  std::string message;  ///< one short line
};

/// The wrong answers by kind, in the order of check's table, then any kind it does not know.
std::string wrong_by_kind(const json& category) {
  static constexpr std::pair<const char*, const char*> kKinds[] = {{"false_miss", "false miss"},
                                                                   {"false_hit", "false hit"},
                                                                   {"wrong_triangle", "wrong triangle"},
                                                                   {"wrong_t", "wrong t"}};
  const json& wrong = object_of(category, "wrong");
  std::string out;
  for (const auto& [key, label] : kKinds)
    out += (out.empty() ? "" : ", ") + std::string(label) + " " + grouped(count_of(wrong, key));
  for (const auto& item : wrong.items()) {
    bool known = false;
    for (const auto& kind : kKinds) known = known || item.key() == kind.first;
    if (!known) out += ", " + clean_text(item.key()) + " " + grouped(count_of(wrong, item.key().c_str()));
  }
  return out;
}

/// The lecture's traps behind a category's wrong rays, each with the first replay found for it.
std::string traps_in(const json& structure, const std::string& category) {
  std::string out;
  for (const json& w : list_of(structure, "wrong_rays")) {
    const std::string trap = text_of(w, "trap");
    if (trap.empty() || text_of(w, "category") != category || out.find("trap: " + trap + "\n") != std::string::npos)
      continue;
    out += "trap: " + trap + "\n";
    if (const std::string replay = text_of(w, "replay"); !replay.empty()) out += "  replay: " + replay + "\n";
  }
  return out;
}

Test category_test(const json& s, const std::string& structure, const json& c) {
  const std::string name = text_of(c, "name", "?");
  const uint64_t rays = count_of(c, "rays"), wrong = category_wrong(c);
  // No ray judged (the check stopped at the case's build) earns nothing.
  Test t{structure + ": " + name + " (" + grouped(rays) + " rays)", wrong == 0 && rays > 0, "", ""};
  t.message = wrong ? grouped(wrong) + " wrong answers" : rays ? "all answers right" : "no ray was judged";
  if (!rays) {
    t.output = "the check stopped before any ray of this category was judged";
    return t;
  }
  t.output = wrong ? "wrong answers: " + wrong_by_kind(c) + "\n" + traps_in(s, name)
                   : "all " + grouped(rays) + " answers right";
  return t;
}

Test invariant_test(const std::string& structure, const json& i) {
  const uint64_t failed = count_of(i, "failed"), checked = count_of(i, "checked");
  Test t{structure + ": invariant: " + text_of(i, "name", "?"), failed == 0 && checked > 0, "", ""};
  t.message = failed ? "failed " + grouped(failed) + " times" : checked ? "kept" : "never checked";
  t.output = failed ? "failed " + grouped(failed) + " of " + grouped(checked) + " checks; the first:\n" +
                          text_of(i, "first_failure")
                    : "kept in all " + grouped(checked) + " checks";
  return t;
}

Test crash_test(const std::string& structure, const json& s) {
  const std::string failure = text_of(s, "failure");
  const json& faults = list_of(s, "faults");
  Test t{structure + ": no crash, loop or exception", failure.empty() && faults.empty(), "", ""};
  if (t.passed) {
    t.message = "finished";
    t.output = "the check finished without a crash, an endless loop or an exception";
    return t;
  }
  for (const json& f : faults)
    if (f.is_string()) t.output += "fault: " + clean_text(f.get_ref<const std::string&>()) + "\n";
  if (!failure.empty()) t.output = failure + "\n" + t.output;
  t.message = failure.empty() ? grouped(faults.size()) + " faults" : first_line(failure);
  // What the code printed is the student's own, and often says where it went wrong.
  if (std::string printed = bounded(text_of(s, "output"), kOutputExcerptBytes); !printed.empty()) {
    while (!printed.empty() && printed.back() == '\n') printed.pop_back();
    t.output += "your code printed:\n" + printed + "\n";
  }
  return t;
}

/// The tests of one structure: its categories (and the expected ones it never reached), its
/// invariants, and the crash test.
void structure_tests(const json& s, const std::vector<std::string>& expected, std::vector<Test>& tests) {
  const std::string structure = text_of(s, "structure", "?");
  std::vector<std::string> seen;
  for (const json& c : list_of(s, "categories")) {
    tests.push_back(category_test(s, structure, c));
    seen.push_back(text_of(c, "name", "?"));
  }
  for (const std::string& name : expected) {
    if (std::find(seen.begin(), seen.end(), name) != seen.end()) continue;
    const std::string failure = text_of(s, "failure");
    tests.push_back({structure + ": " + name + " (not run)", false,
                     "the check stopped before this category" + (failure.empty() ? "" : ": " + failure), "not run"});
  }
  for (const json& i : list_of(s, "invariants"))
    if (flag_of(i, "applies", true)) tests.push_back(invariant_test(structure, i));
  tests.push_back(crash_test(structure, s));
}

std::vector<Test> grade_tests(const json& student, const std::vector<std::string>& expected) {
  const json& compile = object_of(student, "compile");
  std::vector<Test> tests;
  if (!flag_of(compile, "ok", true)) {
    tests.push_back(
        {"compiles", false, bounded(text_of(compile, "error", "(no message)"), kCompileErrorBytes), "compile error"});
    return tests;
  }
  const double seconds = number_of(compile, "seconds", -1.0);
  tests.push_back(
      {"compiles", true, seconds >= 0.0 ? "compiled in " + fixed(seconds, "%.1f") + " s" : "compiled", "ok"});
  for (const json& s : list_of(student, "structures")) structure_tests(s, expected, tests);
  for (Test& t : tests) t.output = bounded(t.output, kTestOutputBytes);
  return tests;
}

size_t passed_count(const std::vector<Test>& tests) {
  return size_t(std::count_if(tests.begin(), tests.end(), [](const Test& t) { return t.passed; }));
}

/// The speed of the first structure that passed and was timed, or nullptr: like the class
/// report's leaderboard, a structure fast because it skips work it owes is not ranked.
const json* leaderboard_speed(const json& student) {
  for (const json& s : list_of(student, "structures"))
    if (structure_passed(s) && flag_of(object_of(s, "speed"), "timed")) return &object_of(s, "speed");
  return nullptr;
}

}  // namespace

// [SECTION] Gradescope

json gradescope_results(const json& student, const std::vector<std::string>& expected_categories) {
  const std::vector<Test> tests = grade_tests(student, expected_categories);
  json out = {{"score", passed_count(tests)},
              {"output", submission_summary(student)},
              {"stdout_visibility", "visible"},
              {"tests", json::array()}};
  if (const double seconds = number_of(student, "seconds", -1.0); seconds >= 0.0)
    out["execution_time"] = uint64_t(std::ceil(seconds));
  for (const Test& t : tests)
    out["tests"].push_back({{"name", t.name},
                            {"score", t.passed ? 1 : 0},
                            {"max_score", 1},
                            {"output", t.output},
                            {"status", t.passed ? "passed" : "failed"}});
  if (const json* speed = leaderboard_speed(student))
    out["leaderboard"] = {{{"name", "Mrays/s"}, {"value", number_of(*speed, "mrays_per_s")}},
                          {{"name", "vs built-in"}, {"value", speed_vs_builtin(*speed)}}};
  return out;
}

// [SECTION] PrairieLearn

json prairielearn_results(const json& student, const std::vector<std::string>& expected_categories) {
  const std::vector<Test> tests = grade_tests(student, expected_categories);
  const size_t passed = passed_count(tests);
  std::string message;
  if (!flag_of(object_of(student, "compile"), "ok", true))
    message = "compile error";
  else if (passed == tests.size())
    message = "PASSED: all " + std::to_string(tests.size()) + " tests";
  else
    message = "FAILED: " + std::to_string(passed) + " of " + std::to_string(tests.size()) + " tests passed";
  json out = {{"gradable", true},
              {"score", tests.empty() ? 0.0 : double(passed) / double(tests.size())},
              {"message", message},
              {"output", submission_summary(student)},
              {"tests", json::array()}};
  for (const Test& t : tests)
    out["tests"].push_back({{"name", t.name},
                            {"max_points", 1},
                            {"points", t.passed ? 1 : 0},
                            {"output", t.output},
                            {"message", t.message}});
  return out;
}

}  // namespace cli
