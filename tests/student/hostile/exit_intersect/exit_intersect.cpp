// Hostile submission: builds a sane root leaf, then calls std::_Exit(0) from intersect() on
// the first ray: a worker that vanishes mid-case with a clean exit code and no answer.
// The grader must report it FAILED, naming the worker's exit (code 0) while answering rays;
// a clean exit code is never a pass.
#include <cstdlib>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class ExitIntersect : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
  }
  Hit intersect(const Ray&, TraversalLog) const override { std::_Exit(0); }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(ExitIntersect, "hostile_exit_intersect", bvh)
