// Hostile submission: vandalises the scene it is given. build() logs a sane root leaf, then
// casts const away and moves every triangle's vertices (and its box, and the scene's
// bounds) to 1e30, so no triangle of the worker's copy can be hit; then every ray misses --
// which a reference computed over the vandalised copy would call right. The grader must
// report it FAILED with false misses: the judge's reference is its own untouched copy of the
// scene, never the worker's. (If the kit maps the scene read-only, a crash in build() is
// also a correct verdict.)
#include <vector>

#include "accelviz_student.h"

using namespace accelviz;

namespace {

class ConstCastScene : public StudentStructure {
 public:
  void build(const Scene& scene, BuildLog& log) override {
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) all.push_back(p);
    log.node(0, kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    const Vec3 far(1e30f);
    for (uint32_t p = 0; p < scene.size(); ++p) {
      auto& t = const_cast<Triangle&>(scene.triangle(p));
      t.v0 = t.v1 = t.v2 = far;
      auto& b = const_cast<Box&>(scene.box(p));
      b.lo = b.hi = far;
    }
    auto& bounds = const_cast<Box&>(scene.bounds());
    bounds.lo = bounds.hi = far;
  }
  Hit intersect(const Ray&, TraversalLog) const override { return Hit{}; }
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(ConstCastScene, "hostile_const_cast_scene", bvh)
