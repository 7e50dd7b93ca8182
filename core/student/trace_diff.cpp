#include "student/trace_diff.h"

#include "student/kit_structure.h"
#include "student/walk_audit.h"
#include "student/waste.h"

#include <cmath>
#include <cstdio>

namespace accel {
namespace {

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
  const std::string counts = "; yours tests " + std::to_string(mine_tests) + " triangles, the built-in " +
                             std::to_string(builtin_tests);
  if (!differs) return "no difference in what the walks mean: the same answer" + counts;
  return "first difference: " + mine_text + (builtin_text.empty() ? "" : " / built-in: " + builtin_text) + counts;
}

std::vector<std::string> builtin_compare_params(const std::string& peer, const Structure* mine, const Scene* scene) {
  std::vector<std::string> out;
  if (const auto* kit = dynamic_cast<const KitStructure*>(mine); kit && scene)
    for (const auto& [key, value] : peer_setup_like(kit->tree(), kit->kind(), *scene)) out.push_back(key + "=" + value);
  auto add = [&](const std::string& key, const std::string& value) {
    for (const std::string& kv : out)
      if (kv.rfind(key + "=", 0) == 0) return;
    out.push_back(key + "=" + value);
  };
  if (peer == "bvh" || peer == "spheretree") {
    add("builder", "median");
    add("axis", "longest");
    add("leaf_size", "4");
    add("traversal", "ordered");
    if (peer == "bvh") add("width", "2");
  }
  return out;
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
  const auto& em = rm.events();
  const auto& eb = rb.events();
  auto tested = [](const std::vector<TraceEvent>& ev, int32_t prim) -> size_t {
    for (size_t i = 0; i < ev.size(); ++i)
      if (ev[i].kind == TraceEventKind::TestPrim && ev[i].prim == prim) return i;
    return size_t(-1);
  };
  for (const TraceEvent& e : em) d.mine_tests += e.kind == TraceEventKind::TestPrim;
  for (const TraceEvent& e : eb) d.builtin_tests += e.kind == TraceEventKind::TestPrim;
  d.mine_step = em.empty() ? 0 : em.size() - 1;
  d.builtin_step = eb.empty() ? 0 : eb.size() - 1;

  // 1. The student's walk against the geometry: its first false claim is the bug.
  if (const auto* kit = dynamic_cast<const KitStructure*>(&mine)) {
    const WalkAuditor auditor(kit->tree(), kit->kind(), scene);
    const WalkAudit audit = auditor.audit(ray, em, rm.recorded_vars(), true);
    const FalseClaim* c = audit.first_lossy();
    if (!c && !audit.claims.empty()) c = &audit.claims.front();
    if (c && (c->loses_hit || d.mine_verdict != HitVerdict::Correct)) {
      d.differs = true;
      d.mine_step = c->step;
      d.mine_text = "your step " + std::to_string(c->step + 1) + " claims " + c->claim + " -- false: " + c->truth;
      return d;
    }
  }
  // 2. The nearest hit: tested by one walk and not by the other.
  const int32_t target = d.reference.prim >= 0 ? d.reference.prim : d.builtin_hit.prim;
  if (target >= 0) {
    const size_t in_mine = tested(em, target), in_builtin = tested(eb, target);
    char t[64];
    std::snprintf(t, sizeof t, "%.9g", d.reference.prim >= 0 ? d.reference.t : double(d.builtin_hit.t));
    if (in_mine == size_t(-1) && in_builtin != size_t(-1)) {
      d.differs = true;
      d.builtin_step = in_builtin;
      d.mine_text = "your walk never tests triangle " + std::to_string(target) + " (the nearest hit, t=" + t + ")";
      d.builtin_text = "its step " + std::to_string(in_builtin + 1) + " tests it";
      return d;
    }
    if (in_mine != size_t(-1) && d.mine_hit.prim != d.builtin_hit.prim && d.mine_verdict != HitVerdict::Correct) {
      d.differs = true;
      d.mine_step = in_mine;
      d.mine_text = "your step " + std::to_string(in_mine + 1) + " tests triangle " + std::to_string(target) +
                    " (the nearest hit, t=" + t + "), but your answer is " + hit_text(d.mine_hit);
      return d;
    }
  }
  // 3. The answers themselves.
  if (d.mine_hit.prim != d.builtin_hit.prim &&
      (d.mine_verdict != HitVerdict::Correct || d.builtin_verdict != HitVerdict::Correct)) {
    d.differs = true;
    d.mine_text = "your answer is " + hit_text(d.mine_hit);
    d.builtin_text = hit_text(d.builtin_hit);
  }
  return d;
}

}  // namespace accel
