#include "student/walk_audit.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <unordered_map>
#include <unordered_set>
#include <variant>

#include "planar_geometry.h"
#include "student/kit_structure.h"
#include "traps.h"

namespace accel {
namespace {

std::string num(double v) {
  char b[48];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

/// a < b by more than rounding (relative 4e-6): t values the student computed in float.
bool clearly_below(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return a < b;
  return a < b - 4e-6 * std::max({std::fabs(a), std::fabs(b), 1e-30});
}

/// The ray's part inside `box` (padded by a relative 1e-6 of its size and place), in double:
/// false when it misses. A zero direction component needs the origin within the slab (no NaN).
bool crossing(const Ray& ray, const Aabb& box, double abs_pad, double& enter, double& exit) {
  if (box.empty()) return false;
  enter = -INFINITY, exit = INFINITY;
  for (int a = 0; a < 3; ++a) {
    const double lo = box.min[a], hi = box.max[a];
    const double pad = 1e-6 * (std::fabs(lo) + std::fabs(hi) + (hi - lo)) + abs_pad;
    const double o = ray.org[a], d = ray.dir[a];
    if (d == 0.0) {
      if (o < lo - pad || o > hi + pad) return false;
      continue;
    }
    double t0 = (lo - pad - o) / d, t1 = (hi + pad - o) / d;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0), exit = std::min(exit, t1);
  }
  return enter <= exit;
}

bool point_in(const Aabb& box, const DVec3& p, double abs_pad) {
  for (int a = 0; a < 3; ++a) {
    const double lo = box.min[a], hi = box.max[a];
    const double pad = 1e-6 * (std::fabs(lo) + std::fabs(hi) + (hi - lo)) + abs_pad;
    if (p[a] < lo - pad || p[a] > hi + pad) return false;
  }
  return true;
}

/// A triangle the ray hits (exactly, in double), with its hit point.
struct ExactHit {
  uint32_t prim;
  double t;
  DVec3 point;
};

bool exact_hit(const Scene& scene, const Ray& ray, uint32_t prim, double& t) {
  double u, v;
  const Vec3 &a = scene.vertex(prim, 0), &b = scene.vertex(prim, 1), &c = scene.vertex(prim, 2);
  if (scene.planar() && is_planar_ray(ray)) return PlanarRayTester(ray).intersect(a, b, c, INFINITY, &t, &u, &v);
  return intersect_triangle_double(ray, a, b, c, INFINITY, &t, &u, &v);
}

/// Every triangle the ray hits in [tmin, tmax], nearest first.
std::vector<ExactHit> all_hits(const Scene& scene, const Ray& ray) {
  std::vector<ExactHit> hits;
  for (uint32_t p : scene.valid_prims()) {
    double t;
    if (!exact_hit(scene, ray, p, t) || t < double(ray.tmin) || t > double(ray.tmax)) continue;
    hits.push_back({p, t, DVec3(ray.org) + t * DVec3(ray.dir)});
  }
  std::sort(hits.begin(), hits.end(), [](const ExactHit& a, const ExactHit& b) { return a.t < b.t; });
  return hits;
}

}  // namespace

const FalseClaim* WalkAudit::first_lossy() const {
  for (const FalseClaim& c : claims)
    if (c.loses_hit) return &c;
  return nullptr;
}

const FalseClaim* WalkAudit::at(size_t step) const {
  for (const FalseClaim& c : claims)
    if (c.step == step) return &c;
  return nullptr;
}

/// Which leaves (trees) or cells (grids) hold each triangle.
struct WalkAuditor::Index {
  std::unordered_map<uint32_t, std::vector<uint32_t>> holders;  ///< prim -> dense leaf ids or cell indexes
  bool has_split = false;                                       ///< some inner node (or a grid)
  /// Triangles some node was made over (the grader keeps them; a grid: every triangle).
  std::unordered_set<uint32_t> given_to_some_node;
};

WalkAuditor::WalkAuditor(const KitTree& tree, accelviz::Kind kind, const Scene& scene)
    : tree_(tree), kind_(kind), scene_(scene) {}
WalkAuditor::~WalkAuditor() = default;

const WalkAuditor::Index& WalkAuditor::index() const {
  if (index_) return *index_;
  index_ = std::make_unique<Index>();
  if (tree_.grid) {
    index_->has_split = true;
    for (uint32_t c = 0; c < tree_.cells.size(); ++c)
      for (uint32_t p : tree_.cells[c]) index_->holders[p].push_back(c);
    for (uint32_t p : scene_.valid_prims()) index_->given_to_some_node.insert(p);
  } else {
    bool made_over_kept = false;
    for (const KitNode& k : tree_.nodes) made_over_kept |= !k.made_over.empty();
    for (uint32_t id = 0; id < tree_.nodes.size(); ++id) {
      const KitNode& k = tree_.nodes[id];
      for (uint32_t p : k.made_over) index_->given_to_some_node.insert(p);
      if (!made_over_kept && k.prim_count > 0 && id == 0)  // the viewer keeps no lists: trust the root's count
        for (uint32_t p : scene_.valid_prims()) index_->given_to_some_node.insert(p);
      if (!k.children.empty()) index_->has_split = true;
      if (k.leaf || k.children.empty())
        for (uint32_t p : k.prims) index_->holders[p].push_back(id);
    }
  }
  return *index_;
}

namespace {

/// The state of one audit: the ray, its hits, and the helpers that read the tree.
class Audit {
 public:
  Audit(const KitTree& tree, const Scene& scene, const Ray& ray, std::vector<ExactHit> hits, double final_t)
      : tree_(tree),
        ray_(ray),
        hits_(std::move(hits)),
        final_t_(final_t),
        // Points computed in double from float data: an absolute slack of the scene's scale
        // (a flat box, a hit on a wall at y = 0), on top of each box's relative one.
        pad(1e-6 * std::max(double(scene.max_abs_coordinate()), 1e-30)) {}

