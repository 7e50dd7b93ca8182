#pragma once
// GL-free part of the node display: which depths are drawn (all, leaves, one, a range) and
// the readable first view of a large structure. Owns nothing; NodeDisplay keeps the state.
#include <cstddef>

#include "structure_view.h"

namespace viz {

/// The "show" combo of the Display section.
enum class DepthFilter { All, Leaves, One, Range };

/// What the Display section's depth controls hold.
struct DepthSettings {
  DepthFilter filter = DepthFilter::All;
  int one = 0;                    ///< DepthFilter::One
  int lo = 0, hi = 64;            ///< DepthFilter::Range, inclusive
  bool hide_empty_leaves = true;
  bool empty_cells = false;       ///< grid: empty cells listed (then never hidden)
  bool auto_limited = false;      ///< the range was chosen by fit_depths(), not the user
};

/// The filter the instances on the GPU are made with.
NodeFilter node_filter(const DepthSettings& s);

/// More nodes than this make one unreadable blob (the bunny's 75k BVH nodes): a new
/// structure that large opens with its top levels only.
inline constexpr size_t kCrowdedNodes = 20000;
/// How many nodes that first view shows at most.
inline constexpr size_t kReadableNodes = 1024;

/// The deepest level a new structure opens with (its top levels: at most kReadableNodes
/// nodes), or -1 to show all depths (small, or a grid whose cells are all at depth 0).
int first_view_depth(const StructureGeometry& g);

/// Fits the settings to a newly built structure: clamps the depths to its levels, and
/// when all depths would be shown (or the previous automatic range is untouched) and the
/// structure is crowded, switches to the range 0..first_view_depth().
void fit_depths(DepthSettings& s, const StructureGeometry& g);

}  // namespace viz
