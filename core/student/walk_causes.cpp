// The causes the kit names for wrong answers (walk_audit.h): one table, the words of the
// report and of docs/student.md's table (tests/test_walk_audit.cpp compares the two).
#include <iterator>
#include <string>

#include "student/walk_audit.h"

namespace accel {
namespace {

// The causes, in the order docs/student.md's table lists them (a test compares the two).
constexpr CauseInfo kCauses[] = {
    {"kd_plane_behind_origin",
     "the split plane lies behind the ray's origin (t_split < 0): case (c) sent the ray to the far child, but it "
     "never crosses the plane and stays in the near one",
     "kd-tree traversal: the slide's 'if t_split < t_min: far only' needs 'near only when t_split <= 0' first "
     "(pbrt: near only when tSplit > tMax or tSplit <= 0)"},
    {"kd_parallel_ray",
     "a ray parallel to the split plane (a direction component of +-0) has t_split = +-inf or NaN and was sent to a "
     "child it never enters",
     "kd-tree traversal: t_split = (split - o) / d is -inf for d = -0; a ray that runs parallel to the plane stays "
     "in the child holding its origin (near only)"},
    {"kd_wrong_t_split", "t_split is not the distance along the ray to the split plane",
     "kd-tree traversal: t_split = (split - o[axis]) / d[axis]"},
    {"kd_near_far_swapped", "near and far children swapped: near is the side the ray is on before t_split",
     "kd-tree traversal: near = the child containing the ray's origin (for a ray starting before the plane)"},
    {"kd_wrong_case",
     "the walk did not take the children of the case its own t_split gives: (b) near only when t_split > t_max, "
     "(c) far only when t_split < t_min, (a) both",
     "kd-tree traversal: the three cases"},
    {"kd_case_drops_child",
     "case (b) or (c) taken although the ray crosses the split plane within [t_min, t_max]: a child it crosses was "
     "left out",
     "kd-tree traversal: the three cases compare t_split with t_min and t_max"},
    {"kd_false_early_exit",
     "the early exit 'if t_hit < t_split: return' was taken with the hit beyond the far child's start",
     "kd-tree traversal: the far child may hold a nearer hit unless t_hit < t_split"},
    {"kd_hit_beyond_t_split",
     "a near-child hit beyond t_split was returned (check t_hit <= t_split before stopping)",
     "kd-tree traversal: 'if t_hit < t_split: return t_hit'"},
    {"slab_nan",
     "the slab test made NaN for a direction component of +-0 with the origin on a box plane (0 * inf), and the box "
     "was skipped as missed",
     "ray/box slab test: compare (lo - o) * (1/d) only where d != 0, or order the min/max so NaN drops out "
     "(Williams et al. 2005)"},
    {"false_cull_missed", "a node the ray crosses was skipped as missed, and it held a nearer hit",
     "traversal: skip a node only when the ray misses its bounding volume within [t_min, t_hit]"},
    {"false_cull_beyond",
     "a node skipped as beyond the closest hit is entered before it, and it held a nearer hit",
     "traversal: skip a node only when it is entered after the closest hit so far (t_enter > t_hit)"},
    {"octree_order", "the octree's children were not visited in the order the ray enters them",
     "octree traversal: visit the children front to back (the entry distances, or the octant order i ^ mask)"},
    {"grid_dda_tie",
     "the 3D-DDA left the ray's path (at a tie of tMax, e.g. tMaxX == tMaxY): a cell the ray crosses was never "
     "entered",
     "grid traversal (3D-DDA): step the axis whose tMax is smallest, one axis at a time"},
    {"grid_cell_skipped", "a cell the ray crosses, holding a nearer hit, was never entered",
     "grid traversal: walk every cell the ray passes through, in order"},
    {"grid_hit_outside_cell",
     "a hit outside the current cell was accepted (it must lie inside the cell to stop the walk)",
     "grid traversal: stop only when the closest hit lies inside the current cell"},
    {"straddle_lost", "a triangle that straddles a split is missing from a child it overlaps",
     "construction: a triangle overlapping both sides of a split (or several octants) goes into each of them"},
    {"grid_insert_lost", "a triangle missing from a cell it overlaps (the insertion lost it)",
     "grid construction: insert each triangle into every cell its box overlaps"},
    {"stopped_first_leaf",
     "stopped at the first leaf with a hit (a farther bounding volume can hold a nearer triangle)",
     "BVH traversal: the closest ray-BV intersection and the closest ray-primitive intersection can occur in "
     "different BVs"},
    {"nearer_hit_dropped", "a nearer triangle was tested and hit, but the answer kept a farther one",
     "traversal: keep the closest hit (t_hit = min)"},
    {"never_reached", "the leaf holding the nearer hit was never visited nor skipped: the walk lost it",
     "traversal: every node the ray crosses is visited or culled for a reason"},
    {"not_a_hit", "the returned triangle is not hit by the ray", "the ray/triangle test (docs/hits.md)"},
    {"wrong_t", "the returned t is not where the ray hits the returned triangle", "the ray/triangle test"},
    {"outside_interval", "the returned hit lies outside [tmin, tmax]", "docs/hits.md: tmin <= t <= tmax"},
    {"unreferenced", "the triangle hit first is in no leaf or cell: the build left it out",
     "construction: every triangle goes into at least one leaf (or every cell it overlaps)"},
    {"nothing_walked", "intersect() logged no visit and answered a miss (still the skeleton's traversal?)",
     "traversal: log visit() for every node (enter_cell() for every cell) the walk enters"},
    {"nothing_built", "the build logged no node or cell: there is nothing to traverse (still the skeleton?)",
     "construction: log every node and leaf (student/README.md)"},
    {"fault", "the structure threw, or the kit stopped it, on this ray (see the faults)", "docs/student.md"},
    {"unexplained", "no logged claim is false and the answer's cause was not found: open the replay",
     "docs/student.md"},
};

}  // namespace

std::span<const CauseInfo> cause_table() { return kCauses; }

const CauseInfo& cause_info(const std::string& id) {
  for (const CauseInfo& c : kCauses)
    if (id == c.id) return c;
  return kCauses[std::size(kCauses) - 1];
}

}  // namespace accel
