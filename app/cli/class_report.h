#pragma once
// The class report of `accelviz-cli grade-class`: a CSV for the grade book and one HTML page
// for the teacher (students x categories, the class's traps, a speed leaderboard, the faults).
// Both read the class object defensively (platform_formats.h's readers): a missing or
// mistyped field gives a default, and every student-controlled text is cleaned and escaped.
//
// The class object:
//   {"title", "generated", "submissions_dir", "sandbox", "ray_scale", "wall_seconds", "jobs",
//    "students": [STUDENT, ...]}
// where STUDENT is a submission as platform_formats.h describes it, plus "hash",
// "skipped_unchanged" and "report" (the path of its report JSON, relative to the HTML file).
#include <nlohmann/json.hpp>
#include <string>

namespace cli {

/// One CSV row per student (RFC 4180 quoting, CRLF line ends, one header row; `passed` holds
/// "passed" or "failed"):
/// student,passed,structures,rays,wrong,invariants_failed,faults,mrays_per_s,speed_vs_builtin,compile_error,report
/// A student's structures are summed (passed only if all passed; faults counts fault texts and
/// failures); the speed is the first timed structure's, empty when none was timed;
/// compile_error is the compiler's first line. Text fields that start with = + - @ (or a tab)
/// get a leading apostrophe, so a spreadsheet never runs a student's name as a formula.
std::string class_report_csv(const nlohmann::json& cls);

/// One self-contained HTML page (inline CSS, no script, nothing external; its Content Security
/// Policy forbids scripts even if an escape were missed): header, students x categories table,
/// the class's traps, the speed leaderboard against the built-in, and the faults with each
/// student's printed output. Laid out for a 1280 px window; under 40 KB for 40 students.
std::string class_report_html(const nlohmann::json& cls);

}  // namespace cli
