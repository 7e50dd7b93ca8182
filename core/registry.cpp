#include "registry.h"

#include "brute_force.h"
#include "bvh.h"
#include "kd_tree.h"
#include "octree.h"
#include "sphere_tree.h"
#include "uniform_grid.h"

namespace accel {

const std::vector<StructureInfo>& structure_registry() {
  static const std::vector<StructureInfo> registry = {
      {"brute", "brute force: test every triangle (the reference)", BruteForce::param_specs(),
       [] { return std::make_unique<BruteForce>(); }},
      {"grid", "uniform grid: cells of equal size, 3D-DDA traversal (Amanatides & Woo 1987)",
       UniformGrid::param_specs(), [] { return std::make_unique<UniformGrid>(); }},
      {"octree", "octree: cells split into 8 equal children", Octree::param_specs(),
       [] { return std::make_unique<Octree>(); }},
      {"kdtree", "kd-tree: axis-aligned split planes, near/far traversal", KdTree::param_specs(),
       [] { return std::make_unique<KdTree>(); }},
      {"bvh", "bounding volume hierarchy with axis-aligned boxes (AABB tree)", Bvh::param_specs(),
       [] { return std::make_unique<Bvh>(); }},
      {"spheretree", "bounding volume hierarchy with bounding spheres (sphere tree)", SphereTree::param_specs(),
       [] { return std::make_unique<SphereTree>(); }},
  };
  return registry;
}

std::vector<std::string> structure_names() {
  std::vector<std::string> names;
  for (const auto& info : structure_registry()) names.push_back(info.name);
  return names;
}

Result<const StructureInfo*> find_structure(const std::string& name) {
  std::string valid;
  for (const auto& info : structure_registry()) {
    if (info.name == name) return &info;
    valid += (valid.empty() ? "" : ", ") + info.name;
  }
  return make_error("unknown structure '" + name + "' (valid: " + valid + ")");
}

Result<std::unique_ptr<Structure>> build_structure(const std::string& name, const Scene& scene,
                                                   const std::vector<std::string>& params, Kernel kernel) {
  auto info = find_structure(name);
  if (!info) return info.error();
  auto set = ParamSet::parse(info.value()->params, params, name);
  if (!set) return set.error();
  std::unique_ptr<Structure> s = info.value()->create();
  s->set_kernel(kernel);
  auto built = s->build(scene, set.value());
  if (!built) return built.error();
  return s;
}

}  // namespace accel
