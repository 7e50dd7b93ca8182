// Hostile submission: a static initialiser calls _Exit(0), so the program leaves with exit
// code 0 before main() runs -- before the worker has said a word. Every ray would miss.
// The grader must report it FAILED ("the worker exited (code 0) before answering" or the
// like): a clean exit code is never a pass, only answers the judge checked are.
#include <cstdlib>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

bool leave_before_main() { std::_Exit(0); }

[[maybe_unused]] const bool left = leave_before_main();

class ExitStatic : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(ExitStatic, "hostile_exit_static", bvh)
