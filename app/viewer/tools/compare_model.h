#pragma once
// GL-free half of the comparison (tools/compare_tool.h is the tool): the same ray through
// every structure and traversal order, each a real build, query and traced query.
// tests/app/test_compare_sweep.cpp drives it without a window.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "built_structure.h"
#include "geometry.h"
#include "scene.h"
#include "trace.h"

namespace viz {

/// One structure and traversal order of the comparison.
struct CompareRow {
  std::string label;                 ///< "bvh (pqueue)"
  std::string structure;
  std::vector<std::string> params;   ///< as built
  bool current = false;              ///< the structure and traversal shown now
  bool ok = false;
  std::string error;
  accel::QueryStats stats;           ///< intersect(ray, &stats)
  size_t steps = 0;                  ///< events recorded by intersect_traced
  accel::Hit hit;
  double build_ms = 0.0;
};

/// One row per built-in structure of the registry (and the current one when it is a
/// student's), and per value of its "traversal" parameter when
/// it has one. The current structure keeps its parameters (the traversal varied); others
/// use their defaults. Each row is a real build + intersect(ray, &stats) + a traced query.
/// Stops early when cancelled; `progress` counts finished rows.
std::vector<CompareRow> compare_structures(std::shared_ptr<const accel::Scene> scene, const accel::Ray& ray,
                                           const StructureRequest& current, const std::atomic<bool>& cancel,
                                           std::atomic<int>* progress = nullptr);

}  // namespace viz
