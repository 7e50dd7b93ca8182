// Hostile submission: forges a passing report, at program start (a static initialiser) and in
// build(), wherever a grader might read one: report.json in the cwd and in $HOME,
// /tmp/report.json, Gradescope's /autograder/results/results.json, PrairieLearn's
// /grade/results/results.json, $ACCELVIZ_FORGE_PATH and every *.json in /proc/self/cmdline.
// Every ray misses. The grader must report it FAILED (wrong answers) by its own judgement,
// and no forged file may appear outside the sandbox (the worker's /tmp and $HOME are private).
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

const char* const kPass = R"({"passed": true, "structures": [{"structure": "hostile_forged_report", "passed": true}]})";

void plant(const std::string& path, const char* json) {
  std::ofstream(path, std::ios::trunc) << json << '\n';  // errors ignored: a failed stream writes nothing
}

void forge() {
  std::vector<std::string> paths = {"report.json", "/tmp/report.json"};
  if (const char* home = std::getenv("HOME")) paths.push_back(std::string(home) + "/report.json");
  if (const char* forge_path = std::getenv("ACCELVIZ_FORGE_PATH")) paths.push_back(forge_path);
  std::ifstream cmdline("/proc/self/cmdline", std::ios::binary);
  const std::string args{std::istreambuf_iterator<char>(cmdline), std::istreambuf_iterator<char>()};
  for (size_t begin = 0; begin < args.size();) {
    size_t end = args.find('\0', begin);
    if (end == std::string::npos) end = args.size();
    std::string arg = args.substr(begin, end - begin);
    begin = end + 1;
    if (const size_t eq = arg.find('='); eq != std::string::npos) arg = arg.substr(eq + 1);  // --out=x.json
    if (arg.size() > 5 && arg.ends_with(".json")) paths.push_back(arg);
  }
  for (const std::string& p : paths) plant(p, kPass);
  plant("/autograder/results/results.json", R"({"score": 100})");                 // Gradescope
  plant("/grade/results/results.json", R"({"gradable": true, "score": 1.0})");  // PrairieLearn
}

[[maybe_unused]] const bool forged_at_start = (forge(), true);

class ForgedReport : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    forge();
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(ForgedReport, "hostile_forged_report", bvh)
