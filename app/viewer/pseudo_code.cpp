#include "pseudo_code.h"

#include <cmath>
#include <utility>

#include "params.h"
#include "structures/bvh_builders.h"
#include "structures/hierarchy_params.h"

namespace viz {
namespace {

using accel::CullReason;
using accel::TraceEvent;
using accel::TraceEventKind;

/// Builds a listing from (anchor, line) pairs.
PseudoCode listing(std::string title, std::vector<std::pair<const char*, const char*>> rows) {
  PseudoCode code;
  code.title = std::move(title);
  for (const auto& [anchor, line] : rows) {
    code.anchors.emplace_back(anchor);
    code.lines.emplace_back(line);
  }
  return code;
}

// The lecture's listings (acceleration-structures-lecture.txt), kept verbatim where the
// lecture gives code; lines marked "(added)" state what the lecture says in prose, lines
// marked "(fix)" what the slide leaves out and a correct traversal needs (each is a cause
// `accelviz-cli check` names: core/student/walk_audit.cpp).
const PseudoCode& brute_code() {
  static const PseudoCode code = listing("Brute force: test every triangle", {
      {"visit", "closest_hit = inf"},
      {"", "for each triangle in the scene:"},
      {"test", "    if ray hits it closer than closest_hit:"},
      {"closest", "        closest_hit = that hit"},
      {"done", "return closest_hit"},
  });
  return code;
}

const PseudoCode& grid_code() {
  static const PseudoCode code = listing("Uniform grid: 3D-DDA (Amanatides & Woo, lecture)", {
      {"", "// for each cell intersected by the ray:   (added)"},
      {"enter_first", "X,Y,Z = cell where the ray enters the grid"},
      {"", "loop:"},
      {"test", "    for each object in ObjectList[X][Y][Z]: is it hit?"},
      {"closest", "        yes, and closer: closest hit = it"},
      {"return_hit", "    if closest hit lies in this cell: return it"},
      {"", "    list= NIL;"},
      {"", "    do {"},
      {"", "        if(tMaxX < tMaxY) {"},
      {"", "            if(tMaxX < tMaxZ) {"},
      {"step_x", "                X= X + stepX;"},
      {"", "                if(X == justOutX)"},
      {"outside", "                    return(NIL); /* outside grid */"},
      {"", "                tMaxX= tMaxX + tDeltaX;"},
      {"", "            } else {"},
      {"step_z", "                Z= Z + stepZ;"},
      {"", "                if(Z == justOutZ)"},
      {"", "                    return(NIL);"},
      {"", "                tMaxZ= tMaxZ + tDeltaZ;"},
      {"", "            }"},
      {"", "        } else {"},
      {"", "            if(tMaxY < tMaxZ) {"},
      {"step_y", "                Y= Y + stepY;"},
      {"", "                if(Y == justOutY)"},
      {"", "                    return(NIL);"},
      {"", "                tMaxY= tMaxY + tDeltaY;"},
      {"", "            } else {"},
      {"", "                Z= Z + stepZ;"},
      {"", "                if(Z == justOutZ)"},
      {"", "                    return(NIL);"},
      {"", "                tMaxZ= tMaxZ + tDeltaZ;"},
      {"", "            }"},
      {"", "        }"},
      {"list", "        list= ObjectList[X][Y][Z];"},
      {"", "    } while(list == NIL);"},
  });
  return code;
}

// The lecture's 2D figure of the same loop: the blackboard's grid steps in X and Y only.
const PseudoCode& grid_2d_code() {
  static const PseudoCode code = listing("Uniform grid: 2D-DDA (Amanatides & Woo, lecture)", {
      {"", "// for each cell intersected by the ray:   (added)"},
      {"enter_first", "X,Y = cell where the ray enters the grid"},
      {"", "loop:"},
      {"test", "    for each object in ObjectList[X][Y]: is it hit?"},
      {"closest", "        yes, and closer: closest hit = it"},
      {"return_hit", "    if closest hit lies in this cell: return it"},
      {"", "    list= NIL;"},
      {"", "    do {"},
      {"", "        if(tMaxX < tMaxY) {"},
      {"step_x", "            X= X + stepX;"},
      {"", "            if(X == justOutX)"},
      {"outside", "                return(NIL); /* outside grid */"},
      {"", "            tMaxX= tMaxX + tDeltaX;"},
      {"", "        } else {"},
      {"step_y", "            Y= Y + stepY;"},
      {"", "            if(Y == justOutY)"},
      {"", "                return(NIL);"},
      {"", "            tMaxY= tMaxY + tDeltaY;"},
      {"", "        }"},
      {"list", "        list= ObjectList[X][Y];"},
      {"", "    } while(list == NIL);"},
  });
  return code;
}

const PseudoCode& octree_code() {
  // Indented by two (the lecture's four would not fit a side panel); one long line wrapped.
  static const PseudoCode code = listing("Octree: OctreeNode::Trace (lecture)", {
      {"", "void Octree::Trace(ray, collision) {"},
      {"root", "  root_node.Trace(ray, collision)"},
      {"", "}"},
      {"enter", "void OctreeNode::Trace(ray, collision) {"},
      {"miss_bounds", "  if ray does not intersect node bounds:"},
      {"", "    return"},
      {"beyond", "  if a collision has already been detected and it's"},
      {"", "     closer than the ray entry point into this node:"},
      {"", "    return"},
      {"visit_leaf", "  if node is a leaf:"},
      {"", "    for each polygon in node:"},
      {"test", "      if ray intersects polygon:"},
      {"", "        if intersection is closer to ray origin"},
      {"", "           than collision:"},
      {"closest", "          update collision with current intersection"},
      {"visit_inner", "  else:"},
      {"", "    for each child_node:"},
      {"", "    // (fix) in the order the ray enters them, front to back:"},
      {"", "    // else the entry test above rarely skips a child"},
      {"push", "      child_node.Trace(ray, collision)"},
      {"", "}"},
  });
  return code;
}

const PseudoCode& kd_code() {
  static const PseudoCode code = listing("kd-tree: traverse (lecture)", {
      {"root", "// first: ray vs. root box -> t_min, t_max (added)"},
      {"", "traverse( Ray r, Node n, float t_min, float t_max ):"},
      {"visit_leaf", "if n is leaf:"},
      {"test", "    intersect r with each primitive in object list,"},
      {"", "    discard those farther away than t_max"},
      {"closest", "    return object with closest intersection (if any)"},
      {"visit_inner", "t_split = signed distance along r to n's split plane"},
      {"", "near = child of n containing origin of r"},
      {"", "far  = the \"other\" child of n"},
      {"", "if t_split > t_max:"},
      {"", "  // (fix) or t_split <= 0: the plane is behind the origin,"},
      {"", "  // the ray never crosses it (pbrt: tSplit > tMax || tSplit <= 0);"},
      {"", "  // a ray parallel to it (d = -0) has t_split = -inf: near too"},
      {"case_b", "    return traverse( r, near, t_min, t_max )   // (b)"},
      {"", "else if t_split < t_min:"},
      {"case_c", "    return traverse( r, far, t_min, t_max )    // (c)"},
      {"", "else:                                         // (a)"},
      {"case_a", "    t_hit = traverse( r, near, t_min, t_split )"},
      {"", "    if t_hit < t_split:"},
      {"early_exit", "        return t_hit                 // early exit"},
      {"far", "    return traverse( r, far, t_split, t_max )"},
      {"done", "// result: the closest hit, or none (added)"},
  });
  return code;
}

const PseudoCode& dfs_code() {
  static const PseudoCode code = listing("BVH / sphere tree: depth-first (stack)", {
      {"init", "stack <- { root };  closest_hit = inf"},
      {"", "while stack not empty:"},
      {"pop", "    node <- pop(stack)"},
      {"cull", "    if ray misses node's volume before closest_hit:"},
      {"", "        continue               // skip this subtree"},
      {"visit_leaf", "    if node is leaf:"},
      {"test", "        intersect ray with all polygons in node"},
      {"closest", "        update closest_hit, if any polygon is closer"},
      {"visit_inner", "    else:                  // inner node: tree order"},
      {"push", "        push(right child); push(left child)"},
      {"done", "return closest_hit"},
  });
  return code;
}

const PseudoCode& ordered_code() {
  static const PseudoCode code = listing("BVH / sphere tree: ordered depth-first (stack)", {
      {"cull_root", "if ray misses the root's volume: return no hit"},
      {"init", "stack <- { root };  closest_hit = inf"},
      {"", "while stack not empty:"},
      {"pop", "    node <- pop(stack)"},
      {"beyond", "    if dist(node) > closest_hit:"},
      {"", "        continue               // skip this subtree"},
      {"visit_leaf", "    if node is leaf:"},
      {"test", "        intersect ray with all polygons in node"},
      {"closest", "        update closest_hit, if any polygon is closer"},
      {"visit_inner", "    else:                  // inner node"},
      {"cull_child", "        skip each child whose volume the ray misses"},
      {"push", "        push(farther child); push(nearer child)"},
      {"done", "return closest_hit"},
  });
  return code;
}

const PseudoCode& pqueue_code() {
  static const PseudoCode code = listing("BVH / sphere tree: priority queue (lecture)", {
      {"init", "Pqueue q <- init with root"},
      {"", "closest_hit = inf"},
      {"", "while q not empty:"},
      {"pop", "    node <- extract front from q   // = nearest BV"},
      {"beyond", "    if dist(node) <= closest_hit:  // else: skip"},
      {"visit_leaf", "        if node is leaf:"},
      {"test", "            intersect ray with all polygons in node"},
      {"closest", "            update closest_hit, if any is closer"},
      {"visit_inner", "        else                       // inner node"},
      {"", "            forall children of node:"},
      {"cull_child", "                if ray intersects child:"},
      {"push", "                    insert child in q with its distance"},
      {"done", "return closest_hit   (added)"},
  });
  return code;
}

const PseudoCode& unknown_code() {
  static const PseudoCode code = listing("(no pseudo code for this structure)", {});
  return code;
}

/// Whether the node of a Visit is a leaf: from the structure when possible, else from the
/// next event (a leaf's visit is followed by its triangle tests).
bool visit_is_leaf(std::span<const TraceEvent> events, size_t step, const NodeLookup& lookup) {
  if (lookup) {
    const accel::NodeView v = lookup(events[step].node);
    if (v.id != accel::kNoNode) return v.leaf;
  }
  return step + 1 < events.size() && events[step + 1].kind == TraceEventKind::TestPrim;
}

/// The previous event of `kind` before `step`, or nullptr.
const TraceEvent* previous(std::span<const TraceEvent> events, size_t step, TraceEventKind kind) {
  for (size_t i = step; i-- > 0;)
    if (events[i].kind == kind) return &events[i];
  return nullptr;
}

bool was_pushed(std::span<const TraceEvent> events, size_t step, accel::NodeId node) {
  for (size_t i = step; i-- > 0;)
    if (events[i].kind == TraceEventKind::Push && events[i].node == node) return true;
  return false;
}

bool follows_pop_of(std::span<const TraceEvent> events, size_t step, accel::NodeId node) {
  return step > 0 && events[step - 1].kind == TraceEventKind::Pop && events[step - 1].node == node;
}

/// The grid axis stepped from the previous cell into this one (-1 for the first cell or
/// when it cannot be told).
int stepped_axis(std::span<const TraceEvent> events, size_t step, const NodeLookup& lookup) {
  const TraceEvent* prev = previous(events, step, TraceEventKind::EnterCell);
  if (!prev || !lookup) return -1;
  const accel::NodeView a = lookup(prev->node), b = lookup(events[step].node);
  for (int axis = 0; axis < 3; ++axis)
    if (a.box.min[axis] != b.box.min[axis]) return axis;
  return -1;
}

std::string anchor_of(TraversalKind kind, std::span<const TraceEvent> events, size_t step, const NodeLookup& lookup) {
  const TraceEvent& e = events[step];
  // Shared by every listing.
  if (e.kind == TraceEventKind::TestPrim) return "test";
  if (e.kind == TraceEventKind::NewClosest) return "closest";
  switch (kind) {
    case TraversalKind::Brute:
      if (e.kind == TraceEventKind::Visit) return "visit";
      if (e.kind == TraceEventKind::Done) return "done";
      return "";
    case TraversalKind::Grid:
    case TraversalKind::Grid2d:
      if (e.kind == TraceEventKind::EnterCell) {
        switch (stepped_axis(events, step, lookup)) {
          case 0: return "step_x";
          case 1: return "step_y";
          case 2: return "step_z";
          default: return previous(events, step, TraceEventKind::EnterCell) ? "list" : "enter_first";
        }
      }
      if (e.kind == TraceEventKind::Done) return e.hit ? "return_hit" : "outside";
      return "";
    case TraversalKind::Octree:
      switch (e.kind) {
        case TraceEventKind::Push: return e.depth == 0 ? "root" : "push";
        case TraceEventKind::Pop: return "enter";
        case TraceEventKind::Cull: return e.reason == CullReason::BeyondClosestHit ? "beyond" : "miss_bounds";
        case TraceEventKind::Visit: return visit_is_leaf(events, step, lookup) ? "visit_leaf" : "visit_inner";
        case TraceEventKind::Done: return "root";
        default: return "";
      }
    case TraversalKind::KdTree:
      switch (e.kind) {
        case TraceEventKind::Visit: return visit_is_leaf(events, step, lookup) ? "visit_leaf" : "visit_inner";
        case TraceEventKind::Push: return "case_a";
        case TraceEventKind::Pop: return "far";
        case TraceEventKind::Cull: {
          if (e.reason == CullReason::BeyondClosestHit) return "early_exit";
          const TraceEvent* visit = previous(events, step, TraceEventKind::Visit);
          if (!visit) return "root";  // the ray misses the root box
          // The traversal records t_split as the skipped child's t0: beyond the node's
          // interval is case (b), before it case (c).
          return e.t0 > visit->t1 ? "case_b" : "case_c";
        }
        case TraceEventKind::Done: return "done";
        default: return "";
      }
    case TraversalKind::HierarchyDfs:
      switch (e.kind) {
        case TraceEventKind::Push: return step == 0 ? "init" : "push";
        case TraceEventKind::Pop: return "pop";
        case TraceEventKind::Cull: return "cull";
        case TraceEventKind::Visit: return visit_is_leaf(events, step, lookup) ? "visit_leaf" : "visit_inner";
        case TraceEventKind::Done: return "done";
        default: return "";
      }
    case TraversalKind::HierarchyOrdered:
    case TraversalKind::HierarchyPqueue: {
      const bool pq = kind == TraversalKind::HierarchyPqueue;
      switch (e.kind) {
        case TraceEventKind::Push: return e.depth == 0 ? "init" : "push";
        case TraceEventKind::Pop: return "pop";
        case TraceEventKind::Cull:
          if (step == 0 && e.depth == 0) return pq ? "init" : "cull_root";
          if (follows_pop_of(events, step, e.node)) return "beyond";
          // The priority queue's final sweep skips queued nodes without popping them.
          if (pq && was_pushed(events, step, e.node)) return "beyond";
          return "cull_child";
        case TraceEventKind::Visit: return visit_is_leaf(events, step, lookup) ? "visit_leaf" : "visit_inner";
        case TraceEventKind::Done: return "done";
        default: return "";
      }
    }
    case TraversalKind::Unknown: return "";
  }
  return "";
}

}  // namespace

TraversalKind traversal_kind(accel::TraversalFamily family, const std::string& traversal) {
  switch (family) {
    case accel::TraversalFamily::Linear: return TraversalKind::Brute;
    case accel::TraversalFamily::Dda: return TraversalKind::Grid;
    case accel::TraversalFamily::Octree: return TraversalKind::Octree;
    case accel::TraversalFamily::KdTree: return TraversalKind::KdTree;
    case accel::TraversalFamily::Hierarchy:
      if (traversal == "dfs") return TraversalKind::HierarchyDfs;
      if (traversal == "pqueue") return TraversalKind::HierarchyPqueue;
      return TraversalKind::HierarchyOrdered;
  }
  return TraversalKind::Unknown;
}

const char* traversal_label(TraversalKind kind) {
  switch (kind) {
    case TraversalKind::Brute: return "linear scan";
    case TraversalKind::Grid: return "3D-DDA";
    case TraversalKind::Grid2d: return "2D-DDA";
    case TraversalKind::Octree: return "octree recursion";
    case TraversalKind::KdTree: return "near/far recursion";
    case TraversalKind::HierarchyDfs: return "depth-first";
    case TraversalKind::HierarchyOrdered: return "ordered depth-first";
    case TraversalKind::HierarchyPqueue: return "priority queue";
    case TraversalKind::Unknown: return "?";
  }
  return "?";
}

const PseudoCode& pseudo_code(TraversalKind kind) {
  switch (kind) {
    case TraversalKind::Brute: return brute_code();
    case TraversalKind::Grid: return grid_code();
    case TraversalKind::Grid2d: return grid_2d_code();
    case TraversalKind::Octree: return octree_code();
    case TraversalKind::KdTree: return kd_code();
    case TraversalKind::HierarchyDfs: return dfs_code();
    case TraversalKind::HierarchyOrdered: return ordered_code();
    case TraversalKind::HierarchyPqueue: return pqueue_code();
    case TraversalKind::Unknown: return unknown_code();
  }
  return unknown_code();
}

std::string pseudo_code_anchor(TraversalKind kind, std::span<const TraceEvent> events, size_t step,
                               const NodeLookup& lookup) {
  if (step >= events.size()) return "";
  return anchor_of(kind, events, step, lookup);
}

int pseudo_code_line(TraversalKind kind, std::span<const TraceEvent> events, size_t step, const NodeLookup& lookup) {
  const std::string anchor = pseudo_code_anchor(kind, events, step, lookup);
  if (anchor.empty()) return -1;
  const PseudoCode& code = pseudo_code(kind);
  for (size_t i = 0; i < code.anchors.size(); ++i)
    if (code.anchors[i] == anchor) return int(i);
  return -1;
}

// ---------------------------------------------------------------------------------------
// Construction listings: the lecture's procedures (../shared/seed/), one line per step the
// builders record; anchors are the event kinds (build_trace.h).

namespace {

const PseudoCode& build_brute_code() {
  static const PseudoCode code = listing("Brute force: no construction", {
      {"scene_box", "box = bbox of the scene"},
      {"node", "list = all triangles"},
      {"leaf", "one leaf holds them all"},
      {"done", "done"},
  });
  return code;
}

const PseudoCode& build_grid_code() {
  static const PseudoCode code = listing("Uniform grid: generation (lecture)", {
      {"scene_box", "box = bbox of the scene"},
      {"grid_resolution", "resolution = lambda * cbrt(N) cells per axis"},
      {"", "    (cells cuboid-like: scaled by the box's extents)"},
      {"", "for each object:   // insert objects in cells"},
      {"grid_insert", "    for each cell under the object's bbox:"},
      {"", "        append the object to ObjectList[X][Y][Z]"},
      {"", "    (exact: keep only cells the triangle touches)"},
      {"done", "done: #cells in O(N)"},
  });
  return code;
}

const PseudoCode& build_octree_code() {
  static const PseudoCode code = listing("Octree: construction (lecture)", {
      {"scene_box", "start with the bbox of the whole scene"},
      {"node", "build(cell, objects):"},
      {"leaf", "    if few objects or max depth: leaf"},
      {"", "    if the sub-cells save less than their visits:"},
      {"", "        leaf   (added: 3 ct + refs/4 >= objects)"},
      {"subdivide", "    subdivide the cell into 8 equal sub-cells (2D: 4)"},
      {"", "    for each sub-cell:"},
      {"", "        build(sub-cell, objects overlapping it)"},
      {"unrecorded", "    (below the recorded depth: built, not shown)"},
      {"done", "done"},
  });
  return code;
}

const PseudoCode& build_kd_code() {
  static const PseudoCode code = listing("kd-tree: construction, top down (lecture)", {
      {"scene_box", "root cell = bbox of the scene"},
      {"node", "build(cell, primitives):"},
      {"axis", "    1. choose an axis-aligned plane: axis"},
      {"candidates", "       position: middle / median / min C(B)"},
      {"split", "       split, unless no plane beats the leaf"},
      {"", "    2. distribute the geometry among the children"},
      {"", "       (some go to both)"},
      {"", "    3. recursion: build(left), build(right)"},
      {"leaf", "    until the stopping criterion: leaf"},
      {"unrecorded", "    (below the recorded depth: built, not shown)"},
      {"done", "done"},
  });
  return code;
}

/// The hierarchies' common tail: fit the volumes, collapse a wide BVH.
std::vector<std::pair<const char*, const char*>> hierarchy_tail() {
  return {
      {"unrecorded", "(below the recorded depth: built, not shown)"},
      {"collapse", "width 4 / 8: open a child where that lowers the SAH cost"},
      {"fit", "fit each node's bounding volume (box / sphere)"},
      {"done", "done"},
  };
}

/// A hierarchy builder's listing from its row (BvhBuilderInfo::listing): a top-down one
/// inside the one recursion's lines, a bottom-up one as it is; the common tail after either.
PseudoCode hierarchy_listing(const accel::BvhBuilderInfo& row) {
  std::vector<std::pair<const char*, const char*>> rows;
  if (row.top_down) {
    rows = {
        {"scene_box", "elementary BVs around all objects"},
        {"node", "build(objects):"},
    };
  }
  for (const accel::ListingLine& line : row.listing->lines) rows.emplace_back(line.anchor, line.text);
  if (row.top_down) {
    rows.insert(rows.end(), {
                                {"", "    left = objects before the plane, right = the rest"},
                                {"", "    build(left); build(right)"},
                                {"leaf", "    terminate when fewer than n objects: leaf"},
                            });
  }
  for (auto line : hierarchy_tail()) rows.push_back(line);
  return listing(row.listing->title, rows);
}

/// The listing of a hierarchy's builder, made once per row of the builders' table (fixed
/// once read).
const PseudoCode& builder_code(accel::BvhBuilderKind builder) {
  static const std::vector<PseudoCode> codes = [] {
    std::vector<PseudoCode> all;
    for (const accel::BvhBuilderInfo& row : accel::bvh_builder_table()) all.push_back(hierarchy_listing(row));
    return all;
  }();
  const std::span<const accel::BvhBuilderInfo> rows = accel::bvh_builder_table();
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].kind == builder) return codes[i];
  return unknown_code();  // not a row (a corrupt value): no listing
}

}  // namespace

