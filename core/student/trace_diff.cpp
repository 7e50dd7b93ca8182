#include "student/trace_diff.h"

#include <cmath>
#include <cstdio>

namespace accel {
namespace {

/// One step as the lecture shows it, independent of node ids.
struct Step {
  TraceEventKind kind = TraceEventKind::Done;
  Aabb box;           ///< Visit / EnterCell
  int32_t prim = -1;  ///< TestPrim / NewClosest / Done
  bool hit = false;   ///< TestPrim
  size_t index = 0;   ///< into the recording
};

std::vector<Step> lecture_steps(const Structure& s, const TraceRecorder& rec) {
  std::vector<Step> out;
  const auto& events = rec.events();
  for (size_t i = 0; i < events.size(); ++i) {
    const TraceEvent& e = events[i];
    Step st;
    st.kind = e.kind;
    st.index = i;
    switch (e.kind) {
      case TraceEventKind::Visit:
      case TraceEventKind::EnterCell:
        st.box = s.node_view(e.node).box;
        break;
      case TraceEventKind::TestPrim:
        st.prim = e.prim, st.hit = e.hit;
        break;
      case TraceEventKind::NewClosest:
      case TraceEventKind::Done:
        st.prim = e.prim;
        break;
      default:
        continue;
    }
    out.push_back(st);
  }
  return out;
}

bool same_box(const Aabb& a, const Aabb& b, float tolerance) {
  if (a.empty() || b.empty()) return a.empty() == b.empty();
  return glm::all(glm::lessThanEqual(glm::abs(a.min - b.min), Vec3(tolerance))) &&
         glm::all(glm::lessThanEqual(glm::abs(a.max - b.max), Vec3(tolerance)));
}

bool same_step(const Step& a, const Step& b, float tolerance) {
  if (a.kind != b.kind) {
    // A grid's cell and a tree's node are both "the region entered".
    const bool a_enter = a.kind == TraceEventKind::Visit || a.kind == TraceEventKind::EnterCell;
    const bool b_enter = b.kind == TraceEventKind::Visit || b.kind == TraceEventKind::EnterCell;
    return a_enter && b_enter && same_box(a.box, b.box, tolerance);
  }
  switch (a.kind) {
    case TraceEventKind::Visit:
    case TraceEventKind::EnterCell:
      return same_box(a.box, b.box, tolerance);
    case TraceEventKind::TestPrim:
      return a.prim == b.prim && a.hit == b.hit;
    default:
      return a.prim == b.prim;
  }
}

std::string box_text(const Aabb& b) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "[%.4g %.4g %.4g .. %.4g %.4g %.4g]", double(b.min.x), double(b.min.y),
                double(b.min.z), double(b.max.x), double(b.max.y), double(b.max.z));
  return buf;
}

std::string step_text(const std::vector<Step>& steps, size_t k) {
  if (k >= steps.size()) return "(ended)";
  const Step& s = steps[k];
  switch (s.kind) {
    case TraceEventKind::Visit:
      return "visit box " + box_text(s.box);
    case TraceEventKind::EnterCell:
      return "enter cell " + box_text(s.box);
    case TraceEventKind::TestPrim:
      return "test triangle " + std::to_string(s.prim) + (s.hit ? " (hit)" : " (miss)");
    case TraceEventKind::NewClosest:
      return "closest hit: triangle " + std::to_string(s.prim);
    case TraceEventKind::Done:
      return s.prim >= 0 ? "answer: triangle " + std::to_string(s.prim) : "answer: miss";
    default:
      return "?";
  }
}

std::string hit_text(const Hit& h) {
  if (!h.valid()) return "miss";
  char buf[64];
  std::snprintf(buf, sizeof buf, "triangle %d at t=%.9g", h.prim, double(h.t));
  return buf;
}

std::string verdict_text(HitVerdict v) { return v == HitVerdict::Correct ? "right" : verdict_name(v); }

}  // namespace

std::string TraceDifference::answers_line() const {
  return "yours: " + hit_text(mine_hit) + " (" + verdict_text(mine_verdict) + "); built-in: " + hit_text(builtin_hit) +
         " (" + verdict_text(builtin_verdict) + ")";
}

std::string TraceDifference::difference_line() const {
  if (!differs) return "no difference: every step agrees";
  return "first difference: your step " + std::to_string(mine_step + 1) + ", the built-in's step " +
         std::to_string(builtin_step + 1) + ": yours " + mine_text + " / built-in " + builtin_text;
}

std::vector<std::string> builtin_compare_params(const std::string& peer) {
  if (peer == "bvh") return {"builder=median", "axis=longest", "leaf_size=4", "traversal=ordered", "width=2"};
  if (peer == "spheretree") return {"builder=median", "axis=longest", "leaf_size=4", "traversal=ordered"};
  return {};
}

TraceDifference compare_with_builtin(const Scene& scene, const Ray& ray, const Structure& mine,
                                     const Structure& builtin) {
  TraceDifference d;
  TraceRecorder rm, rb;
  d.mine_hit = mine.intersect_traced(ray, rm);
  d.builtin_hit = builtin.intersect_traced(ray, rb);
  d.reference = reference_closest(scene, ray);
  d.mine_verdict = judge_hit(scene, ray, d.mine_hit, d.reference);
  d.builtin_verdict = judge_hit(scene, ray, d.builtin_hit, d.reference);
  const std::vector<Step> a = lecture_steps(mine, rm), b = lecture_steps(builtin, rb);
  const Vec3 extent = scene.bounds().extent();
  const float tolerance = 1e-5f * std::max({extent.x, extent.y, extent.z, 1e-30f});
  size_t k = 0;
  while (k < a.size() && k < b.size() && same_step(a[k], b[k], tolerance)) ++k;
  if (k == a.size() && k == b.size()) return d;
  d.differs = true;
  d.mine_step = k < a.size() ? a[k].index : rm.events().size() - 1;
  d.builtin_step = k < b.size() ? b[k].index : rb.events().size() - 1;
  d.mine_text = step_text(a, k);
  d.builtin_text = step_text(b, k);
  return d;
}

}  // namespace accel