  WalkAudit out;
  double closest = INFINITY;  ///< the running closest hit, from the log's tested hits

  bool has_box(NodeId n) const { return tree_.grid ? n < tree_.cells.size() : n < tree_.nodes.size(); }
  Aabb box(NodeId n) const { return tree_.grid ? tree_.cell_box(n) : tree_.nodes[n].box; }
  std::string name(NodeId n) const {
    if (n == kNoNode) return "an unknown node";
    if (!tree_.grid) return "node " + std::to_string(tree_.nodes[n].student_id);
    const int x = int(n % uint32_t(tree_.res[0])), y = int((n / uint32_t(tree_.res[0])) % uint32_t(tree_.res[1])),
              z = int(n / (uint32_t(tree_.res[0]) * uint32_t(tree_.res[1])));
    return "cell (" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) + ")";
  }
  /// The cells holding triangle `prim` whose box contains `p`: the cell of `p` and, on a
  /// boundary, its neighbours.
  std::vector<NodeId> cells_holding(uint32_t prim, const DVec3& p) const {
    std::vector<NodeId> found;
    int c[3];
    for (int a = 0; a < 3; ++a) {
      const double lo = tree_.grid_box.min[a], size = double(tree_.grid_box.max[a] - tree_.grid_box.min[a]);
      const double at = size > 0 ? std::floor((p[a] - lo) / size * tree_.res[a]) : 0.0;
      c[a] = int(std::clamp(std::isnan(at) ? 0.0 : at, -2.0, double(tree_.res[a]) + 1.0));
    }
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const NodeId cell = tree_.cell_index(c[0] + dx, c[1] + dy, c[2] + dz);
          if (cell == kNoNode || !point_in(tree_.cell_box(cell), p, pad)) continue;
          const auto& prims = tree_.cells[cell];
          if (std::find(prims.begin(), prims.end(), prim) != prims.end()) found.push_back(cell);
        }
    return found;
  }
  /// Whether a leaf under `root` (or `root` itself, a leaf or a cell) holds `h`'s triangle and
  /// contains its hit point: found by descending through the boxes that contain the point,
  /// so no index of the whole tree is needed (the viewer audits every ray it shoots).
  bool holds_at(NodeId root, const ExactHit& h) const {
    if (tree_.grid) {
      const auto& prims = tree_.cells[root];
      return std::find(prims.begin(), prims.end(), h.prim) != prims.end();
    }
    std::vector<NodeId> stack{root};
    while (!stack.empty()) {
      const KitNode& k = tree_.nodes[stack.back()];
      stack.pop_back();
      if (k.leaf || k.children.empty()) {
        if (std::find(k.prims.begin(), k.prims.end(), uint32_t(h.prim)) != k.prims.end()) return true;
        continue;
      }
      for (uint32_t c : k.children)
        if (point_in(tree_.nodes[c].box, h.point, pad)) stack.push_back(c);
    }
    return false;
  }
  /// A hit nearer than the running closest hit and the final answer whose triangle sits in
  /// `root`'s subtree with its hit point inside `root`'s box: what skipping `root` loses.
  const ExactHit* lost_in(NodeId root) const {
    if (!has_box(root)) return nullptr;
    const Aabb b = box(root);
    for (const ExactHit& h : hits_) {
      if (!clearly_below(h.t, std::min(closest, final_t_))) break;
      if (point_in(b, h.point, pad) && holds_at(root, h)) return &h;
    }
    return nullptr;
  }
  void claim(size_t step, const char* cause, std::string said, std::string truth, bool lossy) {
    if (out.claims.size() >= WalkAudit::kMaxClaims) return;
    out.claims.push_back({step, cause, std::move(said), std::move(truth), lossy});
  }
  std::string lost_text(const ExactHit& h) const {
    return "it holds triangle " + std::to_string(h.prim) + ", hit at t=" + num(h.t);
  }

