#pragma once
// The list of structures: names as the CLI and viewer take them, their parameters, and a
// factory. Adding a structure means adding one entry in registry.cpp.
#include <memory>
#include <string>
#include <vector>

#include "structure.h"

namespace accel {

/// One registered structure.
struct StructureInfo {
  std::string name;                 ///< "brute", "grid", ...
  std::string description;          ///< one line, in the lecture's terms
  std::vector<ParamSpec> params;    ///< what --param accepts
  std::function<std::unique_ptr<Structure>()> create;
};

/// All structures, in lecture order.
const std::vector<StructureInfo>& structure_registry();
/// Names of all structures, in lecture order.
std::vector<std::string> structure_names();
/// The entry for `name`, or an Error listing the valid names.
Result<const StructureInfo*> find_structure(const std::string& name);

/// Convenience for CLI, tests and viewer: validate `key=value` params, create, set the
/// kernel, build. Errors name the structure or parameter.
Result<std::unique_ptr<Structure>> build_structure(const std::string& name, const Scene& scene,
                                                   const std::vector<std::string>& params,
                                                   Kernel kernel = Kernel::Watertight);

}  // namespace accel
