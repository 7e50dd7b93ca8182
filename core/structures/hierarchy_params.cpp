#include "structures/hierarchy_params.h"

#include "isa.h"
#include "structures/bvh_builders.h"

namespace accel {
namespace {

/// The builder parameter's choices, from the builders' table.
std::vector<std::pair<std::string, BvhBuilderKind>> builder_choices() {
  std::vector<std::pair<std::string, BvhBuilderKind>> choices;
  for (const BvhBuilderInfo& row : bvh_builder_table()) choices.emplace_back(row.name, row.kind);
  return choices;
}

/// "how the tree is built: A, B, ... or Z", from the builders' help phrases.
std::string builder_help() {
  const std::span<const BvhBuilderInfo> rows = bvh_builder_table();
  std::string help = "how the tree is built: ";
  for (size_t k = 0; k < rows.size(); ++k) {
    if (k > 0) help += k + 1 == rows.size() ? ", or " : ", ";
    help += rows[k].help;
  }
  return help;
}

ParamTable<HierarchyOptions> make_table(bool with_width) {
  using O = HierarchyOptions;
  auto table =
      ParamTable<O>()
          .choice("builder", [](O& o) -> auto& { return o.build.builder; }, builder_choices(), builder_help())
          .choice("axis", [](O& o) -> auto& { return o.build.axis; },
                  std::vector<std::pair<std::string, MedianAxis>>{{"x", MedianAxis::X},
                                                                 {"round_robin", MedianAxis::RoundRobin},
                                                                 {"longest", MedianAxis::Longest}},
                  "median builder only: split axis always x, cycling x,y,z by depth, or the longest extent of the "
                  "centres")
          .integer("bins", [](O& o) -> auto& { return o.build.bins; }, 2, 256,
                   "binned_sah and sbvh: bins per axis (a node of n triangles uses at most 4 + n/4)")
          .number("sbvh_alpha", [](O& o) -> auto& { return o.build.sbvh_alpha; }, 0.0, 1.0,
                  "sbvh only: try a spatial split when the object split's children overlap by more than this "
                  "fraction of the root's area (0: at every node)")
          .number("sbvh_budget", [](O& o) -> auto& { return o.build.sbvh_budget; }, 1.0, 4.0,
                  "sbvh only: at most this many triangle references per triangle (1: no spatial splits)")
          .integer("leaf_size", [](O& o) -> auto& { return o.build.leaf_size; }, 1, 64,
                   "maximum number of triangles in a leaf")
          .number("ct", [](O& o) -> auto& { return o.build.ct; }, 0.001, 1000,
                  "SAH cost of one traversal step (inner node)")
          .number("ci", [](O& o) -> auto& { return o.build.ci; }, 0.001, 1000, "SAH cost of one ray/triangle test")
          .choice("traversal", &O::traversal,
                  std::vector<std::pair<std::string, TraversalOrder>>{{"dfs", TraversalOrder::Dfs},
                                                                     {"ordered", TraversalOrder::Ordered},
                                                                     {"pqueue", TraversalOrder::PriorityQueue}},
                  "node order: depth-first in tree order, nearer child first with skipping, or a priority queue by "
                  "entry distance (lecture)");
  if (with_width)
    table.choice("width", &O::width,
                 std::vector<std::pair<std::string, int>>{{"auto", O::kAutoWidth}, {"2", 2}, {"4", 4}, {"8", 8}},
                 "children per node: 2 is the lecture's binary tree, 4 collapses it into nodes whose four boxes are "
                 "tested at once with SSE2, 8 into nodes of eight boxes tested with AVX-512 or AVX2 when the CPU has "
                 "them (SSE2 in two halves otherwise); auto is 8 with AVX2, else 4");
  return table;
}

}  // namespace

const ParamTable<HierarchyOptions>& hierarchy_param_table(bool with_width) {
  static const ParamTable<HierarchyOptions> binary = make_table(false), bvh = make_table(true);
  return with_width ? bvh : binary;
}

HierarchyOptions hierarchy_options(const ParamSet& params) {
  return hierarchy_param_table(params.has("width")).apply(params);
}

int HierarchyOptions::resolved_width() const {
  if (width != kAutoWidth) return width;
  // Without AVX2 the 8-wide node is two SSE2 halves: the 4-wide tree runs fewer instructions.
  return active_isa() >= Isa::Avx2 ? 8 : 4;
}

}  // namespace accel
