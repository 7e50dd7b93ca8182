#include "student/kit_structure.h"

#include <algorithm>
#include <cmath>
#include <exception>

#include "student/kit_access.h"

namespace accel {
namespace {

using accelviz::Box;
using accelviz::KitAccess;

/// More cells than this is a student's resolution bug, not a grid (2^26 = 64M cells).
constexpr size_t kMaxKitCells = size_t(1) << 26;
/// What the grader keeps of one build log, whatever the student's build does (its worker has a
/// memory limit; the judge that mirrors the log must have one too): nodes, and the triangle
/// references of leaves and cells. A sane structure over the check's scenes (at most ~70,000
/// triangles) stays far below; a runaway split that copies triangles into both children
/// reaches them within seconds.
constexpr size_t kMaxKitNodes = size_t(1) << 21;
constexpr size_t kMaxKitReferences = size_t(1) << 25;
/// The triangles each node was made over are kept for the invariants up to this many in all
/// (the checks then use what was kept).
constexpr size_t kMaxKitMadeOver = size_t(1) << 24;

CullReason to_core(accelviz::Cull why) {
  return why == accelviz::Cull::MissedBounds ? CullReason::MissedBounds : CullReason::BeyondClosestHit;
}

LeafReason to_core(accelviz::LeafWhy why) {
  switch (why) {
    case accelviz::LeafWhy::FewTriangles:
      return LeafReason::FewPrims;
    case accelviz::LeafWhy::MaxDepth:
      return LeafReason::MaxDepth;
    case accelviz::LeafWhy::NoGain:
      return LeafReason::NoGain;
    case accelviz::LeafWhy::NoProgress:
      return LeafReason::NoProgress;
  }
  return LeafReason::FewPrims;
}

std::string stopped_message(size_t calls) {
  return "the build stopped after " + std::to_string(calls) + " build-log calls, where it failed in the check";
}

/// Listens to the student's build log: keeps the tree, forwards to the recorder if any.
class KitBuildListener final : public accelviz::detail::BuildListener {
 public:
  KitBuildListener(KitTree& tree, const Scene& scene, BuildRecorder* recorder, size_t call_limit)
      : tree_(tree), scene_(scene), recorder_(recorder), call_limit_(call_limit) {}

  bool records() const override { return recorder_ != nullptr; }

