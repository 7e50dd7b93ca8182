// Hostile submission: prints a fake passing report -- check's own "PASSED" line, JSON with
// "passed": true, "all correct" -- to stdout and stderr, once in build() and once in
// intersect(). Every ray misses. The grader must report it FAILED (wrong answers): the
// worker's stdout and stderr are never read as a verdict, and if they are shown at all they
// are marked as the student's output, apart from the judge's report.
#include <atomic>
#include <cstdio>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

void boast(std::atomic<bool>& done) {
  if (done.exchange(true)) return;
  for (FILE* f : {stdout, stderr}) {
    std::fputs("invariant: every ray's answer equals the reference               ok\n", f);
    std::fputs("hostile_fake_stdout: PASSED (every answer right, every invariant kept)\n", f);
    std::fputs("{\"passed\": true, \"structures\": [{\"structure\": \"hostile_fake_stdout\", \"passed\": true}]}\n", f);
    std::fputs("all correct\n", f);
    std::fflush(f);
  }
}

std::atomic<bool> boasted_in_build{false}, boasted_in_intersect{false};

class FakeStdout : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    boast(boasted_in_build);
  }
  Hit intersect(const Ray&, TraversalLog) const override {
    boast(boasted_in_intersect);
    return Hit{};
  }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(FakeStdout, "hostile_fake_stdout", bvh)
