#include "registry.h"

#include <limits>

#include "structures/brute_force.h"
#include "structures/bvh.h"
#include "structures/kd_tree.h"
#include "structures/octree.h"
#include "structures/sphere_tree.h"
#include "structures/uniform_grid.h"
#include "student/kit_registry.h"

namespace accel {

namespace {

/// A built-in entry: the StructureInfo fields every structure has (the rest are students').
struct BuiltinEntry {
  std::string name, label, description, node_noun;
  TraversalFamily traversal;
  ConstructionFamily construction;
  bool cells, reference;
  std::vector<ParamSpec> params;
  std::function<std::unique_ptr<Structure>(const ParamSet&)> create;
};

}  // namespace

const std::vector<StructureInfo>& structure_registry() {
  using TF = TraversalFamily;
  using CF = ConstructionFamily;
  static const std::vector<BuiltinEntry> builtins = {
      {"brute", "brute force", "brute force: test every triangle (the reference)", "nodes", TF::Linear, CF::Linear,
       false, true, BruteForce::param_specs(), [](const ParamSet&) { return std::make_unique<BruteForce>(); }},
      {"grid", "uniform grid", "uniform grid: cells of equal size, 3D-DDA traversal (Amanatides & Woo 1987)",
       "cells", TF::Dda, CF::GridInsert, true, false, UniformGrid::param_specs(),
       [](const ParamSet&) { return std::make_unique<UniformGrid>(); }},
      {"octree", "octree", "octree: cells split into 8 equal children", "nodes", TF::Octree, CF::Octree, false,
       false, Octree::param_specs(), [](const ParamSet&) { return std::make_unique<Octree>(); }},
      {"kdtree", "kd-tree", "kd-tree: axis-aligned split planes, near/far traversal", "nodes", TF::KdTree,
       CF::KdTree, false, false, KdTree::param_specs(), [](const ParamSet&) { return std::make_unique<KdTree>(); }},
      {"bvh", "BVH", "bounding volume hierarchy with axis-aligned boxes (AABB tree)", "nodes", TF::Hierarchy,
       CF::Hierarchy, false, false, bvh_param_specs(), make_bvh},
      {"spheretree", "sphere tree", "bounding volume hierarchy with bounding spheres (sphere tree)", "nodes",
       TF::Hierarchy, CF::Hierarchy, false, false, SphereTree::param_specs(),
       [](const ParamSet&) { return std::make_unique<SphereTree>(); }},
  };
  static const std::vector<StructureInfo> registry = [] {
    std::vector<StructureInfo> all;
    for (const BuiltinEntry& b : builtins) {
      StructureInfo info;
      info.name = b.name, info.label = b.label, info.description = b.description, info.node_noun = b.node_noun;
      info.traversal = b.traversal, info.construction = b.construction;
      info.cells = b.cells, info.reference = b.reference;
      info.params = b.params, info.create = b.create;
      all.push_back(std::move(info));
    }
    for (StructureInfo& s : student_structure_infos(all)) all.push_back(std::move(s));
    return all;
  }();
  return registry;
}

std::vector<std::string> structure_names() {
  std::vector<std::string> names;
  for (const auto& info : structure_registry()) names.push_back(info.name);
  return names;
}

std::vector<const StructureInfo*> student_structures() {
  std::vector<const StructureInfo*> out;
  for (const auto& info : structure_registry())
    if (info.student) out.push_back(&info);
  return out;
}

Result<const StructureInfo*> find_structure(const std::string& name) {
  std::string valid;
  for (const auto& info : structure_registry()) {
    if (info.name == name) return &info;
    valid += (valid.empty() ? "" : ", ") + info.name;
  }
  return make_error("unknown structure '" + name + "' (valid: " + valid + ")");
}

Result<StructureChoice> parse_structure(const std::string& name, const std::vector<std::string>& params) {
  auto info = find_structure(name);
  if (!info) return info.error();
  auto set = ParamSet::parse(info.value()->params, params, name);
  if (!set) return set.error();
  return StructureChoice{info.value(), std::move(set.value())};
}

std::unique_ptr<Structure> create_structure(const StructureInfo& info, const Scene& scene, const ParamSet& params,
                                            Kernel kernel) {
  std::unique_ptr<Structure> s = info.create(params);
  s->set_kernel(scene.planar() ? Kernel::Planar : kernel);  // a 2D scene has one hit rule
  return s;
}

Result<std::unique_ptr<Structure>> build_structure(const StructureInfo& info, const Scene& scene,
                                                   const ParamSet& params, Kernel kernel, BuildControl* control,
                                                   BuildRecorder* recorder) {
  std::unique_ptr<Structure> s = create_structure(info, scene, params, kernel);
  auto built = recorder ? s->build_recorded(scene, params, *recorder, control) : s->build(scene, params, control);
  if (!built) return built.error();
  return s;
}

Result<RecordedBuild> build_structure_recorded(const StructureInfo& info, const Scene& scene, const ParamSet& params,
                                               Kernel kernel, size_t budget_bytes, BuildControl* control,
                                               int first_depth_limit) {
  RecordedBuild out;
  auto steps = record_within_budget(
      [&](BuildRecorder& recorder) -> Status {
        auto built = build_structure(info, scene, params, kernel, control, &recorder);
        if (!built) return built.error();
        out.structure = std::move(built.value());
        return {};
      },
      first_depth_limit, budget_bytes);
  if (!steps) return steps.error();
  out.trace = std::move(steps.value().trace);
  out.attempts = std::move(steps.value().attempts);
  return out;
}

Result<std::unique_ptr<Structure>> build_structure(const std::string& name, const Scene& scene,
                                                   const std::vector<std::string>& params, Kernel kernel,
                                                   BuildControl* control, BuildRecorder* recorder) {
  auto choice = parse_structure(name, params);
  if (!choice) return choice.error();
  return build_structure(*choice.value().info, scene, choice.value().params, kernel, control, recorder);
}

}  // namespace accel
