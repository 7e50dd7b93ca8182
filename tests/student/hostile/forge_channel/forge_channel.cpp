// Hostile submission: writes straight into the worker's channel to the judge (file
// descriptors 3 and 4 are the kit's wire; see core/student/worker_protocol.h): first frames
// that claim a finished build and a hit for every ray the judge may ask, then a frame whose
// length says 1 GiB. Whatever reaches the judge this way is data it checks, never a verdict:
// forged answers are judged against its own reference, and a frame that is not the
// protocol's ends the check with "broke the kit's channel". The grader must report FAILED.
#include <unistd.h>

#include <cstdint>
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

void forge(uint32_t type, const void* payload, uint32_t size) {
  const uint32_t header[2] = {type, size};
  if (write(4, header, sizeof header) < 0 || (size && write(4, payload, size) < 0)) return;
}

class ForgeChannel : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    forge(109, nullptr, 0);  // "BuildDone", before the real one
    const struct { int32_t prim; float t, u, v; } hit{0, 1.0f, 0.0f, 0.0f};
    for (int i = 0; i < 1000; ++i) forge(121, &hit, sizeof hit);  // "Answer": triangle 0 at t = 1
    forge(121, nullptr, 1u << 30);  // a frame of 1 GiB that never comes
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(ForgeChannel, "hostile_forge_channel", bvh)