BuildCodeKind build_code_of(accel::ConstructionFamily family) { return {true, family}; }

BuildCodeKind build_code_of(accel::BvhBuilderKind builder) {
  return {true, accel::ConstructionFamily::Hierarchy, builder};
}

BuildCodeKind build_code_kind(const std::string& name, const std::vector<std::string>& params) {
  auto info = accel::find_structure(name);
  if (!info) return BuildCodeKind::Unknown;
  const accel::ConstructionFamily family = info.value()->construction;
  if (family != accel::ConstructionFamily::Hierarchy) return build_code_of(family);
  auto set = accel::ParamSet::parse(info.value()->params, params, name);
  if (!set || !set.value().has("builder")) return BuildCodeKind::Unknown;
  return build_code_of(accel::hierarchy_options(set.value()).build.builder);
}

const char* build_code_label(BuildCodeKind kind) {
  if (!kind.known) return "?";
  switch (kind.family) {
    case accel::ConstructionFamily::Linear: return "brute force";
    case accel::ConstructionFamily::GridInsert: return "grid";
    case accel::ConstructionFamily::Octree: return "octree";
    case accel::ConstructionFamily::KdTree: return "kd-tree";
    case accel::ConstructionFamily::Hierarchy: return accel::bvh_builder(kind.builder).label;
  }
  return "?";
}


const PseudoCode& build_pseudo_code(BuildCodeKind kind) {
  if (!kind.known) return unknown_code();
  switch (kind.family) {
    case accel::ConstructionFamily::Linear: return build_brute_code();
    case accel::ConstructionFamily::GridInsert: return build_grid_code();
    case accel::ConstructionFamily::Octree: return build_octree_code();
    case accel::ConstructionFamily::KdTree: return build_kd_code();
    case accel::ConstructionFamily::Hierarchy: return builder_code(kind.builder);
  }
  return unknown_code();
}

int build_code_line(BuildCodeKind kind, const accel::BuildEvent* e) {
  if (!e) return -1;
  const PseudoCode& code = build_pseudo_code(kind);
  const std::string anchor = accel::build_event_kind_name(e->kind);
  for (size_t i = 0; i < code.anchors.size(); ++i)
    if (code.anchors[i] == anchor) return static_cast<int>(i);
  return -1;
}

}  // namespace viz
