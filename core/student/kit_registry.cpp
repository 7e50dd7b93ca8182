#include "student/kit_registry.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>

#include "student/kit_registrations.h"
#include "student/kit_structure.h"

namespace accel {
namespace {

std::optional<std::vector<StudentEntry>>& remote_students() {
  static std::optional<std::vector<StudentEntry>> r;
  return r;
}

bool valid_name(const std::string& name) {
  return !name.empty() && name.size() <= 40 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
}

/// This program's own registrations (the viewer's: the student's code is linked in).
std::vector<StudentEntry> local_students() {
  std::vector<StudentEntry> out;
  for (const accelviz::Registration& r : student_registrations()) {
    auto create = r.create;
    out.push_back({{r.name, r.kind, r.file, r.optimized}, [create] { return create(); }});
  }
  return out;
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

Result<StructureInfo> student_structure_info(const StudentEntry& entry, const std::vector<StructureInfo>& builtins) {
  const StudentRegistration& r = entry.registration;
  const std::string who = r.file + ": student structure '" + r.name + "': ";
  if (!valid_name(r.name)) return make_error(who + "a name is 1 to 40 characters of a-z, 0-9 and _");
  const auto peer = std::find_if(builtins.begin(), builtins.end(),
                                 [&](const StructureInfo& b) { return b.name == kit_kind_name(r.kind); });
  for (const StructureInfo& b : builtins)
    if (b.name == r.name) return make_error(who + "the name of a built-in structure; choose another");
  if (!entry.make || peer == builtins.end()) return make_error(who + "no constructor or an unknown kind");
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
  StudentFactory make = entry.make;
  info.create = [name, kind, make](const ParamSet&) -> std::unique_ptr<Structure> {
    return std::make_unique<KitStructure>(name, kind, make);
  };
  return info;
}

std::vector<StructureInfo> student_structure_infos(const std::vector<StructureInfo>& builtins) {
  std::vector<StudentEntry> entries = remote_students() ? *remote_students() : local_students();
  std::sort(entries.begin(), entries.end(),
            [](const auto& a, const auto& b) { return a.registration.name < b.registration.name; });
  std::vector<StructureInfo> out;
  for (size_t i = 0; i < entries.size(); ++i) {
    const StudentRegistration& r = entries[i].registration;
    auto info = student_structure_info(entries[i], builtins);
    if (info && i > 0 && entries[i - 1].registration.name == r.name)
      info = make_error(r.file + ": student structure '" + r.name + "': registered twice (also in " +
                        entries[i - 1].registration.file + ")");
    if (!info) {
      std::fprintf(stderr, "%s\n", info.error().message.c_str());
      std::exit(2);
    }
    out.push_back(std::move(info.value()));
  }
  return out;
}

void set_remote_students(std::vector<StudentEntry> entries) { remote_students() = std::move(entries); }

}  // namespace accel
