// Hostile submission: its build() logs without end -- leaves of 4,096 triangle references
// each, a new node every call -- so a judge that mirrors the build log without a bound of its
// own would run out of memory long before the worker does (the worker keeps nothing). The
// grader must stop it with the kit's bound ("the kit keeps at most that many"), report it
// FAILED, and neither hang nor grow.
#include <cstdint>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class FloodLog : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> some(4096, 0);
    for (uint32_t p = 0; p < some.size() && p < scene.size(); ++p) some[p] = p;
    log.node(0, kNoParent, 0, scene.bounds(), some);
    for (uint32_t id = 1;; ++id) {
      log.node(id, 0, 1, scene.bounds(), some);
      log.leaf(id, some);
    }
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(FloodLog, "hostile_flood_log", bvh)
