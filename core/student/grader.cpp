#include "student/grader.h"

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <thread>

#include "batch.h"
#include "check_suites.h"
#include "parallel.h"
#include "ray_gen.h"
#include "rays_io.h"
#include "student/kit_structure.h"
#include "student/walk_audit.h"

namespace accel {
namespace {

/// One case of the suites: made on demand (the meshes are loaded only when reached).
struct CaseSpec {
  std::string category, name;
  std::function<Result<HardCase>()> make;
};

size_t scaled(size_t n, double scale) { return std::max<size_t>(1, size_t(double(n) * scale)); }

/// Random rays through the scene box and primary rays of its default camera.
std::vector<Ray> scene_rays(const Scene& scene, size_t random, int side, uint64_t seed) {
  std::vector<Ray> rays = random_rays(scene.bounds(), random, seed, scene.planar());
  if (!scene.planar() && !scene.bounds().empty()) {
    const auto primary = primary_rays(default_camera(scene.bounds()), side, side * 3 / 4);
    rays.insert(rays.end(), primary.begin(), primary.end());
  }
  return rays;
}

std::vector<CaseSpec> case_specs(const CheckOptions& o) {
  std::vector<CaseSpec> specs;
  const double k = o.ray_scale;
  const int side = std::max(8, int(120.0 * std::sqrt(k)));
  for (const std::string& name : procedural_scene_names(false))
    specs.push_back({"procedural", name, [name, k, side]() -> Result<HardCase> {
                       auto scene = make_procedural_scene(name);
                       if (!scene) return scene.error();
                       auto rays = scene_rays(scene.value(), scaled(20000, k), side, 1);
                       return HardCase{name, std::move(scene.value()), std::move(rays)};
                     }});
  for (const std::string& name : edge_scene_names())
    specs.push_back({"edge", name, [name, k]() -> Result<HardCase> {
                       Scene s = edge_scene(name);
                       auto rays = scene_rays(s, scaled(5000, k), 40, 2);
                       return HardCase{name, std::move(s), std::move(rays)};
                     }});
  specs.push_back({"edge", "empty", [k]() -> Result<HardCase> {
                     return HardCase{"empty", Scene{}, random_rays(Aabb{Vec3(-1), Vec3(1)}, scaled(200, k), 3)};
                   }});
  specs.push_back(
      {"edge", "all_degenerate", [k]() -> Result<HardCase> {
         Scene flat({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}, {0, 0, 1}}, "all_degenerate");
         return HardCase{"all_degenerate", std::move(flat), random_rays(Aabb{Vec3(-1), Vec3(3)}, scaled(200, k), 4)};
       }});
  // The hard cases: every one of core/check_suites.h, generated once, handed out one by one
  // (every step-th ray kept, in order, at a ray scale below 1).
  auto hard = std::make_shared<std::vector<HardCase>>(hard_cases());
  for (size_t h = 0; h < hard->size(); ++h)
    specs.push_back({"hard", (*hard)[h].name, [hard, h, k]() -> Result<HardCase> {
                       HardCase c = std::move((*hard)[h]);
                       if (k < 1.0) {
                         const size_t step = std::max<size_t>(1, size_t(1.0 / k));
                         std::vector<Ray> kept;
                         for (size_t i = 0; i < c.rays.size(); i += step) kept.push_back(c.rays[i]);
                         c.rays = std::move(kept);
                       }
                       return c;
                     }});
  if (!o.shared_scenes.empty() && std::filesystem::is_directory(o.shared_scenes))
    for (const char* file : {"cornell_box.obj", "teapot.obj", "bunny_lowres.obj"}) {
      const std::string path = o.shared_scenes + "/" + file;
      if (!std::filesystem::exists(path)) continue;
      specs.push_back({"meshes", file, [path, file, k, side]() -> Result<HardCase> {
                         auto scene = load_obj(path);
                         if (!scene) return scene.error();
                         auto rays = scene_rays(scene.value(), scaled(20000, k), side, 5);
                         return HardCase{file, std::move(scene.value()), std::move(rays)};
                       }});
    }
  return specs;
}

// --- invariants of the logs ----------------------------------------------------------------

/// The grader's query modes of a remote student (worker_protocol.h's kTraced, kFast): each
/// ray listened to, then on the fast path.
constexpr uint8_t wire_traced = 1, wire_fast = 2;

/// Faults (exceptions, kit errors) of one case before its other rays are skipped, and cases
/// with faults before the others are: enough to see the bug, soon enough to see it.
constexpr size_t kFaultsPerCase = 3;
constexpr size_t kFaultyCases = 3;

enum Inv { kReferenced, kNested, kContains, kReported, kListening, kLogSane, kInvCount };

std::vector<CheckInvariant> invariant_rows(accelviz::Kind kind) {
  using K = accelviz::Kind;
  std::vector<CheckInvariant> rows(kInvCount);
  rows[kReferenced].name = "every triangle is referenced";
  rows[kNested].name = "children lie within their parents";
  rows[kNested].applies = kind == K::octree || kind == K::kdtree || kind == K::bvh;
  rows[kContains].name = "every box or sphere contains its triangles";
  rows[kContains].applies = kind == K::bvh || kind == K::spheretree;
  rows[kReported].name = "the returned hit was logged by triangle_tested";
  rows[kListening].name = "the answers with and without a log listening are equal";
  rows[kLogSane].name = "the build log names only nodes it made";
  return rows;
}

void fail(CheckInvariant& inv, const std::string& where, const std::string& what) {
  if (inv.failed++ == 0) inv.first_failure = where + ": " + what;
}

void check_tree(std::vector<CheckInvariant>& inv, const KitStructure& s, const Scene& scene, const std::string& where) {
  const KitTree& tree = s.tree();
  // Every non-degenerate triangle in some leaf or cell.
  std::vector<uint8_t> seen(scene.triangle_count(), 0);
  if (tree.grid) {
    for (const auto& cell : tree.cells)
      for (uint32_t p : cell)
        if (p < seen.size()) seen[p] = 1;
  } else {
    for (const KitNode& k : tree.nodes)
      for (uint32_t p : k.prims)
        if (p < seen.size()) seen[p] = 1;
  }
  ++inv[kReferenced].checked;
  size_t missing = 0;
  uint32_t first_missing = 0;
  for (uint32_t p : scene.valid_prims())
    if (!seen[p] && missing++ == 0) first_missing = p;
  if (missing)
    fail(inv[kReferenced], where,
         std::to_string(missing) + " triangles in no leaf or cell, the first: triangle " +
             std::to_string(first_missing));

  ++inv[kLogSane].checked;
  if (tree.problem_count) fail(inv[kLogSane], where, tree.problems[0]);

  if (tree.grid) return;
  for (uint32_t id = 0; id < tree.nodes.size(); ++id) {
    const KitNode& k = tree.nodes[id];
    const std::string node = "node " + std::to_string(k.student_id);
    if (inv[kNested].applies && k.parent != kNoBuildNode) {
      ++inv[kNested].checked;
      const Aabb& pb = tree.nodes[k.parent].box;
      const Vec3 pad = 1e-6f * (pb.max - pb.min);
      if (!k.box.empty() &&
          (glm::any(glm::lessThan(k.box.min, pb.min - pad)) || glm::any(glm::greaterThan(k.box.max, pb.max + pad))))
        fail(inv[kNested], where,
             node + "'s box is not inside its parent's (node " + std::to_string(tree.nodes[k.parent].student_id) + ")");
    }
    if (inv[kContains].applies) {
      ++inv[kContains].checked;
      const bool sphere = s.kind() == accelviz::Kind::spheretree;
      for (uint32_t p : k.made_over) {
        if (p >= scene.triangle_count() || scene.degenerate(p)) continue;
        bool inside = true;
        for (int v = 0; v < 3 && inside; ++v) {
          const Vec3 x = scene.vertex(p, v);
          if (sphere) {
            const double d = glm::length(DVec3(x) - DVec3(k.sphere.center));
            inside = k.sphere.radius >= 0.0f && d <= double(k.sphere.radius) * (1.0 + 1e-5) + 1e-6;
          } else {
            inside = glm::all(glm::greaterThanEqual(x, k.box.min)) && glm::all(glm::lessThanEqual(x, k.box.max));
          }
        }
        if (!inside) {
          fail(inv[kContains], where,
               node + "'s " + (sphere ? "sphere" : "box") + " does not contain triangle " + std::to_string(p));
          break;
        }
      }
    }
  }
}

/// The returned hit appears as a hitting triangle test at the same t.
bool hit_was_reported(const TraceRecorder& rec, const Hit& h) {
  if (!h.valid()) return true;
  for (const TraceEvent& e : rec.events())
    if (e.kind == TraceEventKind::TestPrim && e.hit && e.prim == h.prim && e.t0 == h.t) return true;
  return false;
}

std::string describe_exception(const std::exception& e) {
  return dynamic_cast<const KitError*>(&e) ? std::string(e.what()) : std::string("threw: ") + e.what();
}

// --- speed ----------------------------------------------------------------------------------

double best_seconds(const Structure& s, const std::vector<Ray>& rays) {
  double best = std::numeric_limits<double>::infinity();
  for (int run = 0; run < 3; ++run) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto hits = trace_all(s, rays);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, dt);
    (void)hits;
  }
  return best;
}