  const KitTree& tree_;
  const Ray& ray_;
  std::vector<ExactHit> hits_;
  double final_t_;
  double pad;
};

/// The plane of a kd-tree inner node: logged by split(), or where its two children meet.
bool kd_plane(const KitTree& tree, NodeId n, int& axis, double& pos) {
  if (n >= tree.nodes.size()) return false;
  const KitNode& k = tree.nodes[n];
  if (k.split_axis >= 0) {
    axis = k.split_axis, pos = k.split_pos;
    return true;
  }
  if (k.children.size() != 2) return false;
  const Aabb &a = tree.nodes[k.children[0]].box, &b = tree.nodes[k.children[1]].box;
  for (int ax = 0; ax < 3; ++ax)
    if (a.max[ax] <= b.min[ax] || b.max[ax] <= a.min[ax]) {
      axis = ax, pos = a.max[ax] <= b.min[ax] ? double(a.max[ax]) : double(b.max[ax]);
      return true;
    }
  return false;
}

/// The children of a kd_split that the walk actually took: pushed or visited before the
/// next visit (inclusive); culled ones are dropped. `logged`: nothing said, fall back to the case.
void kd_taken(std::span<const TraceEvent> ev, size_t from, NodeId near, NodeId far, bool& near_taken,
              bool& far_taken, bool& known) {
  near_taken = far_taken = known = false;
  for (size_t i = from; i < ev.size(); ++i) {
    const TraceEvent& e = ev[i];
    if (e.kind == TraceEventKind::Push || e.kind == TraceEventKind::Visit) {
      if (e.node == near) near_taken = known = true;
      if (e.node == far) far_taken = known = true;
    }
    if (e.kind == TraceEventKind::Cull && (e.node == near || e.node == far)) known = true;
    if (e.kind == TraceEventKind::Visit || e.kind == TraceEventKind::Done) break;
  }
}

