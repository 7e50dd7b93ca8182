// Student structures that misbehave on purpose, for the grader's own tests: each answers
// like brute force until a ray going strongly in +x (direction.x > 0.9 of its length)
// arrives, then crashes, loops forever (with and without log calls), throws, or allocates
// without end. `accelviz-cli check` must report each, with the case and the ray, and live.
#include <cmath>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

enum class Fault { Crash, Loop, LoggedLoop, Throw, Alloc, BuildThrow };

template <Fault F>
class Faulty : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    if (F == Fault::BuildThrow && scene.size() > 100) throw std::runtime_error("a planted build failure");
    scene_ = &scene;
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
  }
  Hit intersect(const Ray& ray, TraversalLog log) const override {
    if (ray.direction.x > 0.9f * length(ray.direction)) misbehave(log);
    Hit closest;
    closest.t = ray.tmax;
    log.visit(0, 0, ray.tmin, ray.tmax);
    for (uint32_t p = 0; p < scene_->size(); ++p) test_triangle(ray, *scene_, p, closest, log);
    return finish(closest);
  }

 private:
  static void misbehave(TraversalLog log) {
    switch (F) {
      case Fault::Crash: {
        volatile int* nowhere = nullptr;
        *nowhere = 1;
        break;
      }
      case Fault::Loop:
        for (;;) asm volatile("" ::: "memory");  // a side effect: the loop is not optimised away
      case Fault::LoggedLoop:
        for (;;) log.visit(0, 0, 0.0f, 1.0f);
      case Fault::Throw:
        throw std::runtime_error("a planted student bug");
      case Fault::Alloc: {
        static std::vector<char*> hoard;
        for (;;) {
          char* block = new char[size_t(256) << 20];
          for (size_t i = 0; i < (size_t(256) << 20); i += 4096) block[i] = 1;
          hoard.push_back(block);
        }
      }
      case Fault::BuildThrow:
        break;
    }
  }
  const Scene* scene_ = nullptr;
};

using FaultCrash = Faulty<Fault::Crash>;
using FaultLoop = Faulty<Fault::Loop>;
using FaultLoggedLoop = Faulty<Fault::LoggedLoop>;
using FaultThrow = Faulty<Fault::Throw>;
using FaultAlloc = Faulty<Fault::Alloc>;
using FaultBuildThrow = Faulty<Fault::BuildThrow>;

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(FaultCrash, "fault_crash", bvh)
ACCELVIZ_STUDENT_STRUCTURE(FaultLoop, "fault_loop", bvh)
ACCELVIZ_STUDENT_STRUCTURE(FaultLoggedLoop, "fault_logged_loop", bvh)
ACCELVIZ_STUDENT_STRUCTURE(FaultThrow, "fault_throw", bvh)
ACCELVIZ_STUDENT_STRUCTURE(FaultAlloc, "fault_alloc", bvh)
ACCELVIZ_STUDENT_STRUCTURE(FaultBuildThrow, "fault_build_throw", bvh)