  void node(uint32_t id, uint32_t parent, int depth, const Box& box, const uint32_t* prims, size_t n) override {
    count_call();
    flush_insert();
    if (tree_.dense_of.count(id)) {
      tree_.problem("node(" + std::to_string(id) + "): a node with this id was made before");
      return;
    }
    const uint32_t dense = uint32_t(tree_.nodes.size());
    KitNode k;
    k.student_id = id;
    k.depth = std::max(0, depth);
    k.box = KitAccess::to_aabb(box);
    k.prim_count = uint32_t(n);
    if (tree_.keep_made_over && made_over_kept_ + n <= kMaxKitMadeOver) {
      k.made_over.assign(prims, prims + n);
      made_over_kept_ += n;
    }
    if (tree_.keep_made_over && tree_.nodes.size() >= kMaxKitNodes)
      throw KitError("the build logged more than " + std::to_string(kMaxKitNodes) +
                     " nodes: a runaway split? (the kit keeps at most that many)");
    if (parent != accelviz::kNoParent) {
      k.parent = tree_.dense(parent);
      if (k.parent == kNoBuildNode)
        tree_.problem("node(" + std::to_string(id) + "): its parent " + std::to_string(parent) + " was never made");
      else
        tree_.nodes[k.parent].children.push_back(dense);
    }
    tree_.dense_of.emplace(id, dense);
    tree_.nodes.push_back(std::move(k));
    if (recorder_ && recorder_->records(depth)) {
      Aabb centroids;
      for (size_t i = 0; i < n; ++i)
        if (prims[i] < scene_.triangle_count()) centroids.extend(scene_.centroid(prims[i]));
      recorder_->node(dense, tree_.nodes[dense].parent, depth, tree_.nodes[dense].box, centroids, prims, n);
    }
  }
  void sphere(uint32_t id, const accelviz::Sphere& s) override {
    count_call();
    KitNode* k = find(id, "sphere");
    if (!k) return;
    k->sphere = BoundingSphere{Vec3(s.center.x, s.center.y, s.center.z), s.radius};
    if (recorder_) recorder_->fit(tree_.dense(id), k->box, k->sphere);
  }
  void split(uint32_t id, int axis, float position, float cost, float leaf_cost, uint32_t left,
             uint32_t right) override {
    count_call();
    KitNode* k = find(id, "split");
    if (!k) return;
    k->split_axis = std::clamp(axis, 0, 2);
    k->split_pos = position;
    if (recorder_) recorder_->split(tree_.dense(id), k->split_axis, position, cost, leaf_cost, left, right, 0);
  }
  void candidates(uint32_t id, int axis, const accelviz::Candidate* c, size_t n) override {
    count_call();
    if (!recorder_ || !find(id, "candidates")) return;
    std::vector<SplitCandidate> out(n);
    for (size_t i = 0; i < n; ++i) out[i] = SplitCandidate{c[i].position, c[i].cost, c[i].left, c[i].right};
    recorder_->candidates(tree_.dense(id), std::clamp(axis, 0, 2), out.data(), out.size());
  }
  void leaf(uint32_t id, const uint32_t* prims, size_t n, accelviz::LeafWhy why) override {
    count_call();
    KitNode* k = find(id, "leaf");
    if (!k) return;
    k->leaf = true;
    k->leaf_why = why;
    count_references(n);
    k->prims.assign(prims, prims + n);
    if (recorder_) recorder_->leaf(tree_.dense(id), to_core(why), prims, n);
  }
  void grid_resolution(const Box& box, int nx, int ny, int nz) override {
    count_call();
    if (nx < 1 || ny < 1 || nz < 1 || size_t(nx) * size_t(ny) * size_t(nz) > kMaxKitCells) {
      tree_.problem("grid_resolution(" + std::to_string(nx) + ", " + std::to_string(ny) + ", " + std::to_string(nz) +
                    "): each count must be at least 1, and at most 2^26 cells in all");
      throw KitError(tree_.problems.back());
    }
    tree_.grid = true;
    tree_.grid_box = KitAccess::to_aabb(box);
    tree_.res[0] = nx, tree_.res[1] = ny, tree_.res[2] = nz;
    tree_.cells.assign(tree_.cell_count(), {});
    if (recorder_) {
      const double n = double(scene_.valid_prims().size());
      const Vec3 e = tree_.grid_box.extent();
      const double volume = double(e.x) * double(e.y) * double(e.z);
      const double values[4] = {0.0, n, volume, std::cbrt(volume)};
      recorder_->grid_resolution(tree_.grid_box, values, tree_.res);
    }
  }
  void cell_filled(int x, int y, int z, uint32_t prim) override {
    count_call();
    const NodeId cell = tree_.cell_index(x, y, z);
    if (cell == kNoNode) {
      tree_.problem("cell_filled(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) +
                    "): no such cell" + (tree_.grid ? "" : " (grid_resolution() was not called)"));
      return;
    }
    count_references(1);
    tree_.cells[cell].push_back(prim);
    if (!recorder_) return;
    if (pending_prim_ != prim) flush_insert();
    pending_prim_ = prim;
    const int c[3] = {x, y, z};
    for (int a = 0; a < 3; ++a) lo_[a] = std::min(lo_[a], c[a]), hi_[a] = std::max(hi_[a], c[a]);
    pending_cells_.push_back(cell);
  }

  /// Ends the build's recording.
  void finish() {
    flush_insert();
    if (recorder_) recorder_->done(tree_.grid ? tree_.cell_count() : tree_.nodes.size());
  }

 private:
  KitNode* find(uint32_t id, const char* call) {
    const uint32_t dense = tree_.dense(id);
    if (dense == kNoBuildNode) {
      tree_.problem(std::string(call) + "(" + std::to_string(id) + "): node " + std::to_string(id) +
                    " was never made (call node() first)");
      return nullptr;
    }
    return &tree_.nodes[dense];
  }
  /// Leaves' and cells' triangle references: bounded in the grader (kMaxKitReferences).
  void count_references(size_t n) {
    references_ += n;
    if (tree_.keep_made_over && references_ > kMaxKitReferences)
      throw KitError("the build logged more than " + std::to_string(kMaxKitReferences) +
                     " triangle references in leaves or cells: a runaway split copying triangles into both "
                     "children? (the kit keeps at most that many)");
  }
  /// Counts one build-log call. A call past the replay's limit stops the build again: the
  /// student's code caught the stop (StopAfterLimit's) and logged on.
  void count_call() {
    if (call_limit_ && tree_.log_calls >= call_limit_) throw KitBuildStopped(stopped_message(call_limit_));
    ++tree_.log_calls;
  }
  /// The grid's construction is recorded per triangle (the lecture's loop): the cells one
  /// triangle was put into, in one step.
  void flush_insert() {
    if (recorder_ && !pending_cells_.empty())
      recorder_->grid_insert(pending_prim_, lo_, hi_, pending_cells_.data(), pending_cells_.size());
    pending_cells_.clear();
    pending_prim_ = kNoBuildNode;
    for (int a = 0; a < 3; ++a) lo_[a] = INT32_MAX, hi_[a] = INT32_MIN;
  }

