#pragma once
// A structure the viewer shows: what to build (StructureRequest), and the built structure
// with everything the viewer draws and says about it (BuiltStructure), made on a build
// thread by build_structure_now. Structures are const once built: queries from any thread
// are safe. build_runner.h runs these builds in the background.
#include <memory>
#include <string>
#include <vector>

#include "build_control.h"
#include "pseudo_code.h"
#include "registry.h"
#include "structure.h"
#include "structure_view.h"

namespace viz {

/// What to build: names and parameters exactly as accelviz-cli takes them.
struct StructureRequest {
  std::string name = "bvh";
  std::vector<std::string> params;  ///< key=value
  accel::Kernel kernel = accel::Kernel::Watertight;
  GeometryOptions geometry;
  /// A student's failed build replayed up to the fault (construct-until): its build stops
  /// right after this many build-log calls, where it failed in the check; 0: the whole build.
  /// Only a student's structure counts calls (other structures ignore it).
  size_t build_call_limit = 0;
};

/// A built structure with everything the viewer shows about it, made on the build thread.
struct BuiltStructure {
  std::shared_ptr<const accel::Scene> scene;  ///< kept alive as long as the structure
  std::unique_ptr<accel::Structure> structure;
  const accel::StructureInfo* info = nullptr;  ///< its registry entry (label, node noun, ...)
  StructureRequest request;
  std::string params_text;      ///< every parameter, "key=value ..."
  accel::BuildStats stats;
  StructureGeometry geometry;   ///< instances for drawing
  std::string traversal;        ///< value of its "traversal" parameter ("" when it has none)
  TraversalKind kind = TraversalKind::Unknown;
};
using BuiltPtr = std::shared_ptr<const BuiltStructure>;

/// The structure `request` names, unbuilt (accel::create_structure), set up for its build:
/// a student's gets the request's build-log call limit.
std::unique_ptr<accel::Structure> create_requested(const accel::StructureInfo& info, const accel::Scene& scene,
                                                   const accel::ParamSet& params, const StructureRequest& request);
/// After a failed build of `structure`: true when it stopped at its build-log call limit (a
/// failed build's replay: what it logged up to there is kept), false for a fault of its own.
bool stopped_at_call_limit(const accel::Structure& structure);

/// Validates, builds and lists the nodes of a structure over `scene` (any thread).
/// Errors name the structure or parameter (from the registry). `control` (optional) gets
/// the build's progress and can cancel it (then the error is accel::cancelled_error()). A
/// build stopped at the request's call limit is an error too: there is nothing to query.
accel::Result<BuiltPtr> build_structure_now(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                                            accel::BuildControl* control = nullptr);

}  // namespace viz
