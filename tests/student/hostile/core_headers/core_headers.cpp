// Hostile submission: reaches past the kit into accelviz's core -- includes the built-in
// kd-tree (core/structures/kd_tree.h) and the registry (core/registry.h) and answers with
// accel::find_structure("kdtree") over a copy of the scene, so it would pass without a line
// of its own. The grader must refuse it at compile time: the worker is compiled with the
// include path student/ only, so this file MUST NOT COMPILE, and the report must show the
// compiler's error naming structures/kd_tree.h.
#include <memory>
#include <vector>

#include "structures/kd_tree.h"
#include "registry.h"
#include "accelviz_student.h"

namespace {

class CoreHeaders : public accelviz::StudentStructure {
 public:
  void build(const accelviz::Scene& scene, accelviz::BuildLog& log) override {
    std::vector<accel::Vec3> positions;
    std::vector<accel::UVec3> triangles;
    std::vector<uint32_t> all;
    for (uint32_t p = 0; p < scene.size(); ++p) {
      const accelviz::Triangle& t = scene.triangle(p);
      for (const accelviz::Vec3& v : {t.v0, t.v1, t.v2}) positions.push_back({v.x, v.y, v.z});
      triangles.push_back({3 * p, 3 * p + 1, 3 * p + 2});
      all.push_back(p);
    }
    log.node(0, accelviz::kNoParent, 0, scene.bounds(), all);
    log.leaf(0, all);
    scene_ = std::make_unique<accel::Scene>(std::move(positions), std::move(triangles));
    const accel::StructureInfo* kd = accel::find_structure("kdtree").value();
    tree_ = std::move(accel::build_structure(*kd, *scene_, accel::ParamSet{}).value());
  }
  accelviz::Hit intersect(const accelviz::Ray& ray, accelviz::TraversalLog) const override {
    accel::Ray r;
    r.org = {ray.origin.x, ray.origin.y, ray.origin.z};
    r.dir = {ray.direction.x, ray.direction.y, ray.direction.z};
    r.tmin = ray.tmin, r.tmax = ray.tmax;
    const accel::Hit h = tree_->intersect(r);
    return h.prim < 0 ? accelviz::Hit{} : accelviz::Hit{h.prim, h.t, h.u, h.v};
  }

 private:
  std::unique_ptr<accel::Scene> scene_;
  std::unique_ptr<accel::Structure> tree_;
};

}  // namespace

ACCELVIZ_STUDENT_STRUCTURE(CoreHeaders, "hostile_core_headers", kdtree)