  KitTree& tree_;
  const Scene& scene_;
  BuildRecorder* recorder_;
  size_t call_limit_;
  size_t made_over_kept_ = 0, references_ = 0;
  uint32_t pending_prim_ = kNoBuildNode;
  int lo_[3] = {INT32_MAX, INT32_MAX, INT32_MAX}, hi_[3] = {INT32_MIN, INT32_MIN, INT32_MIN};
  std::vector<uint32_t> pending_cells_;
};

/// The replay of a failed build (KitStructure::set_build_call_limit): hands each call to the
/// kit's listener, then stops the build right after the limit's call. The check counted the
/// calls heard before the fault, so the student's code between the last of them and the fault
/// (a crash, a runaway allocation) never runs again, in the viewer's own process.
class StopAfterLimit final : public accelviz::detail::BuildListener {
 public:
  StopAfterLimit(KitBuildListener& to, const KitTree& tree, size_t limit) : to_(to), tree_(tree), limit_(limit) {}

  bool records() const override { return to_.records(); }
  void node(uint32_t id, uint32_t parent, int depth, const Box& box, const uint32_t* prims, size_t n) override {
    to_.node(id, parent, depth, box, prims, n);
    stop_at_limit();
  }
  void sphere(uint32_t id, const accelviz::Sphere& s) override {
    to_.sphere(id, s);
    stop_at_limit();
  }
  void split(uint32_t id, int axis, float position, float cost, float leaf_cost, uint32_t left,
             uint32_t right) override {
    to_.split(id, axis, position, cost, leaf_cost, left, right);
    stop_at_limit();
  }
  void candidates(uint32_t id, int axis, const accelviz::Candidate* c, size_t n) override {
    to_.candidates(id, axis, c, n);
    stop_at_limit();
  }
  void leaf(uint32_t id, const uint32_t* prims, size_t n, accelviz::LeafWhy why) override {
    to_.leaf(id, prims, n, why);
    stop_at_limit();
  }
  void grid_resolution(const Box& box, int nx, int ny, int nz) override {
    to_.grid_resolution(box, nx, ny, nz);
    stop_at_limit();
  }
  void cell_filled(int x, int y, int z, uint32_t prim) override {
    to_.cell_filled(x, y, z, prim);
    stop_at_limit();
  }

 private:
  void stop_at_limit() const {
    if (tree_.log_calls >= limit_) throw KitBuildStopped(stopped_message(limit_));
  }

  KitBuildListener& to_;
  const KitTree& tree_;
  size_t limit_;
};

/// Listens to the student's traversal log and hands every step to `Sink` (a TraversalSink:
/// TraceRecorder, StatsSink) as the core's events, with ids made dense; the lecture's
/// variables only to a sink that records them.
template <TraversalSink Sink>
class KitTraversalListener final : public accelviz::detail::TraversalListener {
 public:
  KitTraversalListener(const KitTree& tree, Sink& sink, bool strict) : tree_(tree), sink_(sink), strict_(strict) {}

