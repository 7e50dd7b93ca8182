// Hostile submission: floods the judge with output in build(): 300 MB to stdout and 300 MB
// to stderr, alternating 64 KB chunks (so a judge that drains one stream before the other
// deadlocks), each flushed; a stream stops at its first failed write. Every ray would miss.
// The grader must report it FAILED ("printed more than the output limit" or the like),
// keep at most the limit of it, neither hang nor run out of memory or disk.
#include <cstdio>
#include <cstring>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class FloodOutput : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    static char chunk[64 * 1024];
    std::memset(chunk, 'x', sizeof chunk);
    for (size_t i = 63; i < sizeof chunk; i += 64) chunk[i] = '\n';
    bool out_ok = true, err_ok = true;
    for (size_t written = 0; written < (size_t(300) << 20) && (out_ok || err_ok); written += sizeof chunk) {
      if (out_ok) out_ok = std::fwrite(chunk, 1, sizeof chunk, stdout) == sizeof chunk && std::fflush(stdout) == 0;
      if (err_ok) err_ok = std::fwrite(chunk, 1, sizeof chunk, stderr) == sizeof chunk && std::fflush(stderr) == 0;
    }
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(FloodOutput, "hostile_flood_output", bvh)