void audit_kd_split(Audit& a, const KdSplitVars& kd, NodeId node, size_t step, std::span<const TraceEvent> ev) {
  ++a.out.kd_inner;
  int axis;
  double pos;
  if (!kd_plane(a.tree_, node, axis, pos) || kd.near_child >= a.tree_.nodes.size() ||
      kd.far_child >= a.tree_.nodes.size())
    return;
  const Aabb& near_box = a.tree_.nodes[kd.near_child].box;
  const bool near_is_lower = double(near_box.center()[axis]) < pos;
  bool near_taken, far_taken, known;
  kd_taken(ev, step + 1, kd.near_child, kd.far_child, near_taken, far_taken, known);
  if (!known) near_taken = kd.kase != KdCase::FarOnly, far_taken = kd.kase != KdCase::NearOnly;
  if (far_taken && !near_taken) ++a.out.kd_far_only;

  // Which sides the ray's part [t_min, t_max] really lies on.
  const double o = a.ray_.org[axis], d = a.ray_.dir[axis];
  const Aabb& nb = a.tree_.nodes[node].box;
  const double tol = 1e-6 * (std::fabs(pos) + double(nb.max[axis] - nb.min[axis])) + 1e-30;
  // The ray's true part inside the node (its box, not the logged interval, which an earlier
  // wrong step may have corrupted), up to the closest hit so far.
  bool need_lower = false, need_upper = false;
  double enter, exit;
  if (crossing(a.ray_, nb, a.pad, enter, exit)) {
    enter = std::max(enter, double(a.ray_.tmin));
    exit = std::min({exit, a.closest, double(a.ray_.tmax)});
    if (enter <= exit)
      for (double t : {enter, exit}) {
        const double x = std::isfinite(t) ? o + t * d : o;
        need_lower |= x < pos - tol, need_upper |= x > pos + tol;
      }
  }
  const bool need_near = near_is_lower ? need_lower : need_upper;
  const bool need_far = near_is_lower ? need_upper : need_lower;
  if (need_far && !need_near) ++a.out.kd_needs_far_only;
  const double true_split = d != 0.0 ? (pos - o) / d : (o == pos ? NAN : (pos > o) == !std::signbit(d) ? INFINITY : -INFINITY);
  auto said = [&] {
    return std::string("case ") + kd_case_name(kd.kase) + ": t_min=" + num(kd.t_min) + " t_split=" + num(kd.t_split) +
           " t_max=" + num(kd.t_max) + ", near " + a.name(kd.near_child) + ", far " + a.name(kd.far_child) +
           " (visited: " + (near_taken && far_taken ? "both" : near_taken ? "near only" : far_taken ? "far only" : "none") +
           ")";
  };
  const NodeId dropped = need_near && !near_taken ? kd.near_child : need_far && !far_taken ? kd.far_child : kNoNode;
  if (dropped == kNoNode) return;  // a child taken but not needed is waste: its visit counts as not crossed
  const ExactHit* lost = a.lost_in(dropped);
  const char* cause = "kd_case_drops_child";
  std::string truth;
  const bool case_near = kd.kase != KdCase::FarOnly, case_far = kd.kase != KdCase::NearOnly;
  if (known && (near_taken != case_near || far_taken != case_far)) {
    cause = "kd_wrong_case";
    truth = std::string("its own numbers give case ") + kd_case_name(kd.kase) + ", which " +
            (dropped == kd.near_child ? "takes the near child" : "takes the far child") + "; the ray " +
            (need_near && need_far ? "crosses both children" : need_far ? "is in the far child" : "is in the near child");
  } else if (d == 0.0) {
    cause = "kd_parallel_ray";
    truth = std::string("the ray runs parallel to the plane ") + axis_name(axis) + "=" + num(pos) + " (direction " +
            axis_name(axis) + " = " + (std::signbit(d) ? "-0" : "+0") + "), so it stays in the child holding its origin";
  } else if (true_split <= 0.0 && !near_taken) {
    cause = "kd_plane_behind_origin";
    truth = "the plane " + std::string(axis_name(axis)) + "=" + num(pos) + " lies behind the origin (t_split=" +
            num(true_split) + " <= 0): the ray never crosses it and stays in the near child";
  } else if (std::fabs(double(kd.t_split) - true_split) > 1e-4 * std::max(std::fabs(true_split), 1e-30)) {
    cause = "kd_wrong_t_split";
    truth = "the ray meets the plane " + std::string(axis_name(axis)) + "=" + num(pos) + " at t=" + num(true_split);
  } else if ((d > 0.0) != near_is_lower) {
    cause = "kd_near_far_swapped";
    truth = std::string("the ray runs ") + (d > 0.0 ? "up" : "down") + " the " + axis_name(axis) +
            " axis: the near child is the " + (d > 0.0 ? "lower" : "upper") + " one";
  } else {
    truth = "the ray crosses the plane at t=" + num(true_split) + ", inside [t_min, t_max]: it needs both children";
  }
  if (lost) truth += "; " + a.name(dropped) + " was left out and " + a.lost_text(*lost);
  a.claim(step, cause, said(), truth, lost != nullptr);
}

void audit_far_pop(Audit& a, const KdExitVars& kx, size_t step) {
  if (!kx.exits || kx.far_child >= a.tree_.nodes.size()) return;
  double enter, exit;
  const bool crosses = crossing(a.ray_, a.tree_.nodes[kx.far_child].box, a.pad, enter, exit);
  const bool own_numbers = kx.t_hit < kx.t_split;
  const bool true_claim = !crosses || !clearly_below(enter, a.closest);
  if (own_numbers && true_claim) return;
  const ExactHit* lost = a.lost_in(kx.far_child);
  std::string truth = !own_numbers ? "false by its own numbers: t_hit=" + num(kx.t_hit) + " is not below t_split=" +
                                         num(kx.t_split)
                                   : "the closest hit t=" + num(a.closest) + " lies beyond the far child's start";
  if (crosses) truth += "; the far child " + a.name(kx.far_child) + " is entered at t=" + num(enter);
  if (lost) truth += (crosses ? " and " : "; the far child ") + a.lost_text(*lost);
  a.claim(step, "kd_false_early_exit",
          "t_hit=" + num(kx.t_hit) + " < t_split=" + num(kx.t_split) + ": return (" + a.name(kx.far_child) + " skipped)",
          truth, lost != nullptr);
}