  void visit(uint32_t node, int depth, float t0, float t1) override {
    const NodeId n = dense(node, "visit");
    step();
    sink_.visit(n, depth, t0, t1);
  }
  void enter_cell(int x, int y, int z, float t0, float t1) override {
    const NodeId cell = tree_.cell_index(x, y, z);
    if (cell == kNoNode && strict_)
      throw KitError("enter_cell(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) +
                     "): no such cell in the grid the build logged");
    step();
    sink_.enter_cell(cell, t0, t1);
  }
  void cull(uint32_t node, int depth, accelviz::Cull why, float t) override {
    const NodeId n = dense(node, "cull");
    step();
    sink_.cull(n, depth, to_core(why), t);
  }
  void push(uint32_t node, int depth, float key) override {
    const NodeId n = dense(node, "push");
    step();
    sink_.push(n, depth, key);
  }
  void pop(uint32_t node, int depth, float key) override {
    const NodeId n = dense(node, "pop");
    step();
    sink_.pop(n, depth, key);
  }
  void triangle_tested(uint32_t prim, bool hit, float t) override {
    step();
    sink_.test_prim(prim, hit, t);
  }
  void new_closest(uint32_t prim, float t) override {
    step();
    sink_.new_closest(prim, t);
  }
  void grid_dda(const int cell[3], const int step_[3], const float t_max[3], const float t_delta[3]) override {
    if constexpr (Sink::kRecords) {
      GridDdaVars v;
      for (int a = 0; a < 3; ++a) {
        v.cell[a] = cell[a], v.step[a] = step_[a], v.t_max[a] = t_max[a], v.t_delta[a] = t_delta[a];
      }
      v.next_axis = v.t_max[0] <= v.t_max[1] && v.t_max[0] <= v.t_max[2] ? 0 : v.t_max[1] <= v.t_max[2] ? 1 : 2;
      sink_.vars(v);
    }
  }
  void kd_split(float t_min, float t_split, float t_max, uint32_t near_child, uint32_t far_child, int axis) override {
    if constexpr (Sink::kRecords) {
      KdSplitVars v;
      v.t_min = t_min, v.t_split = t_split, v.t_max = t_max;
      v.near_child = dense(near_child, "kd_split");
      v.far_child = dense(far_child, "kd_split");
      v.axis = std::clamp(axis, 0, 2);
      v.kase = t_split > t_max ? KdCase::NearOnly : t_split < t_min ? KdCase::FarOnly : KdCase::Both;
      sink_.vars(v);
    }
  }
  void kd_far_pop(float t_hit, float t_split, uint32_t far_child, bool exits) override {
    if constexpr (Sink::kRecords) sink_.vars(KdExitVars{t_hit, t_split, dense(far_child, "kd_far_pop"), exits});
  }
  void octree_children(unsigned mask, const accelviz::OctreeChild* children, int count) override {
    if constexpr (Sink::kRecords) {
      OctreeOrderVars v;
      v.mask = mask & 7u;
      v.count = std::clamp(count, 0, 8);
      for (int i = 0; i < v.count; ++i) {
        const accelviz::OctreeChild& c = children[i];
        OctreeOrderVars::Child& o = v.children[i];
        o.node = c.node == accelviz::kNoParent ? kNoNode : dense(c.node, "octree_children");
        o.octant = uint8_t(c.octant & 7);
        o.fate = OctreeOrderVars::Fate(int(c.fate));
        o.t_enter = c.t_enter, o.t_exit = c.t_exit;
      }
      sink_.vars(v);
    }
  }

 private:
  NodeId dense(uint32_t node, const char* call) const {
    if (tree_.grid) return node;  // a grid's traversal names cells, not nodes
    const uint32_t d = tree_.dense(node);
    if (d == kNoBuildNode && strict_)
      throw KitError(std::string(call) + "(" + std::to_string(node) + "): node " + std::to_string(node) +
                     " was never made by the build log");
    return d == kNoBuildNode ? kNoNode : d;
  }
  void step() {
    if (++steps_ > kKitStepBudget)
      throw KitError("more than " + std::to_string(kKitStepBudget) +
                     " logged steps for one ray: an endless loop? (the step budget of the traversal log)");
  }

  const KitTree& tree_;
  Sink& sink_;
  bool strict_;
  uint64_t steps_ = 0;
};

}  // namespace

}  // namespace accel

namespace accelviz {

void KitAccess::fill_scene(Scene& out, const accel::Scene& scene) {
  const uint32_t n = uint32_t(scene.triangle_count());
  std::vector<Triangle> triangles(n);
  std::vector<unsigned char> degenerate(n);
  for (uint32_t i = 0; i < n; ++i) {
    const accel::Vec3 &a = scene.vertex(i, 0), &b = scene.vertex(i, 1), &c = scene.vertex(i, 2);
    triangles[i] = Triangle{{a.x, a.y, a.z}, {b.x, b.y, b.z}, {c.x, c.y, c.z}};
    degenerate[i] = scene.degenerate(i) ? 1 : 0;
  }
  fill_scene(out, std::move(triangles), std::move(degenerate),
             scene.bounds().empty() ? Box{} : to_box(scene.bounds()), scene.planar());
}

}  // namespace accelviz

