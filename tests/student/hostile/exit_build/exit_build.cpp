// Hostile submission: calls std::exit(0) inside build(), after logging a sane root leaf, so
// the worker disappears with exit code 0 (atexit handlers and all) in the middle of a case.
// The grader must report it FAILED, naming the worker's exit (code 0) during the build; a
// clean exit code is never a pass.
#include <cstdlib>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class ExitBuild : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    std::exit(0);
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(ExitBuild, "hostile_exit_build", bvh)
