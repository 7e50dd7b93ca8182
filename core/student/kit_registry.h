#pragma once
// The student structures registered by ACCELVIZ_STUDENT_STRUCTURE (student/accelviz_student.h)
// as registry entries: registry.cpp appends them after the built-in ones.
#include <vector>

#include "accelviz_student.h"
#include "registry.h"

namespace accel {

/// One entry per registered student structure, sorted by name, each tied to the built-in
/// structure of its lecture kind in `builtins`. A name that is empty, not of [a-z0-9_], taken
/// by a built-in or registered twice ends the program with one line naming the file (a
/// build-time mistake of the student's, found at start).
std::vector<StructureInfo> student_structure_infos(const std::vector<StructureInfo>& builtins);

/// "grid", "octree", "kdtree", "bvh", "spheretree": the lecture kind's built-in structure.
const char* kit_kind_name(accelviz::Kind kind);

}  // namespace accel