/// A node skipped as missed or as beyond the closest hit (a cull, an octree child's fate).
void audit_skip(Audit& a, NodeId node, CullReason why, float logged_enter, size_t step) {
  if (!a.has_box(node) || why == CullReason::None) return;
  double enter, exit;
  const bool crosses = crossing(a.ray_, a.box(node), a.pad, enter, exit) && exit >= double(a.ray_.tmin);
  const ExactHit* lost = a.lost_in(node);
  const bool beyond = why == CullReason::BeyondClosestHit;
  const bool own_false = beyond && std::isfinite(logged_enter) && logged_enter < a.closest &&
                         clearly_below(logged_enter, a.closest);
  const bool false_claim =
      beyond ? own_false || (crosses && clearly_below(std::max(enter, double(a.ray_.tmin)), a.closest))
             : crosses && clearly_below(std::max(enter, double(a.ray_.tmin)), a.closest);
  if (!false_claim && !lost) return;
  const char* cause = beyond ? "false_cull_beyond" : "false_cull_missed";
  std::string truth;
  if (!beyond && crosses) {
    bool nan_prone = false;
    const Aabb b = a.box(node);
    for (int ax = 0; ax < 3; ++ax)
      if (a.ray_.dir[ax] == 0.0f && (a.ray_.org[ax] == b.min[ax] || a.ray_.org[ax] == b.max[ax])) nan_prone = true;
    if (nan_prone) cause = "slab_nan";
    truth = "the ray crosses its box over [" + num(enter) + ", " + num(exit) + "]";
    if (nan_prone) truth += " (a +-0 direction component with the origin on the box's plane: 0 * inf = NaN)";
  } else if (beyond) {
    truth = own_false ? "false by its own numbers: entry t=" + num(logged_enter) + " is before the closest hit t=" +
                            num(a.closest)
                      : "it is entered at t=" + num(enter) + ", before the closest hit t=" + num(a.closest);
  } else {
    truth = "the ray does not cross its box, but";
  }
  if (lost) truth += "; " + a.lost_text(*lost);
  const std::string said = a.name(node) + " skipped: " + (beyond ? "entry beyond the closest hit" : "missed") +
                           (beyond && std::isfinite(logged_enter) ? " (entry t=" + num(logged_enter) + ")" : "");
  a.claim(step, cause, said, truth, lost != nullptr);
}

void audit_octree(Audit& a, const OctreeOrderVars& ov, size_t step) {
  double prev_enter = -INFINITY;
  NodeId prev = kNoNode;
  for (int i = 0; i < ov.count; ++i) {
    const OctreeOrderVars::Child& c = ov.children[i];
    if (c.node == kNoNode) continue;
    if (c.fate == OctreeOrderVars::Fate::Missed)
      audit_skip(a, c.node, CullReason::MissedBounds, c.t_enter, step);
    else if (c.fate == OctreeOrderVars::Fate::BeyondClosestHit)
      audit_skip(a, c.node, CullReason::BeyondClosestHit, c.t_enter, step);
    if (c.fate != OctreeOrderVars::Fate::Pushed || !a.has_box(c.node)) continue;
    double enter, exit;
    if (!crossing(a.ray_, a.box(c.node), a.pad, enter, exit)) continue;
    enter = std::max(enter, double(a.ray_.tmin));
    if (prev != kNoNode && clearly_below(enter, prev_enter)) {
      const ExactHit* lost = a.lost_in(c.node);
      a.claim(step, "octree_order",
              a.name(prev) + " listed before " + a.name(c.node),
              a.name(c.node) + " is entered at t=" + num(enter) + ", before " + a.name(prev) + " (t=" +
                  num(prev_enter) + ")" + (lost ? "; " + a.lost_text(*lost) : ""),
              lost != nullptr);
    }
    if (enter > prev_enter) prev_enter = enter, prev = c.node;
  }
}

bool face_adjacent(const KitTree& tree, NodeId a, NodeId b) {
  const auto xyz = [&](NodeId c, int out[3]) {
    out[0] = int(c % uint32_t(tree.res[0]));
    out[1] = int((c / uint32_t(tree.res[0])) % uint32_t(tree.res[1]));
    out[2] = int(c / (uint32_t(tree.res[0]) * uint32_t(tree.res[1])));
  };
  int p[3], q[3];
  xyz(a, p), xyz(b, q);
  return std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) == 1;
}

}  // namespace

