#include "build_trace.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <ostream>

namespace accel {

const char* build_event_kind_name(BuildEventKind kind) {
  switch (kind) {
    case BuildEventKind::SceneBox: return "scene_box";
    case BuildEventKind::GridResolution: return "grid_resolution";
    case BuildEventKind::GridInsert: return "grid_insert";
    case BuildEventKind::Node: return "node";
    case BuildEventKind::Axis: return "axis";
    case BuildEventKind::Candidates: return "candidates";
    case BuildEventKind::Split: return "split";
    case BuildEventKind::Leaf: return "leaf";
    case BuildEventKind::Subdivide: return "subdivide";
    case BuildEventKind::Merge: return "merge";
    case BuildEventKind::InsertStep: return "insert_step";
    case BuildEventKind::Collapse: return "collapse";
    case BuildEventKind::Replace: return "replace";
    case BuildEventKind::Fit: return "fit";
    case BuildEventKind::Unrecorded: return "unrecorded";
    case BuildEventKind::Done: return "done";
  }
  return "?";
}

const char* leaf_reason_name(LeafReason reason) {
  switch (reason) {
    case LeafReason::FewPrims: return "max primitives";
    case LeafReason::MaxDepth: return "max depth";
    case LeafReason::NoGain: return "no gain";
    case LeafReason::Cluster: return "triangle";
    case LeafReason::NoProgress: return "no progress";
    case LeafReason::BadRefines: return "bad refines";
    case LeafReason::TooThin: return "too thin";
  }
  return "?";
}

std::string BuildTrace::coverage() const {
  if (truncated) return "stopped at the step budget after " + std::to_string(events.size()) + " steps";
  if (max_depth_seen > depth_limit)
    return "recorded to depth " + std::to_string(depth_limit) + " of " + std::to_string(max_depth_seen);
  return "complete";
}

BuildRecorder::BuildRecorder(int depth_limit, size_t budget_bytes) : budget_bytes_(budget_bytes) {
  trace_.depth_limit = depth_limit < 0 ? 0 : depth_limit;
}

BuildEvent* BuildRecorder::add(BuildEventKind kind, uint32_t node) {
  if (trace_.truncated) return nullptr;
  if (trace_.bytes() + sizeof(BuildEvent) > budget_bytes_) {
    trace_.truncated = true;
    return nullptr;
  }
  BuildEvent& e = trace_.events.emplace_back();
  e.kind = kind;
  e.node = node;
  const int d = depth_of(node);
  e.depth = uint16_t(d < 0 ? 0 : d);
  return &e;
}

uint32_t BuildRecorder::add_list(const uint32_t* items, size_t n) {
  const uint32_t first = uint32_t(trace_.lists.size());
  if (n) trace_.lists.insert(trace_.lists.end(), items, items + n);
  return first;
}

void BuildRecorder::scene_box(const Aabb& box) {
  if (BuildEvent* e = add(BuildEventKind::SceneBox, kNoBuildNode)) e->box = box;
}

void BuildRecorder::grid_resolution(const Aabb& grid_box, const double* values, const int* cells) {
  if (BuildEvent* e = add(BuildEventKind::GridResolution, kNoBuildNode)) {
    e->box = grid_box;
    for (int i = 0; i < 4; ++i) e->values[i] = float(values[i]);
    e->a = uint32_t(cells[0]);
    e->b = uint32_t(cells[1]);
    e->count = uint32_t(cells[2]);
  }
}

void BuildRecorder::grid_insert(uint32_t prim, const int* lo, const int* hi, const uint32_t* cells, size_t n) {
  if (trace_.bytes() + n * sizeof(uint32_t) > budget_bytes_) trace_.truncated = true;
  if (BuildEvent* e = add(BuildEventKind::GridInsert, kNoBuildNode)) {
    e->prim = prim;
    for (int i = 0; i < 3; ++i) {
      e->lo[i] = lo[i];
      e->hi[i] = hi[i];
    }
    e->first = add_list(cells, n);
    e->list_count = uint32_t(n);
  }
}

void BuildRecorder::node(uint32_t id, uint32_t parent, int depth, const Aabb& box, const Aabb& centroids,
                         const uint32_t* prims, size_t n) {
  trace_.max_depth_seen = std::max(trace_.max_depth_seen, depth);
  if (trace_.truncated || int64_t(depth) > int64_t(trace_.depth_limit) + 1) return;
  if (parent != kNoBuildNode && !known(parent)) return;
  if (id >= depth_of_.size()) depth_of_.resize(size_t(id) + 1 + depth_of_.size() / 2, -1);
  depth_of_[id] = depth;
  const bool below = depth > trace_.depth_limit;
  if (!below && trace_.bytes() + n * sizeof(uint32_t) > budget_bytes_) trace_.truncated = true;
  if (BuildEvent* e = add(below ? BuildEventKind::Unrecorded : BuildEventKind::Node, id)) {
    e->parent = parent;
    e->box = box;
    e->centroids = centroids;
    e->count = uint32_t(n);
    if (!below) {
      e->first = add_list(prims, n);
      e->list_count = uint32_t(n);
    }
  }
}

void BuildRecorder::axis(uint32_t id, int axis, const Vec3& dir) {
  if (!within_limit(id)) return;
  if (BuildEvent* e = add(BuildEventKind::Axis, id)) {
    e->axis = int8_t(axis);
    e->dir = dir;
  }
}

void BuildRecorder::candidates(uint32_t id, int axis, const SplitCandidate* c, size_t n) {
  if (!within_limit(id)) return;
  if (trace_.bytes() + n * sizeof(SplitCandidate) > budget_bytes_) trace_.truncated = true;
  if (BuildEvent* e = add(BuildEventKind::Candidates, id)) {
    e->axis = int8_t(axis);
    e->first = uint32_t(trace_.candidates.size());
    e->list_count = uint32_t(n);
    trace_.candidates.insert(trace_.candidates.end(), c, c + n);
  }
}

void BuildRecorder::split(uint32_t id, int axis, float pos, float cost, float leaf_cost, uint32_t left,
                          uint32_t right, uint32_t straddling, bool spatial) {
  if (!within_limit(id)) return;
  if (BuildEvent* e = add(BuildEventKind::Split, id)) {
    e->axis = int8_t(axis);
    e->pos = pos;
    e->cost = cost;
    e->values[0] = leaf_cost;
    e->a = left;
    e->b = right;
    e->count = straddling;
    e->values[1] = spatial ? 1.0f : 0.0f;
  }
}

void BuildRecorder::leaf(uint32_t id, LeafReason reason, const uint32_t* prims, size_t n) {
  if (!within_limit(id)) return;
  if (trace_.bytes() + n * sizeof(uint32_t) > budget_bytes_) trace_.truncated = true;
  if (BuildEvent* e = add(BuildEventKind::Leaf, id)) {
    e->reason = reason;
    e->first = add_list(prims, n);
    e->list_count = uint32_t(n);
    e->count = uint32_t(n);
  }
}

void BuildRecorder::subdivide(uint32_t id, const uint32_t* children, uint32_t count) {
  if (!within_limit(id)) return;
  if (BuildEvent* e = add(BuildEventKind::Subdivide, id)) {
    e->first = add_list(children, count);
    e->list_count = count;
  }
}

void BuildRecorder::merge(uint32_t id, uint32_t a, uint32_t b, const Aabb& box, float cost) {
  if (trace_.truncated) return;
  if (id >= depth_of_.size()) depth_of_.resize(size_t(id) + 1 + depth_of_.size() / 2, -1);
  depth_of_[id] = 0;
  if (BuildEvent* e = add(BuildEventKind::Merge, id)) {
    e->a = a;
    e->b = b;
    e->box = box;
    e->cost = cost;
  }
}

void BuildRecorder::insert_step(uint32_t prim, uint32_t at, int depth, const Aabb& grown, const float* costs,
                                int choice) {
  if (!records(depth) || depth > trace_.depth_limit) return;
  if (BuildEvent* e = add(BuildEventKind::InsertStep, at)) {
    e->prim = prim;
    e->box = grown;
    e->depth = uint16_t(depth);
    for (int i = 0; i < 3; ++i) e->values[i] = costs[i];
    e->a = uint32_t(choice);
  }
}

void BuildRecorder::collapse(uint32_t parent, uint32_t child) {
  if (!within_limit(parent) || !within_limit(child)) return;
  if (BuildEvent* e = add(BuildEventKind::Collapse, parent)) e->a = child;
}

void BuildRecorder::replace(uint32_t id, uint32_t old) {
  if (!known(id) || !known(old)) return;
  if (BuildEvent* e = add(BuildEventKind::Replace, id)) e->a = old;
}

void BuildRecorder::fit(uint32_t id, const Aabb& box, const BoundingSphere& sphere) {
  if (!within_limit(id)) return;
  if (BuildEvent* e = add(BuildEventKind::Fit, id)) {
    e->box = box;
    e->sphere = sphere;
  }
}

void BuildRecorder::done(size_t nodes) {
  if (BuildEvent* e = add(BuildEventKind::Done, kNoBuildNode)) e->count = uint32_t(nodes);
}

Result<RecordedSteps> record_within_budget(const std::function<Status(BuildRecorder&)>& record,
                                           int first_depth_limit, size_t budget_bytes) {
  RecordedSteps out;
  int limit = std::max(0, first_depth_limit);
  while (true) {
    BuildRecorder recorder(limit, budget_bytes);
    if (auto done = record(recorder); !done) return done.error();
    BuildTrace trace = recorder.take();
    out.attempts.push_back({limit, trace.truncated, trace.events.size()});
    const bool depthless = std::any_of(trace.events.begin(), trace.events.end(),
                                       [](const BuildEvent& e) { return e.kind == BuildEventKind::Merge; });
    if (!trace.truncated || depthless || limit == 0) {
      out.trace = std::move(trace);
      return out;
    }
    limit = std::min(limit, trace.max_depth_seen) / 2;
  }
}

int recording_first_depth_limit(size_t triangles) {
  if (triangles <= kLargeRecordingTriangles) return std::numeric_limits<int>::max();
  return std::max(1, static_cast<int>(std::ceil(std::log2(static_cast<double>(triangles)))) / 2);
}

// ----------------------------------------------------------------------------
// Text
// ----------------------------------------------------------------------------
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.6g", v);
  return buf;
}

