// Hostile submission: build() logs a sane root leaf, then sleeps forever (an hour at a time)
// without using any CPU, so a CPU-time limit alone never stops it. The grader must report
// it FAILED ("no answer within the time limit" or the like) after its wall-clock limit,
// kill the worker, and go on with the other structures.
#include <chrono>
#include <thread>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class SleepBuild : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    for (;;) std::this_thread::sleep_for(std::chrono::hours(1));
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(SleepBuild, "hostile_sleep_build", bvh)