WalkAudit WalkAuditor::audit(const Ray& ray, std::span<const TraceEvent> events, std::span<const RecordedVars> vars,
                             bool find_lossy) const {
  double final_t = INFINITY;
  if (!events.empty() && events.back().kind == TraceEventKind::Done && events.back().hit)
    final_t = events.back().t0;
  Audit a(tree_, scene_, ray, find_lossy ? all_hits(scene_, ray) : std::vector<ExactHit>{}, final_t);
  a.closest = double(ray.tmax);
  size_t v = 0;
  NodeId current = kNoNode, prev_cell = kNoNode;
  std::vector<size_t> grid_anomalies;  // steps where the grid walk left the ray
  for (size_t i = 0; i < events.size(); ++i) {
    const TraceEvent& e = events[i];
    switch (e.kind) {
      case TraceEventKind::Visit:
      case TraceEventKind::EnterCell: {
        current = e.node;
        ++a.out.visits;
        if (!a.has_box(e.node)) break;
        double enter, exit;
        const double t0 = std::max(double(e.t0), double(ray.tmin)), t1 = e.t1;
        const bool crossed = crossing(ray, a.box(e.node), a.pad, enter, exit) && !clearly_below(t1, t0) &&
                             !clearly_below(exit, t0) && !clearly_below(t1, enter);
        if (!crossed) {
          ++a.out.visits_not_crossed;
          if (e.kind == TraceEventKind::EnterCell) grid_anomalies.push_back(i);
          a.claim(i, e.kind == TraceEventKind::EnterCell ? "grid_cell_skipped" : "unexplained",
                  a.name(e.node) + " visited over [" + num(e.t0) + ", " + num(e.t1) + "]",
                  t1 < t0 ? "an empty interval: the ray is not inside it"
                          : "the ray does not cross it there" +
                                (crossing(ray, a.box(e.node), a.pad, enter, exit)
                                     ? std::string(" (it crosses it over [") + num(enter) + ", " + num(exit) + "])"
                                     : std::string(" (it misses it)")),
                  false);
        }
        if (e.kind == TraceEventKind::EnterCell) {
          if (prev_cell != kNoNode && e.node != kNoNode && !face_adjacent(tree_, prev_cell, e.node))
            grid_anomalies.push_back(i);
          prev_cell = e.node;
        }
        break;
      }
      case TraceEventKind::Cull:
        audit_skip(a, e.node, e.reason, e.t0, i);
        break;
      case TraceEventKind::TestPrim:
        if (e.hit && e.t0 >= ray.tmin) a.closest = std::min(a.closest, double(e.t0));
        break;
      case TraceEventKind::NewClosest:
        a.closest = std::min(a.closest, double(e.t0));
        break;
      default:
        break;
    }
    for (; v < vars.size() && vars[v].event == i; ++v) {
      if (const auto* kd = std::get_if<KdSplitVars>(&vars[v].vars))
        audit_kd_split(a, *kd, current, i, events);
      else if (const auto* kx = std::get_if<KdExitVars>(&vars[v].vars))
        audit_far_pop(a, *kx, i);
      else if (const auto* ov = std::get_if<OctreeOrderVars>(&vars[v].vars))
        audit_octree(a, *ov, i);
    }
  }
  // A grid walk that left the ray (a jump over a corner, a cell it does not cross) loses a
  // hit when a nearer hit lies in a cell the walk never entered.
  if (find_lossy && tree_.grid && !grid_anomalies.empty()) {
    std::vector<uint8_t> entered(tree_.cells.size(), 0);
    for (const TraceEvent& e : events)
      if (e.kind == TraceEventKind::EnterCell && e.node < entered.size()) entered[e.node] = 1;
    for (const ExactHit& h : a.hits_) {
      if (!clearly_below(h.t, final_t)) break;
      bool reached = false, held = false;
      for (NodeId c : a.cells_holding(h.prim, h.point)) held = true, reached |= entered[c] != 0;
      if (!held || reached) continue;
      const size_t s = grid_anomalies.front();
      a.claim(s, "grid_dda_tie", "the walk stepped into " + a.name(events[s].node),
              "it left the ray's path: triangle " + std::to_string(h.prim) + ", hit at t=" + num(h.t) +
                  ", lies in a cell the walk never entered",
              true);
      std::stable_sort(a.out.claims.begin(), a.out.claims.end(),
                       [](const FalseClaim& x, const FalseClaim& y) { return x.step < y.step; });
      break;
    }
  }
  return std::move(a.out);
}

