#include "tools/depth_filter.h"

#include <algorithm>

namespace viz {

NodeFilter node_filter(const DepthSettings& s) {
  NodeFilter f;
  f.hide_empty = s.hide_empty_leaves && !s.empty_cells;
  switch (s.filter) {
    case DepthFilter::All: break;
    case DepthFilter::Leaves: f.leaves_only = true; break;
    case DepthFilter::One: f.depth_min = f.depth_max = s.one; break;
    case DepthFilter::Range:
      f.depth_min = s.lo;
      f.depth_max = s.hi;
      break;
  }
  return f;
}

int first_view_depth(const StructureGeometry& g) {
  if (g.uniform_depth || g.nodes <= kCrowdedNodes) return -1;
  const int d = depth_for_budget(g, kReadableNodes);
  // Over budget at the root already (never for a tree), or everything fits: all depths.
  return d >= 0 && d < g.max_depth ? d : -1;
}

void fit_depths(DepthSettings& s, const StructureGeometry& g) {
  // An automatic range the user left alone belongs to the old structure: choose anew.
  if (s.auto_limited && s.filter == DepthFilter::Range) s.filter = DepthFilter::All;
  s.auto_limited = false;
  s.lo = std::min(s.lo, g.max_depth);
  s.hi = std::clamp(s.hi, s.lo, std::max(g.max_depth, s.lo));
  if (s.filter == DepthFilter::All) s.hi = g.max_depth;
  s.one = std::min(s.one, g.max_depth);
  if (s.filter != DepthFilter::All) return;
  const int d = first_view_depth(g);
  if (d < 0) return;
  s.filter = DepthFilter::Range;
  s.lo = 0;
  s.hi = d;
  s.auto_limited = true;
}

}  // namespace viz
