#pragma once
// Text and JSON renderings of BuildStats for `accelviz-cli stats`.
#include <string>

#include "structure.h"

namespace cli {

/// Per-ray query counters of a traced ray set (stats --rays).
struct QueryReport {
  bool present = false;
  std::string rays;
  size_t n_rays = 0;
  size_t hits = 0;
  double nodes_per_ray = 0.0, culled_per_ray = 0.0, prims_per_ray = 0.0;
  double trace_ms = 0.0;       ///< the pass with the counters on
  double trace_fast_ms = 0.0;  ///< the same rays without counters (the fast path)
  int threads = 0;
};

/// Human-readable, one "key: value" per line. `load_ms` is the scene's load time.
std::string stats_text(const std::string& scene, const std::string& structure, const std::string& params,
                       const accel::Scene& s, double load_ms, const accel::BuildStats& b, const QueryReport& q);
/// One JSON object with the same fields.
std::string stats_json(const std::string& scene, const std::string& structure, const std::string& params,
                       const accel::Scene& s, double load_ms, const accel::BuildStats& b, const QueryReport& q);
/// JSON string literal with escapes.
std::string json_quote(const std::string& s);

}  // namespace cli