namespace {

/// kd-tree: the final hit lies beyond the t_split of a node whose far child was never visited.
bool kd_hit_beyond_t_split(std::span<const TraceEvent> ev, std::span<const RecordedVars> vars, const Hit& got) {
  if (!got.valid()) return false;
  for (const RecordedVars& rv : vars) {
    const auto* kd = std::get_if<KdSplitVars>(&rv.vars);
    if (!kd || kd->kase != KdCase::Both || !(kd->t_split < got.t)) continue;
    const bool far_visited = std::any_of(ev.begin(), ev.end(), [&](const TraceEvent& e) {
      return e.kind == TraceEventKind::Visit && e.node == kd->far_child;
    });
    if (!far_visited) return true;
  }
  return false;
}

/// Grid: the final hit was taken in a cell it lies beyond, and the walk stopped there.
bool grid_hit_outside_cell(std::span<const TraceEvent> ev, const Hit& got) {
  if (!got.valid()) return false;
  const TraceEvent* cell = nullptr;
  bool found = false;
  for (const TraceEvent& e : ev) {
    if (e.kind == TraceEventKind::EnterCell) {
      if (found) return false;  // the walk went on after the hit: not this trap
      cell = &e;
    }
    if (e.kind == TraceEventKind::NewClosest && e.prim == got.prim) found = true;
  }
  return found && cell && double(got.t) > double(cell->t1) * (1.0 + 1e-6) + 1e-30;
}

/// Hierarchies: the answer is the first leaf's hit and the walk ended right after that leaf
/// although nodes were still pending (or it logs no stack).
bool stopped_at_first_leaf_hit(std::span<const TraceEvent> ev, const Hit& got) {
  const NaiveAnswer naive = naive_first_leaf_hit(ev);
  if (!naive.hit || !got.valid() || naive.prim != got.prim || naive.t != got.t) return false;
  int64_t pending = 0;
  bool pushes = false;
  for (size_t i = 0; i < ev.size(); ++i) {
    const TraceEventKind k = ev[i].kind;
    if (i > naive.stop_step && k != TraceEventKind::Done && k != TraceEventKind::NewClosest &&
        k != TraceEventKind::TestPrim)
      return false;
    if (i <= naive.stop_step && k == TraceEventKind::Push) ++pending, pushes = true;
    if (i <= naive.stop_step && k == TraceEventKind::Pop) --pending;
  }
  return pending > 0 || !pushes;
}

}  // namespace

