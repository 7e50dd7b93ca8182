#include "student/kit_registry.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>

#include "student/kit_structure.h"

namespace accel {
namespace {

std::vector<accelviz::Registration>& registrations() {
  static std::vector<accelviz::Registration> r;
  return r;
}

[[noreturn]] void fail(const accelviz::Registration& r, const std::string& why) {
  std::fprintf(stderr, "%s: student structure '%s': %s\n", r.file.c_str(), r.name.c_str(), why.c_str());
  std::exit(2);
}

bool valid_name(const std::string& name) {
  return !name.empty() && name.size() <= 40 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

}  // namespace

const char* kit_kind_name(accelviz::Kind kind) {
  switch (kind) {
    case accelviz::Kind::grid:
      return "grid";
    case accelviz::Kind::octree:
      return "octree";
    case accelviz::Kind::kdtree:
      return "kdtree";
    case accelviz::Kind::bvh:
      return "bvh";
    case accelviz::Kind::spheretree:
      return "spheretree";
  }
  return "bvh";
}

std::vector<StructureInfo> student_structure_infos(const std::vector<StructureInfo>& builtins) {
  std::vector<accelviz::Registration> regs = registrations();
  std::sort(regs.begin(), regs.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  std::vector<StructureInfo> out;
  for (size_t i = 0; i < regs.size(); ++i) {
    const accelviz::Registration& r = regs[i];
    if (!valid_name(r.name)) fail(r, "a name is 1 to 40 characters of a-z, 0-9 and _");
    if (i > 0 && regs[i - 1].name == r.name) fail(r, "registered twice (also in " + regs[i - 1].file + ")");
    const auto peer = std::find_if(builtins.begin(), builtins.end(),
                                   [&](const StructureInfo& b) { return b.name == kit_kind_name(r.kind); });
    for (const StructureInfo& b : builtins)
      if (b.name == r.name) fail(r, "the name of a built-in structure; choose another");
    if (!r.create || peer == builtins.end()) fail(r, "no constructor or an unknown kind");
    StructureInfo info;
    info.name = r.name;
    info.label = r.name + " (student " + peer->label + ")";
    info.description = "student structure (" + peer->label + ") from " + r.file;
    info.node_noun = peer->node_noun;
    info.traversal = peer->traversal;
    info.construction = peer->construction;
    info.cells = peer->cells;
    info.listing_traversal = "ordered";
    info.listing_builder = "median";
    info.student = true;
    info.builtin_peer = peer->name;
    info.source_file = r.file;
    info.optimized = r.optimized;
    const std::string name = r.name;
    const accelviz::Kind kind = r.kind;
    auto create = r.create;
    info.create = [name, kind, create](const ParamSet&) -> std::unique_ptr<Structure> {
      return std::make_unique<KitStructure>(name, kind, create);
    };
    out.push_back(std::move(info));
  }
  return out;
}

}  // namespace accel

namespace accelviz {

bool register_student_structure(const Registration& r) {
  accel::registrations().push_back(r);
  return true;
}

}  // namespace accelviz