/// The student's rays per second, nodes and triangles per ray, for a structure whose code
/// runs in a worker process: the worker answers the whole batch on every core, timed from
/// the request to the answers, and its answers must be the right ones (a fast wrong answer
/// says nothing). The counts come from its traversal log over the first rays.
Status time_remote(RemoteAnswers& remote, KitStructure& mine, const Structure& peer, const std::vector<Ray>& rays,
                   const Scene& scene, CheckSpeed& sp) {
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<Hit> answers;
  double best = std::numeric_limits<double>::infinity();
  for (int run = 0; run < 3; ++run) best = std::min(best, remote.time_rays(rays, mine.kernel(), threads, &answers));
  const std::vector<Hit> right = trace_all(peer, rays);
  size_t wrong = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    if (answers[i].prim == right[i].prim && answers[i].t == right[i].t) continue;
    if (answers[i].prim >= int64_t(scene.triangle_count()) || answers[i].prim < -1) {  // not a triangle at all
      ++wrong;
      continue;
    }
    if (judge_hit(scene, rays[i], answers[i], reference_closest(scene, rays[i])) != HitVerdict::Correct) ++wrong;
  }
  if (wrong)
    return make_error(std::to_string(wrong) + " of the " + std::to_string(rays.size()) +
                      " timed answers were wrong: a wrong answer's time says nothing");
  sp.mrays = double(rays.size()) / best * 1e-6;
  const std::vector<Ray> counted(rays.begin(), rays.begin() + std::min<size_t>(rays.size(), 20000));
  remote.expect(counted, mine.kernel(), wire_traced);
  QueryStats total;
  for (const Ray& r : counted) {
    QueryStats q;
    mine.intersect(r, &q);
    total.nodes_visited += q.nodes_visited, total.prims_tested += q.prims_tested;
  }
  QueryStats q_peer;
  trace_all(peer, counted, 0, &q_peer);
  const double n = double(counted.size());
  sp.nodes = double(total.nodes_visited) / n, sp.peer_nodes = double(q_peer.nodes_visited) / n;
  sp.tris = double(total.prims_tested) / n, sp.peer_tris = double(q_peer.prims_tested) / n;
  return {};
}