Diagnosis WalkAuditor::diagnose(const Ray& ray, std::span<const TraceEvent> events,
                                std::span<const RecordedVars> vars, const WalkAudit& audit, const Hit& got,
                                const ReferenceHit& ref) const {
  using K = accelviz::Kind;
  // A wrong turn (a kd-tree case against the geometry) sends the walk off the ray's path
  // with wrong intervals: what it drops later follows from it, so the first wrong turn is
  // the cause even when the hit was lost further down.
  const FalseClaim* lossy = audit.first_lossy();
  const FalseClaim* turn = nullptr;
  for (const FalseClaim& c : audit.claims)
    if (c.cause == "kd_plane_behind_origin" || c.cause == "kd_parallel_ray" || c.cause == "kd_wrong_t_split" ||
        c.cause == "kd_near_far_swapped") {
      turn = &c;
      break;
    }
  if (turn && (!lossy || turn->step < lossy->step))
    return {turn->cause,
            turn->claim + ": " + turn->truth +
                (lossy ? "; the walk never came back to the ray's path (later: " + lossy->claim + ": " + lossy->truth + ")"
                       : "; the walk never came back to the ray's path"),
            turn->step};
  if (lossy) return {lossy->cause, lossy->claim + ": " + lossy->truth, lossy->step};
  const std::string answered =
      got.valid() ? "the answer triangle " + std::to_string(got.prim) + " at t=" + num(got.t) : "the answer a miss";
  // The answer itself is not a hit.
  if (got.valid()) {
    double t;
    if (uint32_t(got.prim) >= scene_.triangle_count() || !exact_hit(scene_, ray, uint32_t(got.prim), t))
      return {"not_a_hit", "triangle " + std::to_string(got.prim) + " is not hit by the ray"};
    if (double(got.t) < double(ray.tmin) || double(got.t) > double(ray.tmax))
      return {"outside_interval", "t=" + num(got.t) + " is outside [" + num(ray.tmin) + ", " + num(ray.tmax) + "]"};
    if (std::fabs(double(got.t) - t) > 1e-4 * std::max(std::fabs(t), 1e-30) + ulp_allowance(scene_))
      return {"wrong_t", "triangle " + std::to_string(got.prim) + " is hit at t=" + num(t) + ", not at t=" + num(got.t)};
  }
  if (!(ref.prim >= 0 && (!got.valid() || double(got.t) > ref.t)))
    return {"unexplained", answered + ", the reference " + (ref.prim < 0 ? std::string("misses") : "triangle " +
                                                                    std::to_string(ref.prim) + " at t=" + num(ref.t))};
  const std::string nearer = "triangle " + std::to_string(ref.prim) + " at t=" + num(ref.t);
  if (!tree_.grid && tree_.nodes.empty())
    return {"nothing_built", "no node was logged; " + answered + ", the reference " + nearer};
  // In no leaf at all: lost at a split when the build handed it to a node that split (the
  // straddle trap), left out from the start otherwise (the skeleton's empty root).
  if (!index().holders.count(uint32_t(ref.prim)) &&
      (index().holders.empty() || !index().has_split || !index().given_to_some_node.count(uint32_t(ref.prim))))
    return {"unreferenced", nearer + " is in no leaf or cell; " + answered};
  if (!got.valid() && std::none_of(events.begin(), events.end(), [](const TraceEvent& e) {
        return e.kind == TraceEventKind::Visit || e.kind == TraceEventKind::EnterCell;
      }))
    return {"nothing_walked", "no visit was logged; the reference " + nearer};
  if (kind_ == K::kdtree && kd_hit_beyond_t_split(events, vars, got))
    return {"kd_hit_beyond_t_split", answered + " lies beyond the t_split of a node whose far child was never visited; "
                                                "the reference " + nearer};
  if (kind_ == K::grid && grid_hit_outside_cell(events, got))
    return {"grid_hit_outside_cell", answered + " lies beyond the cell the walk stopped in; the reference " + nearer};
  if ((kind_ == K::bvh || kind_ == K::spheretree || kind_ == K::octree) && stopped_at_first_leaf_hit(events, got))
    return {"stopped_first_leaf", answered + " is the first leaf's hit, and nodes were still pending; the reference " +
                                      nearer};
  for (size_t i = 0; i < events.size(); ++i)
    if (events[i].kind == TraceEventKind::TestPrim && events[i].prim == ref.prim && events[i].hit)
      return {"nearer_hit_dropped", nearer + " was tested and hit at step " + std::to_string(i) + "; " + answered, i};
  // Where the nearer hit is: in a leaf or cell that holds the triangle, or lost at a split.
  const Index& ix = index();
  const DVec3 p = DVec3(ray.org) + ref.t * DVec3(ray.dir);
  Audit helper(tree_, scene_, ray, {}, INFINITY);
  auto held = ix.holders.find(uint32_t(ref.prim));
  std::vector<uint32_t> holding;  // leaves / cells holding the triangle at the hit point
  if (held != ix.holders.end())
    for (uint32_t n : held->second)
      if (point_in(helper.box(n), p, helper.pad)) holding.push_back(n);
  if (holding.empty() && ix.has_split && kind_ != K::bvh && kind_ != K::spheretree) {
    // Lost at a split: which leaf (or octant with no node) covers the hit point without it?
    std::string where = "no leaf";
    if (tree_.grid) {
      for (uint32_t c = 0; c < tree_.cells.size(); ++c)
        if (point_in(tree_.cell_box(c), p, helper.pad)) {
          where = helper.name(c);
          break;
        }
    } else {
      for (uint32_t n = 0; n < tree_.nodes.size(); ++n)
        if ((tree_.nodes[n].leaf || tree_.nodes[n].children.empty()) && point_in(tree_.nodes[n].box, p, helper.pad)) {
          where = helper.name(n) + " (a leaf)";
          break;
        }
      if (where == "no leaf") where = "no leaf (an octant or child with no node)";
    }
    return {tree_.grid ? "grid_insert_lost" : "straddle_lost",
            nearer + ": its hit point lies in " + where + ", which does not hold it; " + answered};
  }
  if (!holding.empty()) {
    const NodeId n = holding.front();
    if (tree_.grid)
      return {"grid_cell_skipped", nearer + " lies in " + helper.name(n) + ", which the walk never entered; " + answered};
    return {"never_reached", nearer + " lies in " + helper.name(n) + ", never visited nor skipped; " + answered};
  }
  return {"unexplained", nearer + "; " + answered};
}

}  // namespace accel
