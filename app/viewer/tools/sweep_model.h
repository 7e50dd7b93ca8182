#pragma once
// GL-free half of the parameter sweep ("tune at the end"; tools/sweep_tool.h is the tool):
// the values tried, and one build and timed trace of a fixed ray set per value.
// tests/app/test_compare_sweep.cpp drives it without a window.
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "built_structure.h"
#include "params.h"
#include "ray_gen.h"
#include "result.h"
#include "scene.h"

namespace viz {

/// A sweep: one numeric parameter of a structure over a range, the rest fixed.
struct SweepRequest {
  StructureRequest base;          ///< structure and its other parameters
  std::string param;              ///< an Int or Float parameter of base.name
  double lo = 0.0, hi = 1.0;
  int steps = 10;
  bool log_scale = false;         ///< geometric spacing (for wide ranges)
  accel::PinholeCamera camera;    ///< the fixed ray set: primary rays of this camera
  int width = 128, height = 96;
};

struct SweepPoint {
  double value = 0.0;
  std::string text;               ///< the value as passed to the structure
  bool ok = false;
  std::string error;
  double build_ms = 0.0;
  double trace_ms = 0.0;          ///< the whole ray set, all threads, best of 3
  double nodes_per_ray = 0.0;
  double prims_per_ray = 0.0;
  size_t nodes = 0;
  double sah_cost = 0.0;
};

/// Points filled in by run_sweep() as it goes, read by the UI meanwhile.
struct SweepProgress {
  std::mutex mutex;
  std::vector<SweepPoint> points;
  int total = 0;
};

/// The values a sweep tries: `steps` values from lo to hi (geometric when log_scale and
/// lo > 0), Int parameters rounded with duplicates dropped, all clamped to the spec's range.
std::vector<double> sweep_values(const accel::ParamSpec& spec, double lo, double hi, int steps, bool log_scale);

/// Builds and traces once per value; appends each point to `progress` as it finishes.
/// Error when the parameter does not exist or is not numeric.
accel::Status run_sweep(std::shared_ptr<const accel::Scene> scene, const SweepRequest& request,
                              SweepProgress& progress, const std::atomic<bool>& cancel);

}  // namespace viz