namespace accel {

NodeId KitTree::cell_index(int x, int y, int z) const {
  if (!grid || x < 0 || y < 0 || z < 0 || x >= res[0] || y >= res[1] || z >= res[2]) return kNoNode;
  return NodeId(size_t(x) + size_t(res[0]) * (size_t(y) + size_t(res[1]) * size_t(z)));
}

Aabb KitTree::cell_box(NodeId cell) const {
  const int x = int(cell % uint32_t(res[0])), y = int((cell / uint32_t(res[0])) % uint32_t(res[1])),
            z = int(cell / (uint32_t(res[0]) * uint32_t(res[1])));
  const Vec3 size = grid_box.extent() / Vec3(float(res[0]), float(res[1]), float(res[2]));
  Aabb b;
  b.min = grid_box.min + Vec3(float(x), float(y), float(z)) * size;
  b.max = grid_box.min + Vec3(float(x + 1), float(y + 1), float(z + 1)) * size;
  return b;
}

void KitTree::problem(std::string what) {
  if (problems.size() < 8) problems.push_back(std::move(what));
  ++problem_count;
}

KitStructure::KitStructure(std::string name, accelviz::Kind kind, StudentFactory create)
    : name_(std::move(name)), kind_(kind), create_(std::move(create)) {}

Status KitStructure::build_impl(const Scene& scene, const ParamSet&, BuildControl* control, BuildRecorder* recorder) {
  student_.reset();
  scene_ = nullptr;
  tree_ = KitTree{};
  tree_.keep_made_over = strict_;
  build_stopped_ = false;
  if (build_cancelled(control)) return cancelled_error();
  auto student_scene = std::make_unique<accelviz::Scene>();
  KitAccess::fill_scene(*student_scene, scene);
  auto student = create_();
  KitBuildListener listener(tree_, scene, recorder, build_call_limit_);
  StopAfterLimit stopper(listener, tree_, build_call_limit_);
  if (recorder) recorder->scene_box(scene.bounds());
  accelviz::BuildLog log(build_call_limit_ ? static_cast<accelviz::detail::BuildListener*>(&stopper) : &listener);
  try {
    student->build(*student_scene, log);
    listener.finish();
  } catch (const KitBuildStopped& stop) {
    // The replay of a failed build: what was logged up to the fault stays for playback.
    listener.finish();
    build_stopped_ = true;
    return make_error(name_ + ": " + stop.what());
  } catch (const std::exception& e) {
    if (strict_) throw;  // the grader reads the tree made so far (the node being built)
    tree_ = KitTree{};
    return make_error(name_ + ": the student's build threw: " + e.what());
  } catch (...) {
    if (strict_) throw;
    tree_ = KitTree{};
    return make_error(name_ + ": the student's build threw a non-standard exception");
  }
  student_ = std::move(student);
  student_scene_ = std::move(student_scene);
  scene_ = &scene;
  report_progress(control, 1.0);
  return {};
}

Hit KitStructure::run_query(const Ray& ray, accelviz::detail::TraversalListener* listener) const {
  if (!student_) return Hit{};
  const accelviz::Ray r = accelviz::KitAccess::make_ray(ray, kernel_);
  accelviz::TraversalLog log(listener);
  const accelviz::Hit h = student_->intersect(r, log);
  if (h.prim < 0) return Hit{};
  if (uint32_t(h.prim) >= scene_->triangle_count()) {
    if (strict_)
      throw KitError("intersect returned triangle " + std::to_string(h.prim) + ", but the scene has " +
                     std::to_string(scene_->triangle_count()));
    return Hit{};
  }
  return Hit{h.prim, h.t, h.u, h.v};
}

Hit KitStructure::guarded_query(const Ray& ray, accelviz::detail::TraversalListener* listener) const {
  if (strict_) return run_query(ray, listener);
  try {
    return run_query(ray, listener);
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(error_mutex_);
    last_error_ = name_ + ": the student's intersect threw: " + e.what();
  } catch (...) {
    std::lock_guard<std::mutex> lock(error_mutex_);
    last_error_ = name_ + ": the student's intersect threw a non-standard exception";
  }
  return Hit{};
}

std::string KitStructure::last_error() const {
  std::lock_guard<std::mutex> lock(error_mutex_);
  return last_error_;
}

Hit KitStructure::intersect(const Ray& ray, QueryStats* stats) const {
  if (!stats) return guarded_query(ray, nullptr);  // the fast path: nobody listens
  StatsSink sink;
  KitTraversalListener<StatsSink> listener(tree_, sink, strict_);
  const Hit hit = guarded_query(ray, &listener);
  *stats = sink.stats;
  return hit;
}

Hit KitStructure::intersect_traced(const Ray& ray, TraceRecorder& recorder) const {
  KitTraversalListener<TraceRecorder> listener(tree_, recorder, strict_);
  const Hit hit = guarded_query(ray, &listener);
  recorder.done(hit);
  return hit;
}

void KitStructure::for_each_node(const std::function<void(const NodeView&)>& fn) const {
  if (tree_.grid) {
    for (NodeId c = 0; c < tree_.cells.size(); ++c)
      if (!tree_.cells[c].empty()) fn(node_view(c));
    return;
  }
  for (NodeId id = 0; id < tree_.nodes.size(); ++id) fn(node_view(id));
}

NodeView KitStructure::node_view(NodeId id) const {
  NodeView v;
  if (tree_.grid) {
    if (id >= tree_.cells.size()) return v;
    v.id = id;
    v.leaf = true;
    v.prim_count = uint32_t(tree_.cells[id].size());
    v.box = tree_.cell_box(id);
    return v;
  }
  if (id >= tree_.nodes.size()) return v;
  const KitNode& k = tree_.nodes[id];
  v.id = id;
  v.depth = k.depth;
  v.leaf = k.leaf || k.children.empty();
  v.prim_count = k.leaf ? uint32_t(k.prims.size()) : k.prim_count;
  v.box = k.box;
  v.sphere = k.sphere;
  if (kind_ == accelviz::Kind::kdtree && !v.leaf) {
    v.split_axis = k.split_axis;
    v.split_pos = k.split_pos;
  }
  return v;
}

std::vector<uint32_t> KitStructure::node_prims(NodeId id) const {
  if (tree_.grid) return id < tree_.cells.size() ? tree_.cells[id] : std::vector<uint32_t>{};
  return id < tree_.nodes.size() ? tree_.nodes[id].prims : std::vector<uint32_t>{};
}

std::vector<NodeId> KitStructure::node_children(NodeId id) const {
  if (tree_.grid || id >= tree_.nodes.size()) return {};
  return tree_.nodes[id].children;
}

BuildStats KitStructure::compute_stats() const {
  BuildStats s;
  if (!scene_) return s;
  s.prims = scene_->valid_prims().size();
  if (tree_.grid) {
    s.nodes = tree_.cell_count();
    for (const auto& cell : tree_.cells) {
      s.add_leaf(cell.size());
      s.prim_references += cell.size();
    }
    s.memory_bytes = s.nodes * sizeof(uint32_t) * 2 + s.prim_references * sizeof(uint32_t);
    s.extra.push_back({"cells", std::to_string(tree_.res[0]) + "x" + std::to_string(tree_.res[1]) + "x" +
                                    std::to_string(tree_.res[2])});
  } else {
    s.nodes = tree_.nodes.size();
    // The SAH cost of the tree as logged (ct = ci = 1, areas relative to the root's).
    const double root_area = tree_.nodes.empty() ? 0.0 : double(tree_.nodes[0].box.area());
    double cost = 0.0;
    for (const KitNode& k : tree_.nodes) {
      s.max_depth = std::max(s.max_depth, k.depth);
      const double w = root_area > 0.0 ? double(k.box.area()) / root_area : 0.0;
      if (k.leaf || k.children.empty()) {
        s.add_leaf(k.prims.size());
        s.prim_references += k.prims.size();
        cost += w * double(k.prims.size());
      } else {
        cost += w;
      }
    }
    if (root_area > 0.0) s.sah_cost = cost, s.sah_ct = 1.0, s.sah_ci = 1.0;
    s.memory_bytes = s.nodes * 32 + s.prim_references * sizeof(uint32_t);
  }
  s.extra.push_back({"student", "yes (memory: the kit's estimate, 32 bytes a node)"});
  if (tree_.problem_count)
    s.extra.push_back({"build log problems", std::to_string(tree_.problem_count) + ", first: " + tree_.problems[0]});
  return s;
}

}  // namespace accel
