#include "stats_format.h"

#include <cmath>
#include <cstdio>

namespace cli {
namespace {

std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string histogram_text(const accel::BuildStats& b) {
  std::string s;
  for (size_t k = 0; k < b.leaf_size_histogram.size(); ++k) {
    if (!b.leaf_size_histogram[k]) continue;
    const bool last = k + 1 == b.leaf_size_histogram.size();
    if (!s.empty()) s += ' ';
    s += std::to_string(k);
    if (last) s += '+';
    s += ':';
    s += std::to_string(b.leaf_size_histogram[k]);
  }
  return s;
}

}  // namespace

std::string json_quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string stats_text(const std::string& scene, const std::string& structure, const std::string& params,
                       const accel::Scene& s, double load_ms, const accel::BuildStats& b, const QueryReport& q) {
  std::string t;
  auto line = [&](const std::string& k, const std::string& v) { t += k + ": " + v + "\n"; };
  line("scene", scene);
  line("triangles", std::to_string(s.triangle_count()) + " (" + std::to_string(s.degenerate_count()) + " degenerate)");
  line("load_ms", num(load_ms));
  line("structure", structure);
  line("params", params.empty() ? "(defaults)" : params);
  line("build_ms", num(b.build_ms));
  if (std::isfinite(b.refit_ms)) line("refit_ms", num(b.refit_ms));
  line("memory_bytes", std::to_string(b.memory_bytes) + " (" + num(double(b.memory_bytes) / (1024.0 * 1024.0)) + " MB)");
  line("nodes", std::to_string(b.nodes));
  line("leaves", std::to_string(b.leaves));
  line("empty_leaves", std::to_string(b.empty_leaves));
  line("max_depth", std::to_string(b.max_depth));
  line("prim_references", std::to_string(b.prim_references));
  line("refs_per_prim", num(b.refs_per_prim()));
  line("max_leaf_size", std::to_string(b.max_leaf_size));
  line("leaf_size_histogram", histogram_text(b));
  if (std::isfinite(b.sah_cost))
    line("sah_cost", num(b.sah_cost) + " (ct=" + num(b.sah_ct) + ", ci=" + num(b.sah_ci) + ", root area = 1)");
  for (const auto& [k, v] : b.extra) line(k, v);
  if (q.present) {
    line("rays", q.rays + " (" + std::to_string(q.n_rays) + " rays, " + std::to_string(q.hits) + " hits)");
    line("nodes_visited_per_ray", num(q.nodes_per_ray));
    line("nodes_culled_per_ray", num(q.culled_per_ray));
    line("tris_tested_per_ray", num(q.prims_per_ray));
    line("trace_ms", num(q.trace_ms) + " (" + std::to_string(q.threads) + " threads, counters on)");
    line("trace_fast_ms", num(q.trace_fast_ms) + " (" + std::to_string(q.threads) + " threads, counters off)");
  }
  return t;
}

std::string stats_json(const std::string& scene, const std::string& structure, const std::string& params,
                       const accel::Scene& s, double load_ms, const accel::BuildStats& b, const QueryReport& q) {
  std::string j = "{";
  auto field = [&](const std::string& k, const std::string& v) {
    j += (j.size() > 1 ? ", " : "") + json_quote(k) + ": " + v;
  };
  field("scene", json_quote(scene));
  field("triangles", std::to_string(s.triangle_count()));
  field("degenerate_triangles", std::to_string(s.degenerate_count()));
  field("load_ms", num(load_ms));
  field("structure", json_quote(structure));
  field("params", json_quote(params));
  field("build_ms", num(b.build_ms));
  if (std::isfinite(b.refit_ms)) field("refit_ms", num(b.refit_ms));  // only structures that can refit
  field("memory_bytes", std::to_string(b.memory_bytes));
  field("nodes", std::to_string(b.nodes));
  field("leaves", std::to_string(b.leaves));
  field("empty_leaves", std::to_string(b.empty_leaves));
  field("max_depth", std::to_string(b.max_depth));
  field("prim_references", std::to_string(b.prim_references));
  field("refs_per_prim", num(b.refs_per_prim()));
  field("max_leaf_size", std::to_string(b.max_leaf_size));
  std::string hist = "[";
  for (size_t k = 0; k < b.leaf_size_histogram.size(); ++k) hist += (k ? ", " : "") + std::to_string(b.leaf_size_histogram[k]);
  field("leaf_size_histogram", hist + "]");
  field("sah_cost", num(b.sah_cost));
  field("sah_ct", num(b.sah_ct));
  field("sah_ci", num(b.sah_ci));
  std::string extra = "{";
  for (const auto& [k, v] : b.extra) extra += (extra.size() > 1 ? ", " : "") + json_quote(k) + ": " + json_quote(v);
  field("extra", extra + "}");
  if (q.present) {
    field("rays", json_quote(q.rays));
    field("n_rays", std::to_string(q.n_rays));
    field("hits", std::to_string(q.hits));
    field("nodes_visited_per_ray", num(q.nodes_per_ray));
    field("nodes_culled_per_ray", num(q.culled_per_ray));
    field("tris_tested_per_ray", num(q.prims_per_ray));
    field("trace_ms", num(q.trace_ms));
    field("trace_fast_ms", num(q.trace_fast_ms));
  }
  return j + "}\n";
}

}  // namespace cli
