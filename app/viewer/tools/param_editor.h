#pragma once
// The Structure section's editor: which structure, its parameters and the triangle kernel.
// Owns the edited values, typed (an accel::ParamSet: a slider's double is kept to the last
// bit), and talks to the rest only through StructureRequest (set() in, request() out, whose
// key=value texts read back as exactly the edited values).
#include <string>
#include <vector>

#include "built_structure.h"
#include "registry.h"

namespace viz {

/// Edits one structure's parameters.
class ParamEditor {
 public:
  /// Shows `request`: its structure, its parameters (others at their defaults), its kernel.
  void set(const StructureRequest& request);
  /// What the editor shows, as a request: only parameters set explicitly are passed.
  StructureRequest request() const;
  /// The registry entry being edited.
  const accel::StructureInfo& info() const;
  /// The kernel chosen.
  accel::Kernel kernel() const { return kernel_; }
  /// Chooses the kernel.
  void set_kernel(accel::Kernel kernel) { kernel_ = kernel; }

  /// The structure combo (returns the registry name chosen, or "" when unchanged).
  std::string structure_combo();
  /// The kernel combo; true when the kernel changed.
  bool kernel_combo();
  /// One widget per parameter, each with a reset button; true when a value changed. Over a
  /// 2D scene (`planar`) the parameters not set show the 2D defaults the build will use
  /// (accel::ParamSpec::planar_default), and a line names them.
  bool parameter_widgets(bool planar);

 private:
  int structure_ = 0;     // index into accel::structure_registry()
  accel::ParamSet params_;  // that structure's values; only the explicitly set ones are requested
  accel::Kernel kernel_ = accel::Kernel::Watertight;
};

}  // namespace viz
