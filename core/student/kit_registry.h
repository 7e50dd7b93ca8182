#pragma once
// The student structures as registry entries: registry.cpp appends them after the built-in
// ones. Where the student's code is linked in (the viewer, the web page) they come from the
// registrations made by ACCELVIZ_STUDENT_STRUCTURE; in the judge (accelviz-cli, which links
// no student code) from a worker process's list, installed by set_remote_students().
#include <string>
#include <vector>

#include "accelviz_student.h"
#include "registry.h"
#include "result.h"
#include "student/kit_structure.h"

namespace accel {

/// What a student structure says of itself.
struct StudentRegistration {
  std::string name;
  accelviz::Kind kind = accelviz::Kind::bvh;
  std::string file;       ///< the source file that registered it
  bool optimized = true;  ///< that file was compiled with optimisation
};

/// A structure and how to make its student objects.
struct StudentEntry {
  StudentRegistration registration;
  StudentFactory make;
};

/// The registry entry of one student structure tied to the built-in structure of its
/// lecture kind in `builtins`, or an error naming the file: a name that is empty, not of
/// [a-z0-9_] or a built-in's.
Result<StructureInfo> student_structure_info(const StudentEntry& entry, const std::vector<StructureInfo>& builtins);

/// One entry per student structure, sorted by name. In-process registrations that are
/// invalid or registered twice end the program with one line naming the file (a build-time
/// mistake of the student's, found at start).
std::vector<StructureInfo> student_structure_infos(const std::vector<StructureInfo>& builtins);

/// The judge's student structures: a worker's, made by proxies (app/cli/judge/). Call before
/// the registry is first used; they replace this program's own registrations.
void set_remote_students(std::vector<StudentEntry> entries);

/// "grid", "octree", "kdtree", "bvh", "spheretree": the lecture kind's built-in structure.
const char* kit_kind_name(accelviz::Kind kind);

}  // namespace accel
