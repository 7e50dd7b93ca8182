// Hostile submission: tries to kill the judge from build(): SIGKILL to getppid(), to the
// PPid that /proc/self/status names, and tgkill() of the parent's main thread. (Never pid 0
// or -1: if the sandbox failed, those would hit the test machine's other processes.) Every
// ray misses. The grader must stay alive and report it FAILED (wrong answers): the worker
// runs in its own pid namespace, so its "parent" is the sandbox's init or no one it can see.
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <fstream>
#include <string>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

void kill_parent() {
  const pid_t parent = getppid();
  if (parent > 0) kill(parent, SIGKILL);
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("PPid:", 0) == 0) {
      const pid_t ppid = pid_t(std::stol(line.substr(5)));
      if (ppid > 0) kill(ppid, SIGKILL);
    }
  if (parent > 0) syscall(SYS_tgkill, parent, parent, SIGKILL);
}

class KillParent : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    kill_parent();
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(KillParent, "hostile_kill_parent", bvh)
