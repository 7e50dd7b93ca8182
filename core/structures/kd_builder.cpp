// kd-tree build: clipping triangles to boxes (perfect splits), the sorted event lists, the
// middle, median and SAH split choices, distribution and recursion (see kd_builder.h).
//
// Index
//   [SECTION] Depth limit and names
//   [SECTION] Clipping triangles to boxes
//   [SECTION] Events
//   [SECTION] Builder: split choice (middle, median, sah)
//   [SECTION] Builder: distribution and recursion
#include "structures/kd_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "check.h"

namespace accel {

//-----------------------------------------------------------------------------
// [SECTION] Depth limit and names
//-----------------------------------------------------------------------------

int kd_auto_max_depth(size_t n) {
  const double d = 8.0 + 1.3 * std::log2(double(std::max<size_t>(n, 1)));
  return std::min(kKdMaxDepth, int(std::lround(d)));
}

const char* kd_split_name(KdSplit s) {
  switch (s) {
    case KdSplit::Middle: return "middle";
    case KdSplit::Median: return "median";
    case KdSplit::Sah: return "sah";
  }
  return "?";
}

namespace {

//-----------------------------------------------------------------------------
// [SECTION] Clipping triangles to boxes
//-----------------------------------------------------------------------------

/// Largest float <= x.
float round_down(double x) {
  float f = float(x);
  if (double(f) > x) f = std::nextafter(f, -kInf);
  return f;
}
/// Smallest float >= x.
float round_up(double x) {
  float f = float(x);
  if (double(f) < x) f = std::nextafter(f, kInf);
  return f;
}

/// Bounds of the part of triangle `prim` inside the closed box `box`, for perfect splits
/// (Havran 2000; Wald & Havran 2006 sec. 4.3): Sutherland-Hodgman clipping against the six
/// slabs, in double. Conservative both ways rounding could hurt:
///  * the box is enlarged by delta = 2^-30 of the largest coordinate involved (far above the
///    double rounding of the clip, far below a float ulp), so a triangle touching the box is
///    never clipped away;
///  * the polygon's bounds are widened by delta and rounded outward to float, then cut to
///    the triangle's own box and to `box` (both exact bounds of the true clipped part).
/// Returns false only when the triangle certainly misses the box.
bool clip_triangle_bounds(const Scene& scene, uint32_t prim, const Aabb& box, Aabb* out) {
  const Aabb& tri = scene.triangle_bounds(prim);
  Aabb cut;
  cut.min = glm::max(tri.min, box.min);
  cut.max = glm::min(tri.max, box.max);
  if (cut.empty()) return false;
  if (box.contains(tri)) {  // nothing to clip
    *out = tri;
    return true;
  }
  double m = 0.0;
  for (int k = 0; k < 3; ++k) {
    m = std::max({m, std::abs(double(tri.min[k])), std::abs(double(tri.max[k])), std::abs(double(box.min[k])),
                  std::abs(double(box.max[k]))});
  }
  const double delta = std::ldexp(std::max(m, 1e-30), -30);

  // A triangle clipped by 6 planes has at most 3 + 6 vertices.
  DVec3 poly[10], next[10];
  int n = 3;
  for (int k = 0; k < 3; ++k) poly[k] = DVec3(scene.vertex(prim, k));
  for (int axis = 0; axis < 3 && n > 0; ++axis) {
    for (int side = 0; side < 2 && n > 0; ++side) {
      const double plane = side == 0 ? double(box.min[axis]) - delta : double(box.max[axis]) + delta;
      auto inside = [&](const DVec3& p) { return side == 0 ? p[axis] >= plane : p[axis] <= plane; };
      int m_out = 0;
      for (int i = 0; i < n; ++i) {
        const DVec3& a = poly[i];
        const DVec3& b = poly[(i + 1) % n];
        const bool in_a = inside(a), in_b = inside(b);
        if (in_a) next[m_out++] = a;
        if (in_a != in_b) {
          const double s = (plane - a[axis]) / (b[axis] - a[axis]);
          DVec3 q = a + s * (b - a);
          q[axis] = plane;
          next[m_out++] = q;
        }
      }
      n = m_out;
      std::copy(next, next + n, poly);
    }
  }
  if (n == 0) return false;
  DVec3 lo = poly[0], hi = poly[0];
  for (int i = 1; i < n; ++i) {
    lo = glm::min(lo, poly[i]);
    hi = glm::max(hi, poly[i]);
  }
  Aabb b;
  for (int k = 0; k < 3; ++k) {
    b.min[k] = std::max(round_down(lo[k] - delta), cut.min[k]);
    b.max[k] = std::min(round_up(hi[k] + delta), cut.max[k]);
  }
  if (b.empty()) return false;  // the enlarged clip lies outside the exact bounds: a miss
  *out = b;
  return true;
}

//-----------------------------------------------------------------------------
// [SECTION] Events
//-----------------------------------------------------------------------------

/// Event types in sweep order: at one position, ends come before planars before starts
/// (Wald & Havran 2006 sec. 4.2), so a triangle ending at a plane counts left only and one
/// starting there right only.
enum EventType : uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

/// One boundary of a triangle's (clipped) extent along one axis. 8 bytes: the triangle id
/// and the type share one word (ids < 2^30).
struct Event {
  float pos;
  uint32_t prim_type;  // prim << 2 | type
  uint32_t prim() const { return prim_type >> 2; }
  uint32_t type() const { return prim_type & 3u; }
};
static_assert(sizeof(Event) == 8);

bool event_less(const Event& a, const Event& b) {
  return a.pos < b.pos || (a.pos == b.pos && a.type() < b.type());
}

/// The events of one node: per axis, sorted by event_less.
struct EventLists {
  std::vector<Event> axis[3];
  size_t size() const { return axis[0].size() + axis[1].size() + axis[2].size(); }
};

/// Appends the events of `prim` with extent `b` (one planar event on an axis where the extent
/// is flat, else an end and a start).
void add_events(EventLists& lists, uint32_t prim, const Aabb& b) {
  for (int k = 0; k < 3; ++k) {
    if (b.min[k] == b.max[k]) {
      lists.axis[k].push_back({b.min[k], prim << 2 | kPlanar});
    } else {
      lists.axis[k].push_back({b.min[k], prim << 2 | kStart});
      lists.axis[k].push_back({b.max[k], prim << 2 | kEnd});
    }
  }
}

/// Number of triangles in a node: every triangle has one start or planar event per axis.
size_t prim_count(const EventLists& lists) {
  size_t n = 0;
  for (const Event& e : lists.axis[0]) n += e.type() != kEnd;
  return n;
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: split choice (middle, median, sah)
//-----------------------------------------------------------------------------

/// Where to split a node; axis < 0 = make a leaf.
struct SplitChoice {
  int axis = -1;
  float pos = 0.0f;
  bool planar_left = true;  ///< triangles lying in the plane go left (else right)
};

enum Side : uint8_t { kBoth = 0, kLeft = 1, kRight = 2 };

class KdBuilder {
 public:
  /// Reports into [progress_from, 1] of `control` (a retry continues where the last stopped).
  KdBuilder(const Scene& scene, const KdBuildOptions& options, BuildControl* control, double progress_from)
      : scene_(scene), o_(options), control_(control), progress_(control, progress_from, 1.0) {}
  Result<KdTreeData> run();
  /// The last fraction reported.
  double progress_reached() const { return progress_.last(); }

 private:
  void build_node(EventLists& events, const Aabb& box, int depth, int bad_refines, double share);
  double split_cost(const Aabb& box, const SplitChoice& s, size_t nl, size_t nr) const;
  void make_leaf(const EventLists& events, size_t n, int depth);
  int choose_axis(const Aabb& box, int depth) const;
  SplitChoice split_middle(const Aabb& box, int depth) const;
  SplitChoice split_median(const EventLists& events, const Aabb& box, int depth, size_t n);
  SplitChoice split_sah(const EventLists& events, const Aabb& box, size_t n) const;
  void classify(const EventLists& events, const SplitChoice& s);
  void distribute(const EventLists& events, const SplitChoice& s, const Aabb& box, EventLists* left,
                  EventLists* right);
  void over_budget(const char* what, size_t limit);

  const Scene& scene_;
  KdBuildOptions o_;
  KdTreeData out_;
  std::vector<uint8_t> side_;      // per triangle id: Side in the node being split
  std::vector<float> lo_, hi_;     // per triangle id: extent along the median axis
  size_t live_events_ = 0;         // events of all lists alive (the recursion's pending ones)
  EventLists scratch_new_[2];      // distribute(): events of re-clipped straddlers, per side
  std::vector<Event> scratch_only_[2];  // distribute(): events of one-sided triangles, per side
  Status status_;                  // the first budget error (or the cancel); the build stops at it
  BuildControl* control_;
  ProgressSpan progress_;
  double done_ = 0.0;              // share of the build in finished leaves
};

/// Records the budget error (the first one): names the parameters that control the tree size.
void KdBuilder::over_budget(const char* what, size_t limit) {
  if (!status_) return;
  char depth[48];
  if (o_.max_depth > 0)
    std::snprintf(depth, sizeof depth, "%d", o_.max_depth);
  else
    std::snprintf(depth, sizeof depth, "0 (auto: %d)", out_.max_depth_limit);
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "kdtree parameter 'max_depth' = %s (leaf_size = %d, split = %s): the tree would need more than "
                "%zu %s (limit); lower max_depth, raise leaf_size, or use split=sah",
                depth, o_.leaf_size, kd_split_name(o_.split), limit, what);
  status_ = make_error(buf);
}

int KdBuilder::choose_axis(const Aabb& box, int depth) const {
  const Vec3 e = box.max - box.min;
  if (o_.axis == KdAxis::Longest) return box.longest_axis();
  for (int i = 0; i < 3; ++i) {  // round robin, skipping flat axes (no plane fits inside)
    const int axis = (depth + i) % 3;
    if (e[axis] > 0.0f) return axis;
  }
  return depth % 3;
}

SplitChoice KdBuilder::split_middle(const Aabb& box, int depth) const {
  const int axis = choose_axis(box, depth);
  const float pos = 0.5f * box.min[axis] + 0.5f * box.max[axis];
  if (!(pos > box.min[axis] && pos < box.max[axis])) return {};  // region too thin to halve
  return {axis, pos, true};
}

// Median of the centres of the triangles' clipped extents (inside the region, unlike the
// triangles' own centroids, so the plane lies inside too). Falls back to the middle when
// the median is on the region's boundary (e.g. most triangles touch it).
SplitChoice KdBuilder::split_median(const EventLists& events, const Aabb& box, int depth, size_t n) {
  const int axis = choose_axis(box, depth);
  std::vector<float> centres;
  centres.reserve(n);
  for (const Event& e : events.axis[axis]) {
    if (e.type() != kEnd) lo_[e.prim()] = e.pos;
    if (e.type() != kStart) hi_[e.prim()] = e.pos;
  }
  for (const Event& e : events.axis[axis])
    if (e.type() != kEnd) centres.push_back(0.5f * lo_[e.prim()] + 0.5f * hi_[e.prim()]);
  auto mid = centres.begin() + ptrdiff_t(centres.size() / 2);
  std::nth_element(centres.begin(), mid, centres.end());
  const float pos = *mid;
  if (pos > box.min[axis] && pos < box.max[axis]) return {axis, pos, true};
  return split_middle(box, depth);
}

// Wald & Havran 2006, Algorithm 4 (per axis): sweep the sorted events; at each position p
// the counts are N_L (triangles before), N_P (lying in p), N_R (after); the cost of a plane
// is  lambda * (ct + ci * (A_L/A * N_L + A_R/A * N_R))  with the planar ones added to the
// cheaper side, lambda = 1 - empty_bonus when a side is empty. Planes strictly inside the
// region are candidates; a plane on its boundary only to cut off the triangles lying in it.
// Returns "leaf" when no plane beats the leaf cost ci * N (Wald & Havran's automatic
// termination).
SplitChoice KdBuilder::split_sah(const EventLists& events, const Aabb& box, size_t n) const {
  SplitChoice best;
  const DVec3 e = DVec3(box.max) - DVec3(box.min);
  const double area = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
  if (!(area > 0.0)) return best;
  const double inv_area = 1.0 / area;
  double best_cost = o_.ci * double(n);
  auto cost = [&](double pl, double pr, size_t nl, size_t nr) {
    const double c = o_.ct + o_.ci * (pl * double(nl) + pr * double(nr));
    return (nl == 0 || nr == 0) ? c * (1.0 - o_.empty_bonus) : c;
  };
  for (int axis = 0; axis < 3; ++axis) {
    if (!(box.max[axis] > box.min[axis])) continue;
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const double cross = e[a1] * e[a2], around = e[a1] + e[a2];
    const std::vector<Event>& ev = events.axis[axis];
    size_t nl = 0, nr = n;
    for (size_t i = 0; i < ev.size();) {
      const float p = ev[i].pos;
      size_t ends = 0, planars = 0, starts = 0;
      while (i < ev.size() && ev[i].pos == p && ev[i].type() == kEnd) ++ends, ++i;
      while (i < ev.size() && ev[i].pos == p && ev[i].type() == kPlanar) ++planars, ++i;
      while (i < ev.size() && ev[i].pos == p && ev[i].type() == kStart) ++starts, ++i;
      nr -= planars + ends;
      const double dl = double(p) - double(box.min[axis]), dr = double(box.max[axis]) - double(p);
      const double pl = 2.0 * (cross + dl * around) * inv_area, pr = 2.0 * (cross + dr * around) * inv_area;
      if (p > box.min[axis] && p < box.max[axis]) {
        const double c_left = cost(pl, pr, nl + planars, nr), c_right = cost(pl, pr, nl, nr + planars);
        const double c = std::min(c_left, c_right);
        if (c < best_cost) {
          best_cost = c;
          best = {axis, p, c_left <= c_right};
        }
      } else if (planars > 0 && planars < n) {
        // A plane on the region's boundary holding planar triangles: cut them off into a
        // flat cell (Wald & Havran 2006 sec. 4.4), e.g. the walls of axis-aligned rooms.
        // Both sides then hold fewer triangles than the node, so this always progresses.
        const bool at_min = p == box.min[axis];
        const double c = at_min ? cost(pl, pr, planars, n - planars) : cost(pl, pr, n - planars, planars);
        if (c < best_cost) {
          best_cost = c;
          best = {axis, p, at_min};
        }
      }
      nl += starts + planars;
    }
  }
  return best;
}

//-----------------------------------------------------------------------------
// [SECTION] Builder: distribution and recursion
//-----------------------------------------------------------------------------

// Sides by the split axis' events, consistent with the sweep's counts: extent ending at or
// before the plane -> left; starting at or after it -> right; lying in it -> the chosen
// side; crossing it -> both.
void KdBuilder::classify(const EventLists& events, const SplitChoice& s) {
  const std::vector<Event>& ev = events.axis[s.axis];
  for (const Event& e : ev)
    if (e.type() != kEnd) side_[e.prim()] = kBoth;
  for (const Event& e : ev) {
    const uint32_t prim = e.prim();
    switch (e.type()) {
      case kEnd:
        if (e.pos <= s.pos) side_[prim] = kLeft;
        break;
      case kStart:
        if (e.pos >= s.pos) side_[prim] = kRight;
        break;
      default:  // planar
        if (e.pos < s.pos || (e.pos == s.pos && s.planar_left))
          side_[prim] = kLeft;
        else
          side_[prim] = kRight;
        break;
    }
  }
}

// Wald & Havran 2006 sec. 5.2: the events of one-sided triangles are filtered into the
// child lists (staying sorted); the straddling triangles are clipped to each child's region
// (perfect splits) or cut to it (clip=off), their new events sorted -- only these, O(s log s)
// -- and merged in. This keeps every list sorted without a sort per node: O(N log N).
void KdBuilder::distribute(const EventLists& events, const SplitChoice& s, const Aabb& box, EventLists* left,
                           EventLists* right) {
  EventLists& new_left = scratch_new_[0];
  EventLists& new_right = scratch_new_[1];
  for (int k = 0; k < 3; ++k) {
    new_left.axis[k].clear();
    new_right.axis[k].clear();
  }
  const Aabb box_l = kd_child_box(box, s.axis, s.pos, false), box_r = kd_child_box(box, s.axis, s.pos, true);
  for (const Event& e : events.axis[0]) {
    if (e.type() == kEnd || side_[e.prim()] != kBoth) continue;
    const uint32_t prim = e.prim();
    Aabb b;
    if (o_.clip) {
      if (clip_triangle_bounds(scene_, prim, box_l, &b)) add_events(new_left, prim, b);
      if (clip_triangle_bounds(scene_, prim, box_r, &b)) add_events(new_right, prim, b);
    } else {
      const Aabb& tri = scene_.triangle_bounds(prim);
      for (const Aabb* child : {&box_l, &box_r}) {
        b.min = glm::max(tri.min, child->min);
        b.max = glm::min(tri.max, child->max);
        add_events(child == &box_l ? new_left : new_right, prim, b);
      }
    }
  }
  for (int k = 0; k < 3; ++k) {
    std::vector<Event>& only_left = scratch_only_[0];
    std::vector<Event>& only_right = scratch_only_[1];
    only_left.clear();
    only_right.clear();
    for (const Event& e : events.axis[k]) {
      const uint8_t side = side_[e.prim()];
      if (side == kLeft) only_left.push_back(e);
      else if (side == kRight) only_right.push_back(e);
    }
    auto combine = [](const std::vector<Event>& only, std::vector<Event>& fresh, std::vector<Event>* out) {
      std::sort(fresh.begin(), fresh.end(), event_less);
      out->resize(only.size() + fresh.size());
      std::merge(only.begin(), only.end(), fresh.begin(), fresh.end(), out->begin(), event_less);
    };
    combine(only_left, new_left.axis[k], &left->axis[k]);
    combine(only_right, new_right.axis[k], &right->axis[k]);
  }
}

void KdBuilder::make_leaf(const EventLists& events, size_t n, int depth) {
  if (out_.prim_ids.size() + n > o_.reference_limit) {
    over_budget("triangle references", o_.reference_limit);
    return;
  }
  const size_t offset = out_.prim_ids.size();
  for (const Event& e : events.axis[0])
    if (e.type() != kEnd) out_.prim_ids.push_back(e.prim());
  std::sort(out_.prim_ids.begin() + ptrdiff_t(offset), out_.prim_ids.end());  // ascending: stable ties, tidy views
  out_.nodes.push_back(KdNode::make_leaf(uint32_t(offset), uint32_t(n)));
  out_.depth = std::max(out_.depth, depth);
}

/// SAH cost of splitting `box` at `s` with nl / nr triangles on the sides (the formula of
/// split_sah(), for judging middle and median splits).
double KdBuilder::split_cost(const Aabb& box, const SplitChoice& s, size_t nl, size_t nr) const {
  const double area = box.area();
  if (!(area > 0.0)) return kInf;
  const double pl = kd_child_box(box, s.axis, s.pos, false).area() / area;
  const double pr = kd_child_box(box, s.axis, s.pos, true).area() / area;
  const double c = o_.ct + o_.ci * (pl * double(nl) + pr * double(nr));
  return (nl == 0 || nr == 0) ? c * (1.0 - o_.empty_bonus) : c;
}

// Depth-first, writing nodes in pre-order: the below child follows its parent, the above
// child's index is patched in once the below subtree is done (pbrt's layout). `events` is
// consumed: freed before the recursion, so only the pending above lists of the current path
// stay alive, which bounds the build's memory.
//
// Guards against explosion (a kd-tree duplicates straddling triangles, so a split that
// separates nothing only multiplies references):
//  * a split that sends every triangle to both sides makes a leaf instead (identical or
//    all-straddling triangles);
//  * middle and median have no cost function to stop them near a vertex or edge shared by
//    more than leaf_size triangles, where no plane ever separates them: a split whose SAH cost
//    is not below the leaf's (ci * N) is a "bad refine", and the third one on a path makes a
//    leaf (pbrt-v4 KdTreeAggregate's badRefines rule). SAH stops at its first such split.
void KdBuilder::build_node(EventLists& events, const Aabb& box, int depth, int bad_refines, double share) {
  if (!status_) return;
  if (build_cancelled(control_)) {
    status_ = cancelled_error();
    return;
  }
  if (out_.nodes.size() >= o_.node_limit || out_.nodes.size() >= kKdMaxIndex) {
    over_budget("nodes", std::min<size_t>(o_.node_limit, kKdMaxIndex));
    return;
  }
  const size_t n = prim_count(events);
  SplitChoice s;
  size_t* reason = nullptr;
  if (n <= size_t(o_.leaf_size)) {
    reason = &out_.leaf_reasons.few_prims;
  } else if (depth >= out_.max_depth_limit) {
    reason = &out_.leaf_reasons.max_depth;
  } else {
    switch (o_.split) {
      case KdSplit::Middle: s = split_middle(box, depth); break;
      case KdSplit::Median: s = split_median(events, box, depth, n); break;
      case KdSplit::Sah: s = split_sah(events, box, n); break;
    }
    if (s.axis < 0) reason = o_.split == KdSplit::Sah ? &out_.leaf_reasons.no_gain : &out_.leaf_reasons.thin;
  }
  EventLists left, right;
  size_t nl = 0, nr = 0;
  if (s.axis >= 0) {
    classify(events, s);
    distribute(events, s, box, &left, &right);
    nl = prim_count(left);
    nr = prim_count(right);
    if (nl == n && nr == n) {
      s.axis = -1;
      reason = &out_.leaf_reasons.no_progress;
    } else if (o_.split != KdSplit::Sah && split_cost(box, s, nl, nr) >= o_.ci * double(n) && ++bad_refines >= 3) {
      s.axis = -1;
      reason = &out_.leaf_reasons.bad_refines;
    }
  }
  if (s.axis < 0) {
    ++*reason;
    make_leaf(events, n, depth);
    live_events_ -= events.size();
    events = EventLists{};
    done_ += share;
    progress_.advance(done_);
    return;
  }
  const double share_left = share * double(nl) / double(std::max<size_t>(1, nl + nr));
  live_events_ += left.size() + right.size() - events.size();
  events = EventLists{};
  if (live_events_ > o_.event_limit) {
    over_budget("build events", o_.event_limit);
    return;
  }
  const size_t self = out_.nodes.size();
  out_.nodes.push_back(KdNode{});
  build_node(left, kd_child_box(box, s.axis, s.pos, false), depth + 1, bad_refines, share_left);
  if (!status_) return;
  const size_t above = out_.nodes.size();
  if (above > kKdMaxIndex) {
    over_budget("nodes", kKdMaxIndex);
    return;
  }
  out_.nodes[self] = KdNode::make_inner(s.axis, s.pos, NodeId(above));
  build_node(right, kd_child_box(box, s.axis, s.pos, true), depth + 1, bad_refines, share - share_left);
}

Result<KdTreeData> KdBuilder::run() {
  const std::vector<uint32_t>& prims = scene_.valid_prims();
  out_.max_depth_limit = o_.max_depth > 0 ? std::min(o_.max_depth, kKdMaxDepth) : kd_auto_max_depth(prims.size());
  if (prims.empty()) {
    out_.nodes.push_back(KdNode::make_leaf(0, 0));
    ++out_.leaf_reasons.few_prims;
    return std::move(out_);
  }
  if (scene_.triangle_count() > kKdMaxIndex) return make_error("kdtree: scene has too many triangles (limit 2^30)");
  side_.assign(scene_.triangle_count(), kBoth);
  if (o_.split == KdSplit::Median) {
    lo_.assign(scene_.triangle_count(), 0.0f);
    hi_.assign(scene_.triangle_count(), 0.0f);
  }
  EventLists root;
  for (uint32_t prim : prims) {
    out_.root_box.extend(scene_.triangle_bounds(prim));
    add_events(root, prim, scene_.triangle_bounds(prim));  // inside the root box: nothing to clip
  }
  if (build_cancelled(control_)) return cancelled_error();
  for (auto& list : root.axis) std::sort(list.begin(), list.end(), event_less);
  live_events_ = root.size();
  if (live_events_ > o_.event_limit) return make_error("kdtree: scene too large for the build's event budget");
  build_node(root, out_.root_box, 0, 0, 1.0);
  if (!status_) return status_.error();
  ACCEL_CHECK(out_.depth <= kKdMaxDepth);  // the traversal's stack holds kKdMaxDepth entries
  return std::move(out_);
}

}  // namespace

Result<KdTreeData> build_kd_tree(const Scene& scene, const KdBuildOptions& options, BuildControl* control) {
  if (build_cancelled(control)) return cancelled_error();
  if (options.max_depth > 0) return KdBuilder(scene, options, control, 0.0).run();
  // Automatic depth: keep the tree within a size proportional to the scene (at most 64
  // references per triangle, or 4M). Scenes that every plane cuts -- thousands of overlapping
  // coplanar triangles -- would otherwise grow to the absolute budget before failing; there
  // the depth limit is lowered until the tree fits, as the lecture's stop criterion intends.
  KdBuildOptions o = options;
  const size_t n = scene.valid_prims().size();
  o.reference_limit = std::min(options.reference_limit, std::max<size_t>(size_t(1) << 22, 64 * n));
  o.node_limit = std::min(options.node_limit, 2 * o.reference_limit);
  double reached = 0.0;
  for (int depth = kd_auto_max_depth(n);; depth = std::max(1, depth - 4)) {
    o.max_depth = depth;
    KdBuilder builder(scene, o, control, reached);
    Result<KdTreeData> tree = builder.run();
    if (tree || depth == 1 || build_cancelled(control)) return tree;
    reached = builder.progress_reached();
  }
}

}  // namespace accel
