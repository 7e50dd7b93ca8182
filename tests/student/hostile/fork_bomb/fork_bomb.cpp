// Hostile submission: a (bounded) fork bomb in build(): at most 200 fork() calls, stopping at
// the first that fails; each child sleeps 30 s and _exit(0)s without forking again. Then it
// throws "forked N children". Every ray would miss. The grader must report it FAILED, and
// the sandbox's seccomp filter must refuse fork (EPERM), so the message reads
// "forked 0 children" and no stray process outlives the worker.
#include <unistd.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class ForkBomb : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    int forked = 0;
    for (int i = 0; i < 200; ++i) {  // bounded: never more than 200 fork() calls in all
      const pid_t pid = fork();
      if (pid == 0) {  // the child: no fork, no return into the kit, no atexit handlers
        sleep(30);
        _exit(0);
      }
      if (pid < 0) break;
      ++forked;
    }
    throw std::runtime_error("forked " + std::to_string(forked) + " children");
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(ForkBomb, "hostile_fork_bomb", bvh)
