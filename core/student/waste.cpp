#include "student/waste.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "student/kit_structure.h"

namespace accel {
namespace {

std::string fmt(double v, const char* f = "%.3g") {
  char b[48];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

bool near_value(double a, double b, double extent) { return std::fabs(a - b) <= 1e-5 * extent + 1e-30; }

}  // namespace

std::string set_waste_limit(WasteLimits& limits, const std::string& name_value) {
  const size_t eq = name_value.find('=');
  const std::string name = name_value.substr(0, eq);
  double* target = name == "uncrossed"    ? &limits.uncrossed
                   : name == "triangles"  ? &limits.triangles
                   : name == "leaf_size"  ? &limits.leaf_size
                   : name == "references" ? &limits.references
                                          : nullptr;
  if (!target || eq == std::string::npos)
    return "--limit " + name_value + ": expected NAME=VALUE with NAME one of uncrossed, triangles, leaf_size, references";
  char* end = nullptr;
  const std::string value = name_value.substr(eq + 1);
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !(v >= 0.0) || !std::isfinite(v))
    return "--limit " + name_value + ": the value must be a number >= 0 (0: no limit)";
  *target = v;
  return "";
}

void WasteTally::add(const WasteTally& o) {
  rays += o.rays, visits += o.visits, uncrossed += o.uncrossed;
  kd_inner += o.kd_inner, kd_far_only += o.kd_far_only, kd_needs_far_only += o.kd_needs_far_only;
  tris += o.tris, peer_tris += o.peer_tris;
  leaves += o.leaves, leaf_refs += o.leaf_refs, peer_leaves += o.peer_leaves, peer_leaf_refs += o.peer_leaf_refs;
  refs += o.refs, peer_refs += o.peer_refs, prims += o.prims;
  if (!o.peer_setup.empty()) peer_setup = o.peer_setup;
}

std::vector<std::pair<std::string, std::string>> peer_setup_like(const KitTree& tree, accelviz::Kind kind,
                                                                 const Scene& scene) {
  using K = accelviz::Kind;
  std::vector<std::pair<std::string, std::string>> out;
  if (kind == K::grid) {
    if (tree.grid)
      out.push_back({"res", std::to_string(tree.res[0]) + "," + std::to_string(tree.res[1]) + "," +
                                std::to_string(tree.res[2])});
    return out;
  }
  size_t splits = 0, middle = 0, median = 0, longest = 0, few_max = 0;
  size_t pairs = 0, halved = 0;  // object partitions: two children whose counts differ by at most one
  int depth = 0;
  for (const KitNode& k : tree.nodes) {
    depth = std::max(depth, k.depth);
    if (k.children.size() == 2) {
      ++pairs;
      const uint32_t a = tree.nodes[k.children[0]].prim_count, b = tree.nodes[k.children[1]].prim_count;
      halved += (a > b ? a - b : b - a) <= 1 && a + b == k.prim_count;
    }
    if ((k.leaf || k.children.empty()) && k.leaf_why == accelviz::LeafWhy::FewTriangles)
      few_max = std::max(few_max, k.prims.size());
    if (k.split_axis < 0) continue;
    ++splits;
    const int a = k.split_axis;
    const double extent = double(k.box.max[a] - k.box.min[a]);
    if (near_value(k.split_pos, 0.5 * (double(k.box.min[a]) + double(k.box.max[a])), extent)) ++middle;
    if (a == k.box.longest_axis()) ++longest;
    if (!k.made_over.empty()) {
      std::vector<float> c;
      for (uint32_t p : k.made_over)
        if (p < scene.triangle_count()) c.push_back(scene.centroid(p)[a]);
      if (!c.empty()) {
        std::nth_element(c.begin(), c.begin() + long(c.size() / 2), c.end());
        if (near_value(k.split_pos, c[c.size() / 2], extent)) ++median;
      }
    }
  }
  const bool mostly_middle = splits && 10 * middle >= 7 * splits;
  const bool mostly_median = splits && 10 * median >= 7 * splits;
  const bool mostly_longest = splits && 10 * longest >= 7 * splits;
  if (kind == K::kdtree) {
    out.push_back({"split", mostly_middle ? "middle" : mostly_median ? "median" : "sah"});
    if (mostly_middle || mostly_median) out.push_back({"axis", mostly_longest ? "longest" : "round_robin"});
    if (few_max) out.push_back({"leaf_size", std::to_string(std::clamp<size_t>(few_max, 1, 1024))});
  } else if (kind == K::octree) {
    if (few_max) out.push_back({"max_prims", std::to_string(std::clamp<size_t>(few_max, 1, 4096))});
    out.push_back({"max_depth", std::to_string(std::clamp(depth, 0, 40))});
  } else {
    // A BVH's median split halves its triangles: seen in the children's counts even where the
    // triangle lists are not kept (the viewer) or no split() was logged.
    const bool halves = pairs && 10 * halved >= 9 * pairs;
    const bool median_bvh = mostly_median || halves;
    out.push_back({"builder", median_bvh ? "median" : "binned_sah"});
    if (median_bvh && splits) out.push_back({"axis", mostly_longest ? "longest" : "round_robin"});
    if (few_max) out.push_back({"leaf_size", std::to_string(std::clamp<size_t>(few_max, 1, 64))});
    if (kind == K::bvh) out.push_back({"width", "2"});
  }
  return out;
}

WasteReport waste_report(const WasteTally& t, accelviz::Kind kind, const std::string& peer, const WasteLimits& limits,
                         bool strict) {
  WasteReport r;
  if (t.rays == 0) return r;
  r.measured = true;
  r.peer = peer + (t.peer_setup.empty() ? "" : " " + t.peer_setup);
  auto add = [&](const char* name, double value, double limit, double say_above, std::string sentence) {
    if (!(value > say_above)) return;
    WasteFinding f{name, value, limit, std::move(sentence), strict && limit > 0 && value > limit};
    r.over_limit |= f.over;
    r.findings.push_back(std::move(f));
  };
  // Nodes visited where the ray is not: case (c) missing, or a walk that ignores its interval.
  if (t.visits) {
    const double share = double(t.uncrossed) / double(t.visits);
    std::string s = fmt(100.0 * share, "%.0f") + "% of the visited " + (kind == accelviz::Kind::grid ? "cells" : "nodes") +
                    " lie where the ray is not (visited over an interval in which the ray does not cross them)";
    if (kind == accelviz::Kind::kdtree && t.kd_needs_far_only > 0 && t.kd_far_only == 0)
      s = "case (c) was never taken: " + s +
          " -- kd-tree traversal, case (c): when t_split < t_min the ray is past the plane, visit the far child only";
    add("uncrossed", share, limits.uncrossed, 0.01, s);
  }
  if (t.peer_tris > 0) {
    const double ratio = t.tris / t.peer_tris;
    add("triangles", ratio, limits.triangles, 2.0,
        fmt(t.tris / double(t.rays)) + " triangles tested per ray against " + fmt(t.peer_tris / double(t.rays)) +
            " for the built-in " + r.peer + ": " + fmt(ratio, "%.2f") +
            "x -- the structure exists to test few triangles: small leaves, tight bounds, a front-to-back walk that "
            "stops early");
  }
  if (t.leaves > 0 && t.peer_leaves > 0 && t.peer_leaf_refs > 0) {
    const double mine = t.leaf_refs / t.leaves, theirs = t.peer_leaf_refs / t.peer_leaves;
    add("leaf_size", mine / theirs, limits.leaf_size, 2.0,
        "leaves hold " + fmt(mine) + " triangles on average against the built-in's " + fmt(theirs) + ": " +
            fmt(mine / theirs, "%.2f") + "x -- construction: split until a few triangles remain or a leaf is cheaper "
                                         "(the SAH's C(B) against the leaf's cost)");
  }
  if (t.prims > 0 && t.peer_refs > 0) {
    const double mine = t.refs / t.prims, theirs = t.peer_refs / t.prims;
    add("references", mine / theirs, limits.references, 1.5,
        fmt(mine) + " references per triangle against the built-in's " + fmt(theirs) + ": " +
            fmt(mine / theirs, "%.2f") + "x -- construction: a triangle goes only into the children (cells) it overlaps");
  }
  return r;
}

}  // namespace accel