CheckSpeed time_structure(const StructureInfo& info, const CheckOptions& o, const CheckProgress& progress) {
  CheckSpeed sp;
#if !defined(__OPTIMIZE__)
  sp.why_not = "accelviz itself was compiled without optimisation: build it in Release (scripts/build.sh)";
  return sp;
#endif
  if (!info.optimized) {
    sp.why_not = info.source_file +
                 " was compiled without optimisation (or with a sanitizer): its time would say nothing of the "
                 "algorithm. Build with scripts/run.sh --student DIR (a Release build) to be timed";
    return sp;
  }
  progress("speed/stadium", 0);
  auto scene = make_procedural_scene("stadium");
  auto peer_info = find_structure(info.builtin_peer);
  if (!scene || !peer_info) {
    sp.why_not = "no timing scene";
    return sp;
  }
  const std::vector<Ray> rays = random_rays(scene.value().bounds(), scaled(200000, o.ray_scale), 21);
  sp.workload = "procedural:stadium, " + std::to_string(rays.size()) + " random rays, every core";
  auto mine = build_structure(info, scene.value(), ParamSet(info.params, info.name));
  auto peer =
      build_structure(*peer_info.value(), scene.value(), ParamSet(peer_info.value()->params, info.builtin_peer));
  if (!mine || !peer) {
    sp.why_not = !mine ? mine.error().message : peer.error().message;
    return sp;
  }
  const double n = double(rays.size());
  sp.peer_mrays = n / best_seconds(*peer.value(), rays) * 1e-6;
  auto* kit = dynamic_cast<KitStructure*>(mine.value().get());
  if (auto* remote = kit ? dynamic_cast<RemoteAnswers*>(kit->student()) : nullptr) {
    if (auto timed = time_remote(*remote, *kit, *peer.value(), rays, scene.value(), sp); !timed) {
      sp.why_not = timed.error().message;
      return sp;
    }
    sp.timed = true;
    return sp;
  }
  sp.mrays = n / best_seconds(*mine.value(), rays) * 1e-6;
  QueryStats q_mine, q_peer;
  trace_all(*mine.value(), rays, 0, &q_mine);
  trace_all(*peer.value(), rays, 0, &q_peer);
  sp.nodes = double(q_mine.nodes_visited) / n, sp.peer_nodes = double(q_peer.nodes_visited) / n;
  sp.tris = double(q_mine.prims_tested) / n, sp.peer_tris = double(q_peer.prims_tested) / n;
  sp.timed = true;
  return sp;
}

}  // namespace