const char* axis_name(int axis) {
  static const char* const kNames[] = {"x", "y", "z", "pca"};
  return axis >= 0 && axis < 4 ? kNames[axis] : "?";
}

}  // namespace

std::string describe_build_event(const BuildTrace& trace, const BuildEvent& e) {
  const std::string node = "node " + std::to_string(e.node);
  switch (e.kind) {
    case BuildEventKind::SceneBox: return "scene box computed";
    case BuildEventKind::GridResolution: {
      // The rule's numbers that apply (NaN: not used by this rule; no lambda: res was given).
      std::string rule = std::isnan(e.values[0]) ? "res given" : "lambda " + num(e.values[0]);
      rule += ", N " + num(e.values[1]);
      if (!std::isnan(e.values[3])) rule += ", cube root " + num(e.values[3]);
      return "grid resolution " + std::to_string(e.a) + "x" + std::to_string(e.b) + "x" + std::to_string(e.count) +
             " (" + rule + ")";
    }
    case BuildEventKind::GridInsert: {
      const uint64_t bbox_cells = uint64_t(e.hi[0] - e.lo[0] + 1) * uint64_t(e.hi[1] - e.lo[1] + 1) *
                                  uint64_t(e.hi[2] - e.lo[2] + 1);
      return "insert triangle " + std::to_string(e.prim) + " into " + std::to_string(e.list_count) + " cells (" +
             std::to_string(bbox_cells) + " under its box)";
    }
    case BuildEventKind::Node:
      return node + " (depth " + std::to_string(e.depth) + ") with " + std::to_string(e.count) + " triangles";
    case BuildEventKind::Axis:
      if (e.axis == 3)
        return node + ": PCA axis (" + num(e.dir.x) + ", " + num(e.dir.y) + ", " + num(e.dir.z) + ")";
      return node + ": split axis " + axis_name(e.axis);
    case BuildEventKind::Candidates: {
      float best = kInf;
      for (uint32_t i = 0; i < e.list_count; ++i) best = std::min(best, trace.candidates_of(e)[i].cost);
      return node + ": " + std::to_string(e.list_count) + " candidate planes on " + axis_name(e.axis) +
             (e.list_count ? ", min C(B) = " + num(best) : std::string());
    }
    case BuildEventKind::Split:
      return std::string(e.values[1] == 1.0f ? "spatial split " : "split ") + node + " on " + axis_name(e.axis) + " at " + num(e.pos) + ": " + std::to_string(e.a) +
             " left, " + std::to_string(e.b) + " right" +
             (e.count ? ", " + std::to_string(e.count) + " both" : std::string()) +
             (std::isnan(e.cost) ? std::string() : ", C(B) = " + num(e.cost) + " (leaf " + num(e.values[0]) + ")");
    case BuildEventKind::Leaf:
      return "leaf " + node + " with " + std::to_string(e.count) + " triangles (" + leaf_reason_name(e.reason) + ")";
    case BuildEventKind::Subdivide:
      return "subdivide " + node + (e.list_count == 4 ? " into 4 quadrants" : " into 8 octants");
    case BuildEventKind::Merge:
      return "merge clusters " + std::to_string(e.a) + " and " + std::to_string(e.b) + " into " + node;
    case BuildEventKind::InsertStep: {
      static const char* const kChoice[] = {"stays here", "goes left", "goes right"};
      return "insert triangle " + std::to_string(e.prim) + " at " + node + ": here " + num(e.values[0]) + ", left " +
             num(e.values[1]) + ", right " + num(e.values[2]) + " -> " + kChoice[e.a < 3 ? e.a : 0];
    }
    case BuildEventKind::Collapse:
      return node + " adopts the children of node " + std::to_string(e.a);
    case BuildEventKind::Replace:
      return "subtree too deep: node " + std::to_string(e.a) + " replaced by the balanced " + node;
    case BuildEventKind::Fit:
      return e.sphere.radius >= 0.0f ? "fit sphere of " + node + ", radius " + num(e.sphere.radius)
                                     : "fit box of " + node;
    case BuildEventKind::Unrecorded:
      return node + " (depth " + std::to_string(e.depth) + ", " + std::to_string(e.count) +
             " triangles): built below the recorded depth";
    case BuildEventKind::Done: return "done: " + std::to_string(e.count) + " nodes";
  }
  return "?";
}

