#pragma once
// One submission's grade in the result files of course platforms (Gradescope, PrairieLearn),
// and the safe reading of a submission's report that they and class_report.h share: every
// field is read with its type checked and every text is cleaned, so a malformed or hostile
// report gives defaults and printable text, never an exception or a broken file.
//
// A submission (STUDENT) is the object `accelviz-cli grade-class` writes per student:
//   {"student", "passed", "seconds", "compile": {"ok", "seconds", "error"},
//    "structures": [the report of `accelviz-cli check --json` per structure, plus
//                   "failure", "output", "output_bytes"]}
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace cli {

// [SECTION] Reading a submission's report

/// Text from a submission made safe to show anywhere: invalid UTF-8 becomes U+FFFD; control
/// characters other than \n and \t, and bidirectional overrides, are dropped; the result holds
/// at most `max_bytes`, cut at a character boundary (`*cut` says whether anything was cut).
std::string clean_text(std::string_view text, size_t max_bytes = std::string::npos, bool* cut = nullptr);
/// j[key] as clean text when `j` is an object holding a string there, else `fallback`.
std::string text_of(const nlohmann::json& j, const char* key, const std::string& fallback = "");
/// j[key] when it is a finite number, else `fallback`.
double number_of(const nlohmann::json& j, const char* key, double fallback = 0.0);
/// j[key] when it is a non-negative number (rounded down), else `fallback`.
uint64_t count_of(const nlohmann::json& j, const char* key, uint64_t fallback = 0);
/// j[key] when it is a boolean, else `fallback`.
bool flag_of(const nlohmann::json& j, const char* key, bool fallback = false);
/// j[key] when it is an array, else an empty array.
const nlohmann::json& list_of(const nlohmann::json& j, const char* key);
/// j[key] when it is an object, else an empty object.
const nlohmann::json& object_of(const nlohmann::json& j, const char* key);
/// 1234567 -> "1,234,567".
std::string grouped(uint64_t n);

/// Wrong answers of one entry of a structure's "categories", all kinds together.
uint64_t category_wrong(const nlohmann::json& category);
/// Rays a structure was checked on, and its wrong answers: the report's totals, or the sums
/// over its categories when a total is missing.
uint64_t structure_rays(const nlohmann::json& structure);
uint64_t structure_wrong(const nlohmann::json& structure);
/// An invariant that applies to the structure and failed at least once.
bool invariant_failed(const nlohmann::json& invariant);
/// mrays_per_s / builtin_mrays_per_s of a structure's "speed", 0 when either is missing.
double speed_vs_builtin(const nlohmann::json& speed);
/// A structure's check finished ("failure" empty) and found nothing wrong ("passed").
bool structure_passed(const nlohmann::json& structure);
/// The submission compiled, holds at least one structure, and every structure passed.
bool submission_passed(const nlohmann::json& student);
/// One line per structure ("my_kdtree: FAILED — 1,234 wrong answers of 300,000; trap: ..."),
/// its failure and faults, or the compile error; at most 4 KB.
std::string submission_summary(const nlohmann::json& student);

// [SECTION] Platforms' result files
//
// The tests, the same for both platforms, 1 point each: "compiles"; per structure one per
// category ("<structure>: <category> (<rays> rays)", no wrong answer), one per invariant that
// applies ("<structure>: invariant: <name>", never failed), and "<structure>: no crash, loop
// or exception". A compile error leaves "compiles" alone, at 0 points.
//
// A check that crashed part way reports no categories: name them in `expected_categories`
// (e.g. the class's union) so each one it did not reach counts as a failed test instead of
// vanishing, which would lift the fraction PrairieLearn grades by.

/// Gradescope's results.json (gradescope-autograders.readthedocs.io/en/latest/specs/): score
/// (the points, one per passed test), output, tests, stdout_visibility, and a leaderboard
/// (Mrays/s and the ratio to the built-in's) when a structure that passed was timed.
nlohmann::json gradescope_results(const nlohmann::json& student,
                                  const std::vector<std::string>& expected_categories = {});
/// PrairieLearn's external grader results.json (prairielearn.readthedocs.io, externalGrading):
/// gradable (always true, so a compile error reaches the student), score in [0, 1], a one-line
/// message, output and tests.
nlohmann::json prairielearn_results(const nlohmann::json& student,
                                    const std::vector<std::string>& expected_categories = {});

}  // namespace cli
