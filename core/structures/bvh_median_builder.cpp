// Median split (lecture, BVH top-down: "sort all objects according to their centre along the
// x-axis, partition the scene along the median, assign half of the objects to each subtree";
// variants: cycle the axis per level, or take the axis of longest extent). No cost function:
// a node stops splitting when it holds at most leaf_size triangles. The recursion and its
// parallel tasks are bvh_top_down.h's.
#include "structures/bvh_median_builder.h"

#include "structures/bvh_top_down.h"

namespace accel {
namespace {

using namespace top_down;

/// Splits a node at the median of its centres along the axis the options choose.
template <class Sink>
class MedianSplitter : public InPlaceSplitter<MedianSplitter<Sink>, Sink> {
 public:
  static constexpr bool kSahLeafRule = false;
  using Scratch = ScratchBase;
  using InPlaceSplitter<MedianSplitter<Sink>, Sink>::InPlaceSplitter;

  Split split(Scratch&, RefRange& w, const Aabb&, int depth, [[maybe_unused]] uint32_t id) {
    int axis = 0;
    if (this->o_.axis == MedianAxis::RoundRobin) axis = depth % 3;
    if (this->o_.axis == MedianAxis::Longest) axis = centroid_bounds_of(this->refs_, w.begin, w.end).longest_axis();
    Split s = object_median_split(this->refs_, w.begin, w.end, axis);
    if constexpr (Sink::kRecords) record_median_split(this->sink_, this->o_, this->refs_, id, axis, w.begin, w.end, s);
    return s;
  }
};

}  // namespace

BuildTree build_median_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                            BuildRecorder* recorder) {
  return build_top_down<MedianSplitter>(scene, options, progress, recorder);
}

}  // namespace accel