// ----------------------------------------------------------------------------
// JSON lines
// ----------------------------------------------------------------------------
namespace {

void write_num(std::ostream& out, double v) {
  if (!std::isfinite(v)) {
    out << "null";
    return;
  }
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  out << buf;
}

void write_box(std::ostream& out, const char* key, const Aabb& b) {
  out << ",\"" << key << "\":[";
  const float v[6] = {b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z};
  for (int i = 0; i < 6; ++i) {
    if (i) out << ',';
    write_num(out, v[i]);
  }
  out << ']';
}

void write_list(std::ostream& out, const char* key, const uint32_t* items, uint32_t n) {
  out << ",\"" << key << "\":[";
  for (uint32_t i = 0; i < n; ++i) {
    if (i) out << ',';
    out << items[i];
  }
  out << ']';
}

/// `,"key":` and the number.
void write_num_field(std::ostream& out, const char* key, double v) {
  out << ",\"" << key << "\":";
  write_num(out, v);
}

/// `[a,b,...]` of numbers.
void write_nums(std::ostream& out, std::initializer_list<double> values) {
  out << '[';
  for (auto v = values.begin(); v != values.end(); ++v) {
    if (v != values.begin()) out << ',';
    write_num(out, *v);
  }
  out << ']';
}

/// The first line: the trace's size and how much of the build it covers.
void write_header(const BuildTrace& trace, std::ostream& out) {
  out << "{\"steps\":" << trace.events.size() << ",\"coverage\":\"" << trace.coverage() << "\",\"depth_limit\":";
  if (trace.depth_limit == std::numeric_limits<int>::max())
    out << "null";
  else
    out << trace.depth_limit;
  out << ",\"max_depth\":" << trace.max_depth_seen << ",\"truncated\":" << (trace.truncated ? "true" : "false")
      << "}\n";
}

/// A Candidates step's planes: [pos, cost, left, right] each.
void write_candidates(const BuildTrace& trace, const BuildEvent& e, std::ostream& out) {
  out << ",\"axis\":" << int(e.axis) << ",\"planes\":[";
  for (uint32_t i = 0; i < e.list_count; ++i) {
    const SplitCandidate& c = trace.candidates_of(e)[i];
    if (i) out << ',';
    out << '[';
    write_num(out, c.pos);
    out << ',';
    write_num(out, c.cost);
    out << ',' << c.left << ',' << c.right << ']';
  }
  out << ']';
}

/// The fields of one step after its step, kind and node (docs/build-trace.md).
void write_event_fields(const BuildTrace& trace, const BuildEvent& e, std::ostream& out) {
  switch (e.kind) {
    case BuildEventKind::SceneBox: write_box(out, "box", e.box); break;
    case BuildEventKind::GridResolution:
      write_box(out, "box", e.box);
      write_num_field(out, "lambda", e.values[0]);
      write_num_field(out, "n", e.values[1]);
      write_num_field(out, "volume", e.values[2]);
      write_num_field(out, "cube_root", e.values[3]);
      out << ",\"cells\":[" << e.a << ',' << e.b << ',' << e.count << ']';
      break;
    case BuildEventKind::GridInsert:
      out << ",\"prim\":" << e.prim << ",\"bbox_cells\":[" << e.lo[0] << ',' << e.lo[1] << ',' << e.lo[2] << ','
          << e.hi[0] << ',' << e.hi[1] << ',' << e.hi[2] << ']';
      write_list(out, "cells", trace.list(e), e.list_count);
      break;
    case BuildEventKind::Node:
    case BuildEventKind::Unrecorded:
      out << ",\"depth\":" << e.depth;
      if (e.parent != kNoBuildNode) out << ",\"parent\":" << e.parent;
      write_box(out, "box", e.box);
      write_box(out, "centroids", e.centroids);
      out << ",\"count\":" << e.count;
      if (e.kind == BuildEventKind::Node) write_list(out, "prims", trace.list(e), e.list_count);
      break;
    case BuildEventKind::Axis:
      out << ",\"axis\":" << int(e.axis);
      if (e.axis == 3) {
        out << ",\"dir\":";
        write_nums(out, {e.dir.x, e.dir.y, e.dir.z});
      }
      break;
    case BuildEventKind::Candidates: write_candidates(trace, e, out); break;
    case BuildEventKind::Split:
      out << ",\"axis\":" << int(e.axis);
      write_num_field(out, "pos", e.pos);
      write_num_field(out, "cost", e.cost);
      write_num_field(out, "leaf_cost", e.values[0]);
      out << ",\"left\":" << e.a << ",\"right\":" << e.b << ",\"both\":" << e.count;
      if (e.values[1] == 1.0f) out << ",\"spatial\":true";
      break;
    case BuildEventKind::Leaf:
      out << ",\"reason\":\"" << leaf_reason_name(e.reason) << '"';
      write_list(out, "prims", trace.list(e), e.list_count);
      break;
    case BuildEventKind::Subdivide: write_list(out, "children", trace.list(e), e.list_count); break;
    case BuildEventKind::Merge:
      out << ",\"a\":" << e.a << ",\"b\":" << e.b;
      write_box(out, "box", e.box);
      break;
    case BuildEventKind::InsertStep:
      out << ",\"prim\":" << e.prim << ",\"depth\":" << e.depth << ",\"costs\":";
      write_nums(out, {e.values[0], e.values[1], e.values[2]});
      out << ",\"choice\":" << e.a;
      break;
    case BuildEventKind::Collapse: out << ",\"child\":" << e.a; break;
    case BuildEventKind::Replace: out << ",\"replaces\":" << e.a; break;
    case BuildEventKind::Fit:
      write_box(out, "box", e.box);
      if (e.sphere.radius >= 0.0f) {
        out << ",\"sphere\":";
        write_nums(out, {e.sphere.center.x, e.sphere.center.y, e.sphere.center.z, e.sphere.radius});
      }
      break;
    case BuildEventKind::Done: out << ",\"nodes\":" << e.count; break;
  }
}

}  // namespace

void write_build_trace_jsonl(const BuildTrace& trace, std::ostream& out) {
  write_header(trace, out);
  for (size_t k = 0; k < trace.events.size(); ++k) {
    const BuildEvent& e = trace.events[k];
    out << "{\"step\":" << k << ",\"kind\":\"" << build_event_kind_name(e.kind) << '"';
    if (e.node != kNoBuildNode) out << ",\"node\":" << e.node;
    write_event_fields(trace, e, out);
    out << "}\n";
  }
}

}  // namespace accel
