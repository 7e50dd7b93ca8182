#include "class_report.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string_view>
#include <vector>

#include "platform_formats.h"
#include "text_format.h"

// Index
//   [SECTION] Text helpers
//   [SECTION] CSV
//   [SECTION] HTML: header and students table
//   [SECTION] HTML: the class's traps
//   [SECTION] HTML: speed leaderboard
//   [SECTION] HTML: faults
//   [SECTION] HTML: the page

namespace cli {

using accel::fixed;

namespace {

using nlohmann::json;

/// The excerpts of printed output share this budget, each between the two bounds: a class
/// where everyone prints stays a page a browser opens at once (40 students: under 40 KB).
constexpr size_t kOutputBudget = 8 * 1024, kOutputMin = 256, kOutputMax = 2048;
constexpr size_t kCompileErrorBytes = 1500, kFaultBytes = 400, kShortBytes = 90, kFaultsShown = 8;

// [SECTION] Text helpers

/// HTML-escapes text already cleaned by clean_text (both quotes: it also goes in attributes).
std::string esc(std::string_view s) {
  std::string out;
  out.reserve(s.size() + s.size() / 8);
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

/// At most `max_bytes` of `text`, an ellipsis where it was cut.
std::string shortened(const std::string& text, size_t max_bytes) {
  bool cut = false;
  std::string out = clean_text(text, max_bytes, &cut);
  return cut ? out + "…" : out;
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

/// A relative link to a report: every byte but unreserved ones and '/' percent-encoded, so a
/// student's folder named "javascript:..." is a file name, never a scheme.
std::string href_path(std::string_view path) {
  std::string out;
  for (char c : path) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '-' || c == '.' || c == '_' || c == '~' || c == '/') {
      out += c;
    } else {
      char buf[4];
      std::snprintf(buf, sizeof buf, "%%%02X", u);
      out += buf;
    }
  }
  return out;
}

/// A green or red pill; the markup is terse because the table holds one per category and row.
std::string badge(bool ok, const std::string& text) {
  return std::string(ok ? "<i class=g>" : "<i class=r>") + text + "</i>";
}

std::string student_name(const json& student) {
  const std::string name = text_of(student, "student");
  return name.empty() ? "(unnamed)" : name;
}

bool compiled(const json& student) { return flag_of(object_of(student, "compile"), "ok", true); }

/// Invariants that applied and failed, over one structure.
size_t failed_invariants(const json& structure) {
  const json& list = list_of(structure, "invariants");
  return size_t(std::count_if(list.begin(), list.end(), [](const json& i) { return invariant_failed(i); }));
}

/// The texts of a structure's fault list (its non-string entries skipped).
std::vector<std::string> faults_of(const json& structure) {
  std::vector<std::string> out;
  for (const json& f : list_of(structure, "faults"))
    if (f.is_string()) out.push_back(clean_text(f.get_ref<const std::string&>()));
  return out;
}

// [SECTION] CSV

/// RFC 4180: a field holding a comma, a quote or a line break is quoted, its quotes doubled.
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// A text cell a spreadsheet would read as a formula (OWASP's CSV injection list) starts
/// with an apostrophe instead; numbers are written by us and never pass through here.
std::string csv_text(const std::string& s) {
  const bool formula = !s.empty() && std::string_view("=+-@\t\r").find(s[0]) != std::string_view::npos;
  return csv_field(formula ? "'" + s : s);
}

std::string csv_row(const json& student) {
  uint64_t rays = 0, wrong = 0, invariants = 0, faults = 0;
  const json* speed = nullptr;
  const json& structures = list_of(student, "structures");
  for (const json& s : structures) {
    rays += structure_rays(s), wrong += structure_wrong(s), invariants += failed_invariants(s);
    faults += faults_of(s).size() + (text_of(s, "failure").empty() ? 0 : 1);
    if (!speed && flag_of(object_of(s, "speed"), "timed")) speed = &object_of(s, "speed");
  }
  const std::string compile_error =
      compiled(student) ? "" : first_line(text_of(object_of(student, "compile"), "error", "compile error"));
  std::string row = csv_text(text_of(student, "student"));
  row += std::string(",") + (submission_passed(student) ? "passed" : "failed");
  row += "," + std::to_string(structures.size()) + "," + std::to_string(rays) + "," + std::to_string(wrong);
  row += "," + std::to_string(invariants) + "," + std::to_string(faults);
  row += "," + (speed ? fixed(number_of(*speed, "mrays_per_s"), "%.6g") : "");
  row += "," + (speed ? fixed(speed_vs_builtin(*speed), "%.4g") : "");
  row += "," + csv_text(compile_error) + "," + csv_text(text_of(student, "report"));
  return row + "\r\n";
}

// [SECTION] HTML: header and students table

/// The category names of the whole class, in the order they first appear.
std::vector<std::string> class_categories(const json& students) {
  std::vector<std::string> names;
  for (const json& st : students)
    for (const json& s : list_of(st, "structures"))
      for (const json& c : list_of(s, "categories"))
        if (const std::string n = text_of(c, "name", "?"); std::find(names.begin(), names.end(), n) == names.end())
          names.push_back(n);
  return names;
}

std::string header_html(const json& cls, const json& students) {
  const size_t n = students.size();
  const size_t passed = size_t(std::count_if(students.begin(), students.end(), submission_passed));
  const double wall = number_of(cls, "wall_seconds");
  std::string h = "<header><h1>" + esc(text_of(cls, "title", "accelviz class report")) + "</h1>\n";
  h += "<p class=\"meta\">generated " + esc(text_of(cls, "generated", "?"));
  if (const std::string dir = text_of(cls, "submissions_dir"); !dir.empty())
    h += " · submissions <code>" + esc(dir) + "</code>";
  h += " · ray scale " + fixed(number_of(cls, "ray_scale", 1.0), "%g") + "</p>\n<div class=\"stats\">";
  h += "<div><b>" + std::to_string(n) + "</b>students</div>";
  h += "<div><b class=\"okc\">" + std::to_string(passed) + "</b>passed</div>";
  h += "<div><b class=\"" + std::string(passed < n ? "badc" : "") + "\">" + std::to_string(n - passed) +
       "</b>failed</div>";
  h +=
      "<div><b>" + fixed(wall, "%.1f") + " s</b>wall time, " + fixed(number_of(cls, "jobs", 1.0), "%g") + " jobs</div>";
  h += "<div><b>" + (n ? fixed(wall / double(n), "%.1f") + " s" : std::string("-")) + "</b>per submission</div></div>\n";
  h += "<p class=\"meta\">sandbox: " + esc(text_of(cls, "sandbox", "none")) + "</p></header>\n";
  return h;
}

/// The student's cell: on a student's first row, a link to the report JSON when there is one.
std::string student_cell(const json& student, bool first_row = true) {
  const std::string name = esc(student_name(student)), report = text_of(student, "report");
  if (!first_row) return "<td class=na>" + name + "</td>";
  std::string cell = report.empty() ? name : "<a href=\"" + esc(href_path(report)) + "\">" + name + "</a>";
  if (flag_of(student, "skipped_unchanged"))
    cell += " <span class=\"na\" title=\"unchanged since the last run: its report was reused\">(reused)</span>";
  return "<td>" + cell + "</td>";
}

std::string category_cell(const json& structure, const std::string& category) {
  for (const json& c : list_of(structure, "categories")) {
    if (text_of(c, "name", "?") != category) continue;
    const uint64_t wrong = category_wrong(c);
    // A check that stopped at a case's build judged none of its rays: not "ok".
    if (count_of(c, "rays") == 0) return "<td class=na title=\"no ray judged\">-</td>";
    return "<td>" + badge(wrong == 0, wrong ? grouped(wrong) : "ok") + "</td>";
  }
  return "<td class=na>-</td>";
}

std::string invariants_cell(const json& structure) {
  const json& list = list_of(structure, "invariants");
  uint64_t checked = 0;
  for (const json& i : list) checked += count_of(i, "checked");
  if (list.empty() || checked == 0) return "<td class=na>-</td>";
  const size_t failed = failed_invariants(structure);
  std::string names;
  for (const json& i : list)
    if (invariant_failed(i)) names += (names.empty() ? "" : ", ") + text_of(i, "name", "?");
  const std::string title = names.empty() ? "" : " title=\"" + esc(names) + "\"";
  return "<td" + title + ">" + badge(failed == 0, failed ? std::to_string(failed) + " failed" : "ok") + "</td>";
}

/// The failure, else the first fault: short, linking to the student's entry under the faults.
std::string fault_cell(const json& structure, size_t student_index) {
  std::string text = text_of(structure, "failure");
  const std::vector<std::string> faults = faults_of(structure);
  if (text.empty() && !faults.empty())
    text = faults.front() + (faults.size() > 1 ? " (+" + std::to_string(faults.size() - 1) + " more)" : "");
  if (text.empty()) return "<td></td>";
  return "<td class=\"f\"><a href=\"#f" + std::to_string(student_index) + "\">" + esc(shortened(text, kShortBytes)) +
         "</a></td>";
}

std::string structure_row(const json& student, size_t index, const json& s, const std::vector<std::string>& cats,
                          bool first_row) {
  std::string row = "<tr>" + student_cell(student, first_row) + "<td>" + esc(text_of(s, "structure", "?")) + "</td>";
  for (const std::string& c : cats) row += category_cell(s, c);
  row += invariants_cell(s) + fault_cell(s, index);
  return row + "<td>" + badge(structure_passed(s), structure_passed(s) ? "PASSED" : "FAILED") + "</td></tr>\n";
}

/// A row for a submission without structures: its compile error, or that none was found.
std::string spanning_row(const json& student, size_t index, size_t span) {
  const std::string what =
      compiled(student)
          ? std::string("no structure found")
          : "<b>compile error</b>: " + esc(shortened(first_line(text_of(object_of(student, "compile"), "error")), 160));
  return "<tr>" + student_cell(student) + "<td class=na>-</td><td colspan=\"" + std::to_string(span) +
         "\" class=\"f\"><a href=\"#f" + std::to_string(index) + "\">" + what + "</a></td><td>" +
         badge(false, "FAILED") + "</td></tr>\n";
}

std::string students_html(const json& students) {
  const std::vector<std::string> cats = class_categories(students);
  std::string h = "<h2 id=\"students\">Students</h2>\n<table><thead><tr><th>student</th><th>structure</th>";
  for (const std::string& c : cats) h += "<th>" + esc(c) + "</th>";
  h += "<th>invariants</th><th>faults / failure</th><th>result</th></tr></thead><tbody>\n";
  for (size_t k = 0; k < students.size(); ++k) {
    const json& st = students[k];
    const json& structures = list_of(st, "structures");
    if (!compiled(st) || structures.empty()) {
      h += spanning_row(st, k, cats.size() + 2);
      continue;
    }
    for (size_t r = 0; r < structures.size(); ++r) h += structure_row(st, k, structures[r], cats, r == 0);
  }
  return h + "</tbody></table>\n";
}

// [SECTION] HTML: the class's traps

/// A trap (or a broken invariant) and who fell into it.
struct ClassTrap {
  bool invariant = false;
  std::string text;
  std::vector<size_t> students;  ///< indices, each once
  std::string example;           ///< the first replay command, or the first failure's text
};

ClassTrap& trap_entry(std::vector<ClassTrap>& traps, bool invariant, const std::string& text) {
  for (ClassTrap& t : traps)
    if (t.invariant == invariant && t.text == text) return t;
  traps.push_back({invariant, text, {}, ""});
  return traps.back();
}

void add_student(ClassTrap& t, size_t student, const std::string& example) {
  if (t.students.empty() || t.students.back() != student) t.students.push_back(student);
  if (t.example.empty()) t.example = example;
}

/// Every trap and broken invariant of the class, the most students first.
std::vector<ClassTrap> class_traps(const json& students) {
  std::vector<ClassTrap> traps;
  for (size_t k = 0; k < students.size(); ++k)
    for (const json& s : list_of(students[k], "structures")) {
      for (const json& w : list_of(s, "wrong_rays"))
        if (const std::string trap = text_of(w, "trap"); !trap.empty())
          add_student(trap_entry(traps, false, trap), k, text_of(w, "replay"));
      for (const json& i : list_of(s, "invariants"))
        if (invariant_failed(i))
          add_student(trap_entry(traps, true, text_of(i, "name", "?")), k, text_of(i, "first_failure"));
    }
  std::stable_sort(traps.begin(), traps.end(),
                   [](const ClassTrap& a, const ClassTrap& b) { return a.students.size() > b.students.size(); });
  return traps;
}

std::string traps_html(const json& students) {
  const std::vector<ClassTrap> traps = class_traps(students);
  std::string h = "<h2 id=\"traps\">The class's traps</h2>\n";
  if (traps.empty()) return h + "<p class=\"meta\">No wrong answer matched a trap, and no invariant failed.</p>\n";
  h += "<table><thead><tr><th>trap or invariant</th><th class=n>students</th><th>who</th>"
       "<th>replay, or the first failure</th></tr></thead><tbody>\n";
  for (const ClassTrap& t : traps) {
    std::string who;
    for (size_t k : t.students) who += (who.empty() ? "" : ", ") + esc(student_name(students[k]));
    h += "<tr><td class=t><span class=\"tag\">" + std::string(t.invariant ? "invariant" : "trap") + "</span> " +
         esc(t.text) + "</td><td class=n>" + std::to_string(t.students.size()) + "</td><td class=w>" + who +
         "</td><td class=t><code>" + esc(shortened(t.example, 600)) + "</code></td></tr>\n";
  }
  return h + "</tbody></table>\n";
}

// [SECTION] HTML: speed leaderboard

struct SpeedEntry {
  size_t student;
  const json* structure;
  double mrays;
};

std::string with_builtin(const json& speed, const char* own, const char* builtin) {
  return fixed(number_of(speed, own), "%.3g") + " <span class=\"na\">(" + fixed(number_of(speed, builtin), "%.3g") +
         ")</span>";
}

std::string speed_html(const json& students) {
  std::vector<SpeedEntry> entries;
  for (size_t k = 0; k < students.size(); ++k)
    for (const json& s : list_of(students[k], "structures"))
      if (structure_passed(s) && flag_of(object_of(s, "speed"), "timed"))
        entries.push_back({k, &s, number_of(object_of(s, "speed"), "mrays_per_s")});
  std::stable_sort(entries.begin(), entries.end(),
                   [](const SpeedEntry& a, const SpeedEntry& b) { return a.mrays > b.mrays; });
  std::string h = "<h2 id=\"speed\">Speed against the built-in</h2>\n";
  if (entries.empty()) return h + "<p class=\"meta\">No structure that passed was timed.</p>\n";
  h += "<table><thead><tr><th class=n>#</th><th>student</th><th>structure</th><th class=n>Mrays/s</th>"
       "<th>built-in</th><th class=n>vs built-in</th><th class=n>nodes/ray (built-in)</th>"
       "<th class=n>triangles/ray (built-in)</th></tr></thead><tbody>\n";
  for (size_t r = 0; r < entries.size(); ++r) {
    const json& s = *entries[r].structure;
    const json& speed = object_of(s, "speed");
    const double ratio = speed_vs_builtin(speed);
    h += "<tr><td class=n>" + std::to_string(r + 1) + "</td><td>" + esc(student_name(students[entries[r].student])) +
         "</td><td class=w>" + esc(text_of(s, "structure", "?")) + "</td><td class=n><b>" +
         fixed(entries[r].mrays, "%.3g") + "</b></td><td>" + esc(text_of(s, "builtin", "?")) + " <span class=\"na\">" +
         fixed(number_of(speed, "builtin_mrays_per_s"), "%.3g") + "</span></td><td class=n>" +
         badge(ratio >= 1.0, fixed(ratio, "%.2f") + "×") + "</td><td class=n>" +
         with_builtin(speed, "nodes_per_ray", "builtin_nodes_per_ray") + "</td><td class=n>" +
         with_builtin(speed, "triangles_per_ray", "builtin_triangles_per_ray") + "</td></tr>\n";
  }
  return h + "</tbody></table>\n";
}

// [SECTION] HTML: faults

bool has_faults(const json& student) {
  if (!compiled(student)) return true;
  for (const json& s : list_of(student, "structures"))
    if (!text_of(s, "failure").empty() || !list_of(s, "faults").empty()) return true;
  return false;
}

/// Bytes of printed output each excerpt may show, the budget shared by those shown.
size_t output_share(const json& students) {
  size_t shown = 0;
  for (const json& st : students)
    if (has_faults(st))
      for (const json& s : list_of(st, "structures")) shown += text_of(s, "output").empty() ? 0 : 1;
  return shown ? std::clamp(kOutputBudget / shown, kOutputMin, kOutputMax) : kOutputMax;
}

std::string structure_faults(const json& s, size_t output_bytes) {
  std::string h = "<p><b>" + esc(text_of(s, "structure", "?")) + "</b>";
  if (const std::string failure = text_of(s, "failure"); !failure.empty())
    h += ": " + badge(false, "failure") + " " + esc(shortened(failure, kFaultBytes));
  h += "</p>\n";
  const std::vector<std::string> faults = faults_of(s);
  if (!faults.empty()) {
    h += "<ul>";
    for (size_t k = 0; k < faults.size() && k < kFaultsShown; ++k)
      h += "<li>" + esc(shortened(faults[k], kFaultBytes)) + "</li>";
    if (faults.size() > kFaultsShown)
      h += "<li class=\"na\">and " + std::to_string(faults.size() - kFaultsShown) + " more</li>";
    h += "</ul>\n";
  }
  if (const std::string output = text_of(s, "output"); !output.empty()) {
    std::string excerpt = clean_text(output, output_bytes);
    while (!excerpt.empty() && excerpt.back() == '\n') excerpt.pop_back();  // the ellipsis on the last line
    const uint64_t total = std::max<uint64_t>(count_of(s, "output_bytes"), output.size());
    h += "<p class=\"meta\">printed " + grouped(total) + " bytes" +
         (total > excerpt.size() ? ", the first " + grouped(excerpt.size()) : std::string()) + ":</p><pre>" +
         esc(excerpt) + (total > excerpt.size() ? "…" : "") + "</pre>\n";
  }
  return h;
}

std::string faults_html(const json& students) {
  std::string h = "<h2 id=\"faults\">Faults</h2>\n";
  const size_t output_bytes = output_share(students);
  bool any = false;
  for (size_t k = 0; k < students.size(); ++k) {
    const json& st = students[k];
    if (!has_faults(st)) continue;
    any = true;
    h += "<section class=\"fault\" id=\"f" + std::to_string(k) + "\"><h3>" + esc(student_name(st)) + "</h3>\n";
    if (!compiled(st))
      h += "<p>" + badge(false, "compile error") + "</p><pre>" +
           esc(shortened(text_of(object_of(st, "compile"), "error", "(no message)"), kCompileErrorBytes)) + "</pre>\n";
    for (const json& s : list_of(st, "structures"))
      if (!text_of(s, "failure").empty() || !list_of(s, "faults").empty()) h += structure_faults(s, output_bytes);
    h += "</section>\n";
  }
  return any ? h : h + "<p class=\"meta\">No compile error, crash or fault.</p>\n";
}

// [SECTION] HTML: the page

constexpr const char* kStyle = R"(
:root{--fg:#1f2328;--mute:#6e7781;--line:#d8dee4;--ok:#1a7f37;--okbg:#dafbe1;--bad:#b3261e;--badbg:#ffebe9}
*{box-sizing:border-box}
body{margin:0;color:var(--fg);background:#fff;font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,"Helvetica Neue",Arial,sans-serif}
main{max-width:1240px;margin:0 auto;padding:20px 20px 60px}
h1{font-size:24px;margin:0 0 4px}
h2{font-size:18px;margin:32px 0 10px;padding-bottom:4px;border-bottom:2px solid var(--line)}
h3{font-size:15px;margin:0 0 6px}
a{color:#0969da;text-decoration:none}a:hover{text-decoration:underline}
.meta,.na{color:var(--mute)}.meta{margin:4px 0}
.stats{display:flex;gap:12px;margin:12px 0}
.stats div{border:1px solid var(--line);border-radius:8px;padding:8px 14px;min-width:120px;color:var(--mute);font-size:12px}
.stats b{display:block;font-size:22px;color:var(--fg)}.stats .okc{color:var(--ok)}.stats .badc{color:var(--bad)}
table{border-collapse:collapse;width:100%;font-size:13px}
th,td{padding:5px 8px;text-align:left;vertical-align:top;border-bottom:1px solid #eaeef2}
td:first-child,td:nth-child(2){max-width:260px;overflow-wrap:anywhere}.w{overflow-wrap:anywhere}.t{min-width:240px;overflow-wrap:anywhere}
thead th{position:sticky;top:0;z-index:1;background:#f6f8fa;border-bottom:1px solid var(--line);font-weight:600;white-space:nowrap}
tbody tr:nth-child(even){background:#f8fafc}tbody tr:hover{background:#eef4ff}
.n{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
i.g,i.r{display:inline-block;padding:1px 8px;border-radius:10px;font-size:12px;font-weight:600;font-style:normal;white-space:nowrap}
i.g{background:var(--okbg);color:var(--ok)}i.r{background:var(--badbg);color:var(--bad)}
.f{max-width:380px;overflow-wrap:anywhere}.f a{color:var(--bad)}
.tag{font-size:11px;text-transform:uppercase;letter-spacing:.04em;color:var(--mute);margin-right:4px}
code,pre{font:12px/1.4 ui-monospace,SFMono-Regular,Menlo,Consolas,monospace;overflow-wrap:anywhere}
pre{background:#f6f8fa;border:1px solid #eaeef2;border-radius:6px;padding:8px 10px;margin:4px 0 10px;max-height:260px;overflow:auto;white-space:pre-wrap}
.fault{overflow-wrap:anywhere;border:1px solid var(--line);border-left:4px solid var(--bad);border-radius:6px;padding:10px 14px;margin:10px 0}
.fault p{margin:4px 0}.fault ul{margin:4px 0 8px;padding-left:22px}
)";

}  // namespace

std::string class_report_csv(const json& cls) {
  std::string csv =
      "student,passed,structures,rays,wrong,invariants_failed,faults,mrays_per_s,speed_vs_builtin,compile_error,"
      "report\r\n";
  for (const json& st : list_of(cls, "students")) csv += csv_row(st);
  return csv;
}

std::string class_report_html(const json& cls) {
  const json& students = list_of(cls, "students");
  const std::string title = esc(text_of(cls, "title", "accelviz class report"));
  std::string h =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'\">\n"
      "<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">\n<title>" +
      title + "</title>\n<style>" + kStyle + "</style></head>\n<body><main>\n";
  h += header_html(cls, students);
  h += students_html(students);
  h += traps_html(students);
  h += speed_html(students);
  h += faults_html(students);
  return h + "</main></body></html>\n";
}

}  // namespace cli