size_t CheckReport::rays() const {
  size_t n = 0;
  for (const auto& c : categories) n += c.rays;
  return n;
}
size_t CheckReport::wrong() const {
  size_t n = 0;
  for (const auto& c : categories) n += c.wrong_total();
  return n;
}
size_t CheckReport::invariant_failures() const {
  size_t n = 0;
  for (const auto& i : invariants) n += i.applies ? i.failed : 0;
  return n;
}

namespace {

/// The wrong rays of every cause while the check runs: counts per case, and the first ray of
/// each case kept as a candidate example.
struct CauseBook {
  struct Entry {
    size_t rays = 0;
    std::vector<std::pair<std::string, size_t>> cases;  // in the order met
    std::vector<WrongRay> firsts;                       // the first ray of each case (bounded)
  };
  std::vector<std::pair<std::string, Entry>> entries;

  void add(WrongRay w) {
    auto it = std::find_if(entries.begin(), entries.end(), [&](const auto& e) { return e.first == w.cause; });
    if (it == entries.end()) it = entries.insert(entries.end(), {w.cause, Entry{}});
    Entry& e = it->second;
    ++e.rays;
    const std::string where = w.category + "/" + w.case_name;
    auto c = std::find_if(e.cases.begin(), e.cases.end(), [&](const auto& p) { return p.first == where; });
    if (c == e.cases.end()) {
      e.cases.push_back({where, 0});
      c = e.cases.end() - 1;
      if (e.firsts.size() < 64) e.firsts.push_back(std::move(w));
    }
    ++c->second;
  }
  /// The causes, the most rays first; the examples from the cases with the most rays.
  std::vector<CheckCause> causes(size_t per_cause) const {
    std::vector<CheckCause> out;
    for (const auto& [id, e] : entries) {
      CheckCause c{id, e.rays, e.cases, {}};
      std::stable_sort(c.cases.begin(), c.cases.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
      for (const auto& [where, n] : c.cases) {
        if (c.examples.size() == per_cause) break;
        for (const WrongRay& w : e.firsts)
          if (w.category + "/" + w.case_name == where) c.examples.push_back(w);
      }
      out.push_back(std::move(c));
    }
    std::stable_sort(out.begin(), out.end(), [](const CheckCause& a, const CheckCause& b) { return a.rays > b.rays; });
    return out;
  }
};

CheckCategory& category_of(CheckReport& report, const std::string& name) {
  auto cat = std::find_if(report.categories.begin(), report.categories.end(),
                          [&](const CheckCategory& c) { return c.name == name; });
  if (cat != report.categories.end()) return *cat;
  report.categories.push_back({name});
  return report.categories.back();
}

/// What the build had made when it failed: the last node, its depth and triangles, and how
/// the triangle counts grew on the way down to it (a runaway split copies them).
std::string build_fault_node(const KitTree& tree) {
  if (tree.grid) return "after " + std::to_string(tree.cells.size()) + " cells were made";
  if (tree.nodes.empty()) return "before its first node() call";
  const KitNode& last = tree.nodes.back();
  std::vector<uint32_t> path;
  for (uint32_t n = uint32_t(tree.nodes.size() - 1); n != kNoBuildNode && path.size() < 64; n = tree.nodes[n].parent)
    path.push_back(tree.nodes[n].prim_count);
  std::reverse(path.begin(), path.end());
  // The path from the root: its first three and last four counts.
  std::string growth;
  for (size_t i = 0; i < path.size(); ++i) {
    if (path.size() > 7 && i == 3) {
      growth += " -> ...";
      i = path.size() - 4;
    }
    growth += (growth.empty() ? "" : " -> ") + std::to_string(path[i]);
  }
  double refs = 0;
  for (const KitNode& k : tree.nodes) refs += double(k.prim_count);
  const double root = tree.nodes.front().prim_count;
  char total[160];
  std::snprintf(total, sizeof total, "%zu nodes made so far, over %.3g triangles in all (%.3gx the root's %.0f)",
                tree.nodes.size(), refs, root > 0 ? refs / root : 0.0, root);
  return "at node " + std::to_string(last.student_id) + " (depth " + std::to_string(last.depth) + ", " +
         std::to_string(last.prim_count) + " triangles; the counts down its path: " + growth + "); " + total;
}

/// Counts the built-in's triangles and nodes per ray over `rays`, set up like the student's
/// tree, and both trees' leaves and references: the waste report's comparison.
void tally_peer(const StructureInfo& info, accelviz::Kind kind, const KitStructure& kit, const Scene& scene,
                const std::vector<Ray>& rays, WasteTally& tally) {
  auto peer_info = find_structure(info.builtin_peer);
  if (!peer_info) return;
  ParamSet params(peer_info.value()->params, info.builtin_peer);
  std::string setup;
  for (const auto& [key, value] : peer_setup_like(kit.tree(), kind, scene))
    if (params.set(key, value)) setup += (setup.empty() ? "" : " ") + key + "=" + value;
  auto peer = build_structure(*peer_info.value(), scene, params);
  if (!peer) return;
  QueryStats q;
  trace_all(*peer.value(), rays, 0, &q);
  tally.peer_tris += double(q.prims_tested);
  tally.peer_setup = setup;
  const BuildStats mine = kit.build_stats(), theirs = peer.value()->build_stats();
  tally.leaves += double(mine.leaves - mine.empty_leaves), tally.leaf_refs += double(mine.prim_references);
  tally.peer_leaves += double(theirs.leaves - theirs.empty_leaves), tally.peer_leaf_refs += double(theirs.prim_references);
  tally.refs += double(mine.prim_references), tally.peer_refs += double(theirs.prim_references);
  tally.prims += double(scene.valid_prims().size());
}

/// Counts a case as faulty when it added a fault, whichever way it ends.
struct CaseFaults {
  size_t& cases;
  const std::vector<std::string>& faults;
  size_t before;
  ~CaseFaults() { cases += faults.size() > before; }
};

/// The invariants of one answer: the same with and without a listener, and the returned hit
/// logged by a hitting triangle test.
void check_answers(std::vector<CheckInvariant>& inv, const std::string& where, const Hit& fast, const Hit& traced,
                   const TraceRecorder& rec) {
  CheckInvariant& listening = inv[kListening];
  ++listening.checked;
  if (fast.prim != traced.prim || !(fast.t == traced.t || (std::isnan(fast.t) && std::isnan(traced.t))))
    fail(listening, where,
         "without a listener prim " + std::to_string(fast.prim) + ", with one prim " + std::to_string(traced.prim));
  CheckInvariant& reported = inv[kReported];
  ++reported.checked;
  if (!rec.truncated() && !hit_was_reported(rec, traced))
    fail(reported, where,
         "triangle " + std::to_string(traced.prim) + " returned without a triangle_tested(hit) at its t");
}

/// One right walk's waste: visits, visits where the ray is not, kd cases, triangle tests.
void tally_walk(WasteTally& t, const WalkAudit& audit, const TraceRecorder& rec) {
  ++t.rays;
  t.visits += audit.visits, t.uncrossed += audit.visits_not_crossed;
  t.kd_inner += audit.kd_inner, t.kd_far_only += audit.kd_far_only;
  t.kd_needs_far_only += audit.kd_needs_far_only;
  for (const TraceEvent& e : rec.events()) t.tris += e.kind == TraceEventKind::TestPrim;
}

/// Builds the student's structure over the case's scene: false (with a fault and a build
/// replay) when the build failed; a lost worker goes through, its build replay recorded.
bool build_case(const CaseSpec& spec, const StructureInfo& info, const std::shared_ptr<const Scene>& scene,
                KitStructure& kit, CheckReport& report) {
  std::string build_fault;
  try {
    auto built = kit.build(*scene, ParamSet(info.params, info.name));
    if (!built) build_fault = "build: " + built.error().message;
  } catch (const StudentProcessLost& lost) {
    report.build_faults.push_back({spec.category, spec.name, scene, lost.what(), build_fault_node(kit.tree()),
                                   kit.build_log_calls()});
    throw;
  } catch (const std::exception& e) {
    build_fault =
        dynamic_cast<const KitError*>(&e) ? "build: " + std::string(e.what()) : "build " + describe_exception(e);
  } catch (...) {
    build_fault = "build threw a non-standard exception";
  }
  if (build_fault.empty()) return true;
  const std::string node = build_fault_node(kit.tree());
  report.faults.push_back(spec.category + "/" + spec.name + ": " + build_fault + ", " + node);
  report.build_faults.push_back({spec.category, spec.name, scene, build_fault, node, kit.build_log_calls()});
  return false;
}

/// One case: builds the student's structure over its scene and judges every ray, adding to
/// `report`; every wrong ray's cause goes to `book`, the procedural cases' waste to `tally`.
/// `at` follows where it is ("hard/slivers ray 12"); a StudentProcessLost goes through to
/// the caller, every other student failure becomes a fault.
void check_case(const CaseSpec& spec, const StructureInfo& info, accelviz::Kind kind,
                const CheckProgress& progress, CheckReport& report, CauseBook& book, WasteTally& tally,
                size_t& cases_with_faults, std::string& at) {
  CaseFaults case_faults{cases_with_faults, report.faults, report.faults.size()};
  const std::string where = spec.category + "/" + spec.name;
  progress(where, 0);
  auto made = spec.make();
  if (!made) {
    report.faults.push_back(where + ": " + made.error().message);
    return;
  }
  auto scene = std::make_shared<const Scene>(std::move(made.value().scene));
  const std::vector<Ray>& rays = made.value().rays;
  CheckCategory& cat = category_of(report, spec.category);
  ++cat.cases;
  report.cases.push_back({spec.category, spec.name, 0, 0, 0});
  const size_t case_index = report.cases.size() - 1;
  auto skip_rest = [&](size_t from) {
    report.cases[case_index].skipped += rays.size() - from;
    cat.skipped_rays += rays.size() - from;
  };

  std::vector<ReferenceHit> ref(rays.size());
  par::parallel_for(size_t(0), rays.size(), [&](size_t i) { ref[i] = reference_closest(*scene, rays[i]); });

  auto created = info.create(ParamSet(info.params, info.name));
  auto* kit = dynamic_cast<KitStructure*>(created.get());
  if (!kit) {
    report.faults.push_back(where + ": not a student structure");
    skip_rest(0);
    return;
  }
  kit->set_strict(true);
  at = where + " (build)";
  if (!build_case(spec, info, scene, *kit, report)) {
    skip_rest(0);
    return;
  }
  check_tree(report.invariants, *kit, *scene, where);
  // A worker answers the case's rays in one stream instead of one request a ray.
  if (auto* remote = dynamic_cast<RemoteAnswers*>(kit->student()))
    remote->expect(rays, kit->kernel(), wire_traced | wire_fast);

  const WalkAuditor auditor(kit->tree(), kind, *scene);
  const bool measure_waste = spec.category == "procedural";
  WasteTally here;
  size_t faults_here = 0;
  std::string fault;
  for (size_t i = 0; i < rays.size(); ++i) {
    progress(where, i);
    at = where + " ray " + std::to_string(i);
    Hit fast = no_hit(rays[i]), traced = no_hit(rays[i]);
    TraceRecorder rec(size_t(64) << 20);
    try {
      // Listened to first: the log's step budget stops an endless loop that logs.
      traced = kit->intersect_traced(rays[i], rec);
      fast = kit->intersect(rays[i]);
    } catch (const StudentProcessLost&) {
      throw;
    } catch (const std::exception& e) {
      fault = where + " ray " + std::to_string(i) + ": " + describe_exception(e);
    } catch (...) {
      fault = where + " ray " + std::to_string(i) + ": threw a non-standard exception";
    }
    ++cat.rays;
    ++report.cases[case_index].rays;
    if (!fault.empty()) {  // counted as a wrong answer; three per case are enough to see
      WrongRay w{spec.category, spec.name, scene, i, rays[i], HitVerdict::FalseMiss, Hit{}, ref[i], "fault", fault};
      report.faults.push_back(std::move(fault));
      fault.clear();
      ++cat.wrong[int(HitVerdict::FalseMiss)];
      ++report.cases[case_index].wrong;
      book.add(std::move(w));
      if (++faults_here == kFaultsPerCase) {
        report.faults.push_back(where + ": its other " + std::to_string(rays.size() - i - 1) + " rays skipped after " +
                                std::to_string(kFaultsPerCase) + " faults");
        skip_rest(i + 1);
        break;
      }
      continue;
    }
    check_answers(report.invariants, where + " ray " + std::to_string(i), fast, traced, rec);
    const HitVerdict v = judge_hit(*scene, rays[i], fast, ref[i]);
    const bool wrong = v != HitVerdict::Correct;
    if (!wrong && !measure_waste) continue;
    // The kit's own reading of the walk: every claim against the geometry.
    const WalkAudit audit = auditor.audit(rays[i], rec.events(), rec.recorded_vars(), wrong);
    if (measure_waste) tally_walk(here, audit, rec);
    if (!wrong) continue;
    ++cat.wrong[int(v)];
    ++report.cases[case_index].wrong;
    const Diagnosis d = auditor.diagnose(rays[i], rec.events(), rec.recorded_vars(), audit, traced, ref[i]);
    book.add(WrongRay{spec.category, spec.name, scene, i, rays[i], v, fast, ref[i], d.cause, d.detail, d.step});
  }
  if (measure_waste && report.cases[case_index].wrong == 0 && report.cases[case_index].skipped == 0) {
    tally_peer(info, kind, *kit, *scene, rays, here);
    tally.add(here);
  }
}

/// The rays of a case the check did not reach (after faults in other cases), counted as skipped.
void count_skipped_case(const CaseSpec& spec, CheckReport& report) {
  auto made = spec.make();
  const size_t n = made ? made.value().rays.size() : 0;
  CheckCategory& cat = category_of(report, spec.category);
  ++cat.skipped_cases;
  cat.skipped_rays += n;
  report.cases.push_back({spec.category, spec.name, 0, 0, n});
}

}  // namespace

std::vector<const WrongRay*> CheckReport::examples() const {
  std::vector<const WrongRay*> out;
  for (const CheckCause& c : causes)
    for (const WrongRay& w : c.examples) out.push_back(&w);
  return out;
}

CheckReport check_structure(const StructureInfo& info, const CheckOptions& options, const CheckProgress& progress) {
  CheckReport report;
  report.structure = info.name;
  report.peer = info.builtin_peer;
  report.source_file = info.source_file;
  auto probe = info.create(ParamSet(info.params, info.name));
  auto* kit_probe = dynamic_cast<KitStructure*>(probe.get());
  const accelviz::Kind kind = kit_probe ? kit_probe->kind() : accelviz::Kind::bvh;
  report.kind = info.builtin_peer.empty() ? info.name : info.builtin_peer;
  report.invariants = invariant_rows(kind);
  if (options.shared_scenes.empty() || !std::filesystem::is_directory(options.shared_scenes))
    report.notices.push_back("meshes: skipped: no folder of shared meshes" +
                             (options.shared_scenes.empty() ? std::string() : " at " + options.shared_scenes) +
                             " (put cornell_box.obj, teapot.obj and bunny_lowres.obj in ../shared/scenes beside the "
                             "repository, or give --shared DIR)");

  size_t cases_with_faults = 0;
  CauseBook book;
  WasteTally tally;
  std::string at = "before the first case";  // where the check is: a lost worker's failure names it
  const std::vector<CaseSpec> specs = case_specs(options);
  size_t next = 0;
  auto finish_causes = [&] { report.causes = book.causes(options.examples_per_cause); };
  try {
    for (; next < specs.size(); ++next) {
      if (cases_with_faults == kFaultyCases) {
        report.faults.push_back("the other " + std::to_string(specs.size() - next) + " cases skipped after faults in " +
                                std::to_string(kFaultyCases) + " cases");
        for (; next < specs.size(); ++next) count_skipped_case(specs[next], report);
        break;
      }
      at = specs[next].category + "/" + specs[next].name;
      check_case(specs[next], info, kind, progress, report, book, tally, cases_with_faults, at);
    }
  } catch (const StudentProcessLost& lost) {
    report.failure = std::string(lost.what()) + " at " + at + (lost.hint().empty() ? "" : ": " + lost.hint());
    for (++next; next < specs.size(); ++next) count_skipped_case(specs[next], report);
    report.speed.why_not = "the check did not finish";
    finish_causes();
    return report;
  }
  finish_causes();
  const bool right = report.passed();
  if (right) report.waste = waste_report(tally, kind, report.kind, options.limits, options.strict);
  if (options.time && right) {
    try {
      std::unique_lock<std::mutex> exclusive;
      if (options.timing_mutex) exclusive = std::unique_lock<std::mutex>(*options.timing_mutex);
      if (options.before_timing) options.before_timing();
      report.speed = time_structure(info, options, progress);
    } catch (const StudentProcessLost& lost) {
      // The correctness report stands: only the speed is missing.
      report.speed = CheckSpeed{};
      report.speed.why_not = std::string("the timing stopped: ") + lost.what() + " at procedural/stadium" +
                             (lost.hint().empty() ? "" : ": " + lost.hint());
    }
  } else if (options.time) {
    report.speed.why_not = "a structure that is not right is not timed (a wrong answer's time says nothing)";
  } else {
    report.speed.why_not = "--no-time was given";
  }
  return report;
}


Status write_scene_obj(const Scene& scene, const std::string& path) {
  std::string text = "# written by accelviz-cli check: " + std::to_string(scene.triangle_count()) +
                     " triangles, numbered as in the checked scene\n";
  char line[128];
  for (const Vec3& p : scene.positions()) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", double(p.x), double(p.y), double(p.z));
    text += line;
  }
  for (const UVec3& t : scene.triangles()) {
    std::snprintf(line, sizeof line, "f %u %u %u\n", t[0] + 1, t[1] + 1, t[2] + 1);
    text += line;
  }
  return write_file_atomic(path, text);
}

}  // namespace accel
