#pragma once
// The correctness suites' scenes and rays that are not plain procedural scenes: the
// numerically hard cases (rays through shared edges and vertices, axis-parallel rays in
// split planes, far-from-origin and tiny scenes, slivers, coplanar overlaps, hits exactly at
// tmin / tmax, diagonal rays through grid corners) and the builders' edge cases (one
// triangle, all coplanar, all identical). The tests (tests/test_hard_cases.cpp,
// structure_suite.cpp) and the assignment kit's grader (`accelviz-cli check`) run the same.
#include <string>
#include <vector>

#include "scene.h"

namespace accel {

/// One numerically hard case: its scene and rays (answers: the double-precision reference).
struct HardCase {
  std::string name;
  Scene scene;
  std::vector<Ray> rays;
};

/// Every hard case, in a fixed order (deterministic: the same scenes and rays each call).
std::vector<HardCase> hard_cases();

/// "one_triangle", "coplanar", "identical".
std::vector<std::string> edge_scene_names();
/// Scenes that stress builders: one triangle, 2000 in one plane, 500 identical; an empty
/// scene for other names.
Scene edge_scene(const std::string& name);

}  // namespace accel
