#include "structures/bvh.h"

#include "structures/bvh_builders.h"

namespace accel {

void add_hierarchy_option_lines(const BvhBuildOptions& options, TraversalOrder order, BuildStats* s) {
  s->extra.push_back({"builder", builder_name(options.builder)});
  static constexpr const char* kOrder[] = {"dfs", "ordered", "pqueue"};
  s->extra.push_back({"traversal", kOrder[int(order)]});
}

std::unique_ptr<Structure> make_bvh(const ParamSet& params) {
  // The layout is a class, not a branch in every query: width is read once, here.
  switch (hierarchy_options(params).resolved_width()) {
    case 2: return std::make_unique<BinaryBvh>();
    case 8: return std::make_unique<WideBvh8>();
    default: return std::make_unique<WideBvh>();
  }
}

BuildStats BinaryBvh::compute_stats() const {
  BuildStats s = Hierarchy::compute_stats();
  s.extra.push_back({"width", "2"});
  return s;
}

}  // namespace accel
