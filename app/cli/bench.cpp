// accelviz-cli bench: speed against error on the same rays. For every scene x structure x
// kernel: build time (best of kBuildReps builds on --threads threads) and its ratio to
// Embree's medium-quality build, memory, Mrays/s with one and with all threads (tracing only,
// repeated to >= --min-time seconds, median of 3), and the errors against the
// double-precision reference. Two peers run the same rays: Embree 3 (rtcIntersect1, build
// quality medium and high) is the baseline of the embree_* ratios, and tinybvh (BVH8_CPU over
// its binned and its spatial-split build, BVH4_CPU) joins it; peer_ratio_* compares each
// accelviz row with the fastest peer row of its scene.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>
#include <utility>

#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "accuracy.h"
#include "batch.h"
#include "commands.h"
#include "embree_baseline.h"
#include "interrupt.h"
#include "ray_gen.h"
#include "rays_io.h"
#include "registry.h"
#include "stats_format.h"
#include "tinybvh_baseline.h"

namespace cli {

// Here, not in tinybvh_baseline.cpp: that unit is compiled with -mavx2, so the check itself
// must run from code the CPU surely executes.
bool tinybvh_cpu_supported() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

namespace {

using Clock = std::chrono::steady_clock;

/// Builds per structure and per Embree quality; the fastest one's time is reported. Best-of,
/// not the median: build noise (the first build's page faults, other work on the machine)
/// only ever adds time. Embree and our structures get the same count and the same threads,
/// so embree_build_ratio compares like with like.
constexpr int kBuildReps = 3;

/// The tinybvh rows, in order: its fastest CPU layout over the binned build, the 4-wide SSE
/// layout over the same build, and the 8-wide one over the spatial-split build.
constexpr std::pair<const char*, TinyBvhLayout> kTinyBvhRows[] = {
    {"tinybvh-bvh8", TinyBvhLayout::Bvh8},
    {"tinybvh-bvh4", TinyBvhLayout::Bvh4},
    {"tinybvh-bvh8-hq", TinyBvhLayout::Bvh8Hq},
};

/// The ratio column's value: empty when either time is missing (no Embree, or a build too
/// short for the clock).
std::optional<double> build_ratio(std::optional<double> embree_ms, double ms) {
  if (!embree_ms || *embree_ms <= 0.0 || ms <= 0.0) return std::nullopt;
  return *embree_ms / ms;
}

struct Row {
  std::string scene, structure, params, kernel, rays;
  size_t n_rays = 0;
  double build_ms = 0.0;
  size_t memory_bytes = 0;
  double mrays_1t = 0.0, mrays_mt = 0.0;
  int threads = 0;
  size_t false_miss = 0, false_hit = 0, wrong_prim = 0, wrong_t = 0;
  double max_rel_t_err = 0.0, mean_rel_t_err = 0.0;
  std::optional<double> embree_ratio_mt, embree_ratio_1t;
  /// Embree medium build ms / this row's build_ms (> 1: this row builds faster); empty
  /// without Embree.
  std::optional<double> embree_build_ratio;
  /// The structure's SAH cost (BuildStats::sah_cost; ct/ci per its parameters), empty
  /// when it reports none: to compare builders' quality next to their build times.
  std::optional<double> sah_cost;
  /// This row's Mrays/s over the fastest peer row's (any embree-* or tinybvh-* row) on the
  /// same scene and rays (> 1: this row is faster); empty on peer rows and without peers.
  std::optional<double> peer_ratio_mt, peer_ratio_1t;
  bool is_embree = false;
  bool is_peer = false;  ///< an embree-* or tinybvh-* row
};

Row make_row(const std::string& scene, const std::string& structure, const std::string& params,
             const std::string& kernel, const std::string& rays, size_t n_rays) {
  Row r;
  r.scene = scene;
  r.structure = structure;
  r.params = params;
  r.kernel = kernel;
  r.rays = rays;
  r.n_rays = n_rays;
  return r;
}

int fail(const std::string& message) {
  std::fprintf(stderr, "accelviz-cli: %s\n", message.c_str());
  return kExitBadInput;
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

/// Rays per second of `trace_pass` (one pass over n rays): passes are repeated until a
/// sample lasts >= min_time seconds; the median of three samples is returned, in Mrays/s.
/// Stops early after a signal (the caller then discards the number).
template <class Pass>
double measure_mrays(size_t n, double min_time, Pass&& trace_pass) {
  const auto t0 = Clock::now();
  trace_pass();
  const double first = std::chrono::duration<double>(Clock::now() - t0).count();
  const int reps = int(std::clamp(std::ceil(min_time / std::max(first, 1e-9)), 1.0, 1e9));
  std::vector<double> rates;
  for (int sample = 0; sample < 3; ++sample) {
    const auto s0 = Clock::now();
    for (int r = 0; r < reps && !interrupted(); ++r) trace_pass();
    const double secs = std::chrono::duration<double>(Clock::now() - s0).count();
    rates.push_back(double(n) * reps / secs / 1e6);
  }
  std::sort(rates.begin(), rates.end());
  return rates[1];
}

/// Runs `query(i)` for every ray on `threads` threads and returns the hits (misses for the
/// rays skipped after a signal).
template <class Query>
std::vector<accel::Hit> run_parallel(size_t n, int threads, Query&& query) {
  std::vector<accel::Hit> hits(n);
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1024), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i) {
        if ((i - r.begin()) % 1024 == 0 && interrupted()) break;
        hits[i] = query(i);
      }
    });
  });
  return hits;
}

/// One single-threaded pass of `query` over the rays, stopping after a signal (polled every
/// 1024 rays: negligible next to the queries).
template <class Query>
void run_serial(const std::vector<accel::Ray>& rays, Query&& query) {
  for (size_t i = 0; i < rays.size(); ++i) {
    if (i % 1024 == 0 && interrupted()) return;
    (void)query(rays[i]);
  }
}

/// The reference answers: the double-precision kernel, found through a BVH (its box tests are
/// conservative, and the test suite checks it against a brute-force double scan), with t
/// recomputed exactly in double for the triangle it returns.
accel::Result<std::vector<accel::ReferenceHit>> reference_hits(const accel::Scene& scene,
                                                               const std::vector<accel::Ray>& rays, int threads,
                                                               const accel::BuildControl& limits) {
  accel::BuildControl control;
  control.set_memory_limit(limits.memory_limit());
  control.set_cancel_flag(interrupt_flag());
  auto bvh = accel::build_structure("bvh", scene, {"builder=sah", "width=2"}, accel::Kernel::Double, &control);
  if (!bvh) return accel::make_error("the reference BVH: " + bvh.error().message);
  std::vector<accel::ReferenceHit> ref(rays.size());
  const auto hits = run_parallel(rays.size(), threads, [&](size_t i) { return bvh.value()->intersect(rays[i]); });
  for (size_t i = 0; i < rays.size(); ++i) {
    if (!hits[i].valid()) continue;
    double t, u, v;
    const uint32_t p = uint32_t(hits[i].prim);
    if (accel::intersect_triangle_double(rays[i], scene.vertex(p, 0), scene.vertex(p, 1), scene.vertex(p, 2),
                                         double(rays[i].tmax), &t, &u, &v))
      ref[i] = {hits[i].prim, t};
    else
      ref[i] = {hits[i].prim, double(hits[i].t)};
  }
  return ref;
}

void score(Row& row, const accel::Scene& scene, const std::vector<accel::Ray>& rays,
           const std::vector<accel::Hit>& hits, const std::vector<accel::ReferenceHit>& ref) {
  double sum_err = 0.0;
  size_t both_hit = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    switch (accel::judge_hit(scene, rays[i], hits[i], ref[i])) {
      case accel::HitVerdict::FalseMiss: ++row.false_miss; break;
      case accel::HitVerdict::FalseHit: ++row.false_hit; break;
      case accel::HitVerdict::WrongPrim: ++row.wrong_prim; break;
      case accel::HitVerdict::WrongT: ++row.wrong_t; break;
      case accel::HitVerdict::Correct: break;
    }
    if (hits[i].valid() && ref[i].prim >= 0) {
      const double err = std::abs(double(hits[i].t) - ref[i].t) / std::max(1e-30, std::abs(ref[i].t));
      row.max_rel_t_err = std::max(row.max_rel_t_err, err);
      sum_err += err;
      ++both_hit;
    }
  }
  row.mean_rel_t_err = both_hit ? sum_err / double(both_hit) : 0.0;
}

/// A scene and its rays.
struct BenchInput {
  accel::Scene scene;
  std::vector<accel::Ray> rays;
};

/// Loads the scene and makes its rays; a signal meanwhile ends the process at once (nothing
/// to clean up yet, and a rays file that is a FIFO may block).
accel::Result<BenchInput> load_input(const std::string& scene_spec, const std::string& rays_spec) {
  ExitOnInterrupt reading;
  auto scene = accel::load_scene(scene_spec);
  if (!scene) return scene.error();
  auto rays = accel::make_rays(rays_spec, scene.value());
  if (!rays) return rays.error();
  return BenchInput{std::move(scene.value()), std::move(rays.value())};
}

/// Parameters for one structure: unprefixed keys it knows, and "structure:key=value".
std::vector<std::string> params_for(const accel::StructureInfo& info, const std::vector<std::string>& all) {
  std::vector<std::string> out;
  for (const std::string& p : all) {
    const size_t colon = p.find(':'), eq = p.find('=');
    if (colon != std::string::npos && colon < eq) {
      if (p.substr(0, colon) == info.name) out.push_back(p.substr(colon + 1));
      continue;
    }
    const std::string key = p.substr(0, eq);
    for (const auto& spec : info.params)
      if (spec.name == key) out.push_back(p);
  }
  return out;
}

std::string fmt(double v, const char* f = "%.3g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string markdown(const std::vector<Row>& rows) {
  std::string md =
      "| scene | structure | params | kernel | build ms | Embree build ratio | MB | Mrays/s 1t | Mrays/s mt | "
      "vs Embree (1t) | vs Embree (mt) | false miss | false hit | wrong tri | max rel t err | vs peer (1t) | "
      "vs peer (mt) |\n"
      "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  auto peer_cell = [](const Row& r, const std::optional<double>& ratio) {
    return ratio ? fmt(*ratio, "%.2f") : std::string(r.is_peer ? "(peer)" : "-");
  };
  for (const Row& r : rows) {
    md += "| " + r.scene + " | " + r.structure + " | " + (r.params.empty() ? "default" : r.params) + " | " + r.kernel +
          " | " + fmt(r.build_ms, "%.1f") + " | " +
          (r.embree_build_ratio ? fmt(*r.embree_build_ratio, "%.2f") : std::string("-")) + " | " +
          fmt(double(r.memory_bytes) / 1048576.0, "%.1f") + " | " +
          fmt(r.mrays_1t, "%.2f") + " | " + fmt(r.mrays_mt, "%.2f") + " | " +
          (r.embree_ratio_1t ? fmt(*r.embree_ratio_1t, "%.2f") : std::string(r.is_embree ? "1 (baseline)" : "")) + " | " +
          (r.embree_ratio_mt ? fmt(*r.embree_ratio_mt, "%.2f") : std::string(r.is_embree ? "1 (baseline)" : "")) +
          " | " + std::to_string(r.false_miss) + " | " + std::to_string(r.false_hit) + " | " +
          std::to_string(r.wrong_prim + r.wrong_t) + " | " + fmt(r.max_rel_t_err, "%.2g") + " | " +
          peer_cell(r, r.peer_ratio_1t) + " | " + peer_cell(r, r.peer_ratio_mt) + " |\n";
  }
  return md;
}

std::string csv(const std::vector<Row>& rows) {
  std::string out =
      "scene,structure,params,kernel,rays,n_rays,build_ms,memory_bytes,mrays_1t,mrays_mt,threads,false_miss,false_hit,"
      "wrong_prim,wrong_t,max_rel_t_err,mean_rel_t_err,embree_ratio_mt,embree_ratio_1t,embree_build_ratio,"
      "peer_ratio_mt,peer_ratio_1t\n";
  auto q = [](const std::string& s) { return "\"" + s + "\""; };
  for (const Row& r : rows)
    out += q(r.scene) + "," + r.structure + "," + q(r.params) + "," + r.kernel + "," + q(r.rays) + "," +
           std::to_string(r.n_rays) + "," + fmt(r.build_ms, "%.3f") + "," + std::to_string(r.memory_bytes) + "," +
           fmt(r.mrays_1t, "%.4f") + "," + fmt(r.mrays_mt, "%.4f") + "," + std::to_string(r.threads) + "," +
           std::to_string(r.false_miss) + "," + std::to_string(r.false_hit) + "," + std::to_string(r.wrong_prim) + "," +
           std::to_string(r.wrong_t) + "," + fmt(r.max_rel_t_err, "%.6g") + "," + fmt(r.mean_rel_t_err, "%.6g") + "," +
           (r.embree_ratio_mt ? fmt(*r.embree_ratio_mt, "%.4f") : "") + "," +
           (r.embree_ratio_1t ? fmt(*r.embree_ratio_1t, "%.4f") : "") + "," +
           (r.embree_build_ratio ? fmt(*r.embree_build_ratio, "%.4f") : "") + "," +
           (r.peer_ratio_mt ? fmt(*r.peer_ratio_mt, "%.4f") : "") + "," +
           (r.peer_ratio_1t ? fmt(*r.peer_ratio_1t, "%.4f") : "") + "\n";
  return out;
}

std::string json(const std::vector<Row>& rows) {
  std::string out = "[\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    out += "  {\"scene\": " + json_quote(r.scene) + ", \"structure\": " + json_quote(r.structure) +
           ", \"params\": " + json_quote(r.params) + ", \"kernel\": " + json_quote(r.kernel) +
           ", \"rays\": " + json_quote(r.rays) + ", \"n_rays\": " + std::to_string(r.n_rays) +
           ", \"build_ms\": " + fmt(r.build_ms, "%.3f") + ", \"embree_build_ratio\": " +
           (r.embree_build_ratio ? fmt(*r.embree_build_ratio, "%.4f") : std::string("null")) +
           ", \"sah_cost\": " + (r.sah_cost ? fmt(*r.sah_cost, "%.6g") : std::string("null")) +
           ", \"memory_bytes\": " + std::to_string(r.memory_bytes) +
           ", \"mrays_1t\": " + fmt(r.mrays_1t, "%.4f") + ", \"mrays_mt\": " + fmt(r.mrays_mt, "%.4f") +
           ", \"threads\": " + std::to_string(r.threads) + ", \"false_miss\": " + std::to_string(r.false_miss) +
           ", \"false_hit\": " + std::to_string(r.false_hit) + ", \"wrong_prim\": " + std::to_string(r.wrong_prim) +
           ", \"wrong_t\": " + std::to_string(r.wrong_t) + ", \"max_rel_t_err\": " + fmt(r.max_rel_t_err, "%.6g") +
           ", \"mean_rel_t_err\": " + fmt(r.mean_rel_t_err, "%.6g");
    if (!r.is_embree)
      out += ", \"embree_ratio_mt\": " + (r.embree_ratio_mt ? fmt(*r.embree_ratio_mt, "%.4f") : std::string("null")) +
             ", \"embree_ratio_1t\": " + (r.embree_ratio_1t ? fmt(*r.embree_ratio_1t, "%.4f") : std::string("null"));
    if (!r.is_peer)
      out += ", \"peer_ratio_mt\": " + (r.peer_ratio_mt ? fmt(*r.peer_ratio_mt, "%.4f") : std::string("null")) +
             ", \"peer_ratio_1t\": " + (r.peer_ratio_1t ? fmt(*r.peer_ratio_1t, "%.4f") : std::string("null"));
    out += std::string("}") + (i + 1 < rows.size() ? "," : "") + "\n";
  }
  return out + "]\n";
}

/// One progress line on stderr ("\r"-updated on a terminal, one line per step otherwise).
void progress(size_t done, size_t total, const std::string& what) {
  const bool tty = ::isatty(2);
  const int width = 30, filled = int(double(width) * double(done) / double(std::max<size_t>(1, total)));
  std::fprintf(stderr, "%s[%s%s] %zu/%zu %s%s", tty ? "\r" : "", std::string(size_t(filled), '#').c_str(),
               std::string(size_t(width - filled), ' ').c_str(), done, total, what.c_str(), tty ? "\033[K" : "\n");
  if (tty && done == total) std::fputc('\n', stderr);
  std::fflush(stderr);
}

/// What the options ask for, checked before the first (slow) scene load.
struct BenchPlan {
  std::vector<const accel::StructureInfo*> structures;
  std::vector<accel::Kernel> kernels;
  std::vector<accel::ParamSet> param_sets;  ///< by structure
  accel::BuildControl limits;  ///< carries the budget only; each build gets its own control
  int threads = 0;
  bool with_embree = false, with_tinybvh = false;
};

/// Validates every option (structures, kernels, parameters, output paths, limits) into
/// `plan`, and decides which peers run.
accel::Status plan_bench(const BenchOptions& o, BenchPlan& plan) {
  if (o.structures == "all") {
    for (const auto& info : accel::structure_registry())
      if (!info.reference) plan.structures.push_back(&info);
  } else {
    for (const std::string& name : split_list(o.structures)) {
      auto info = accel::find_structure(name);
      if (!info) return accel::make_error("--structures: " + info.error().message);
      plan.structures.push_back(info.value());
    }
  }
  if (plan.structures.empty()) return accel::make_error("--structures: empty list");
  for (const std::string& k : split_list(o.kernels)) {
    accel::Kernel kernel;
    if (!accel::parse_kernel(k, &kernel))
      return accel::make_error("--kernel '" + k + "' is invalid (valid: " + accel::kernel_names_text() + ")");
    plan.kernels.push_back(kernel);
  }
  if (plan.kernels.empty()) return accel::make_error("--kernel: empty list");
  for (const auto* info : plan.structures) {
    auto set = accel::ParamSet::parse(info->params, params_for(*info, o.params), info->name);
    if (!set) return set.error();
    plan.param_sets.push_back(set.value());
  }
  for (const std::string& p : o.params) {  // every --param must be used by some structure
    bool used = false;
    for (const auto* info : plan.structures)
      for (const std::string& q : params_for(*info, {p})) used |= !q.empty();
    if (!used) return accel::make_error("--param '" + p + "' matches no parameter of the benchmarked structures");
  }
  for (const std::string* path : {&o.out_md, &o.out_csv, &o.out_json})  // before minutes of work, not after
    if (!path->empty())
      if (auto writable = accel::check_writable(*path); !writable) return writable.error();
  if (auto ok = apply_build_limits(o.memory_limit, o.time_limit, &plan.limits); !ok) return ok.error();
  plan.threads = o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  plan.with_embree = o.embree && embree_available();
  // tinybvh's unit is AVX2 code throughout (BVH4_CPU included): never call it without AVX2.
  plan.with_tinybvh = o.tinybvh && tinybvh_available() && tinybvh_cpu_supported();
  if (o.tinybvh && tinybvh_available() && !plan.with_tinybvh)
    std::fprintf(stderr, "accelviz-cli: note: this CPU lacks AVX2/FMA; the tinybvh rows are skipped\n");
  return {};
}

/// One scene's benchmark: its rays, their reference answers, the progress, and the rows
/// measured so far with the peers' best rates that later rows are compared with.
struct SceneBench {
  const BenchOptions& o;
  const BenchPlan& plan;
  const std::string& spec;
  const accel::Scene& scene;
  const std::vector<accel::Ray>& rays;
  const std::vector<accel::ReferenceHit>& ref;
  size_t& step;
  size_t total_steps;
  std::optional<double> embree_mt, embree_1t, embree_medium_build_ms;
  std::vector<Row> rows;

  /// A row of this scene, its build already timed: the rest of what every row reports.
  Row make_row(const std::string& structure, const std::string& params, const std::string& kernel,
               double build_ms) const {
    Row row = cli::make_row(spec, structure, params, kernel, o.rays, rays.size());
    row.build_ms = build_ms;
    row.embree_build_ratio = build_ratio(embree_medium_build_ms, build_ms);
    row.threads = plan.threads;
    return row;
  }
  /// Scores the hits, adds the ratios to Embree's best (when there is one) and keeps the row.
  void keep(Row& row, const std::vector<accel::Hit>& hits) {
    score(row, scene, rays, hits, ref);
    if (!row.is_embree) {
      if (embree_mt) row.embree_ratio_mt = row.mrays_mt / *embree_mt;
      if (embree_1t) row.embree_ratio_1t = row.mrays_1t / *embree_1t;
    }
    rows.push_back(row);
    ++step;
  }
};

/// The best of kBuildReps builds of a peer (`build()` makes one; one in memory at a time):
/// the last one built and the best build time. Null after a signal.
template <class Built, class Build>
std::unique_ptr<Built> best_peer_build(double* best_build_ms, Build&& build) {
  std::unique_ptr<Built> built;
  *best_build_ms = std::numeric_limits<double>::infinity();
  for (int rep = 0; rep < kBuildReps; ++rep) {
    built.reset();
    built = build();
    *best_build_ms = std::min(*best_build_ms, built->build_ms());
    if (interrupted()) return nullptr;
  }
  return built;
}

/// The Embree rows' qualities (EmbreeScene), medium first: it is the build baseline, and the
/// rows after it get its ratio too.
std::vector<const char*> embree_qualities(const BenchOptions& o) {
  std::vector<const char*> qualities{"medium", "high"};
  if (o.embree_robust) qualities.push_back("robust");
  return qualities;
}

/// The Embree rows, one per quality of embree_qualities(). Returns false after a signal.
bool embree_rows(SceneBench& b) {
  for (const char* quality : embree_qualities(b.o)) {
    progress(b.step, b.total_steps, b.spec + ": embree-" + quality);
    double best_build_ms = 0.0;
    const auto built = best_peer_build<EmbreeScene>(
        &best_build_ms, [&] { return std::make_unique<EmbreeScene>(b.scene, quality, b.plan.threads); });
    if (!built) return false;
    const EmbreeScene& embree = *built;
    if (std::string(quality) == "medium") b.embree_medium_build_ms = best_build_ms;
    Row row = b.make_row(std::string("embree-") + quality, "", "embree", best_build_ms);
    row.is_embree = true;
    row.is_peer = true;
    row.memory_bytes = embree.memory_bytes();
    row.mrays_1t = measure_mrays(b.rays.size(), b.o.min_time, [&] {
      run_serial(b.rays, [&](const accel::Ray& r) { return embree.intersect(r); });
    });
    std::vector<accel::Hit> hits;
    row.mrays_mt = measure_mrays(b.rays.size(), b.o.min_time, [&] {
      hits = run_parallel(b.rays.size(), b.plan.threads, [&](size_t i) { return embree.intersect(b.rays[i]); });
    });
    if (interrupted()) return false;
    b.keep(row, hits);
    b.embree_mt = std::max(b.embree_mt.value_or(0.0), row.mrays_mt);
    b.embree_1t = std::max(b.embree_1t.value_or(0.0), row.mrays_1t);
  }
  return true;
}

/// The tinybvh rows (kTinyBvhRows), over a copy of the triangles. tinybvh has no tmin: a
/// ray with tmin > 0 is traced from t = 0 and its answer scored as it comes (a hit before
/// tmin counts as an error). Said once per scene on stderr. Returns false after a signal.
bool tinybvh_rows(SceneBench& b) {
  const accel::Scene& s = b.scene;
  const size_t with_tmin =
      size_t(std::count_if(b.rays.begin(), b.rays.end(), [](const accel::Ray& r) { return r.tmin > 0.0f; }));
  if (with_tmin > 0)
    std::fprintf(stderr, "accelviz-cli: note: %s: %zu rays have tmin > 0; tinybvh has no tmin, so they are traced "
                 "from t = 0 and scored as they come\n", b.spec.c_str(), with_tmin);
  std::vector<float> triangles;
  triangles.reserve(9 * s.triangle_count());
  for (const auto& tri : s.triangles())
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) triangles.push_back(s.positions()[tri[k]][c]);
  for (const auto& [name, layout] : kTinyBvhRows) {
    progress(b.step, b.total_steps, b.spec + ": " + name);
    double best_build_ms = 0.0;
    const auto built = best_peer_build<TinyBvhScene>(&best_build_ms, [&, layout = layout] {
      return std::make_unique<TinyBvhScene>(triangles.data(), s.triangle_count(), layout);
    });
    if (!built) return false;
    const TinyBvhScene& bvh = *built;
    auto query = [&bvh](const accel::Ray& r) {
      const TinyBvhHit h = bvh.intersect(&r.org.x, &r.dir.x, r.tmax);
      return h.prim < 0 ? accel::Hit{} : accel::Hit{h.prim, h.t, h.u, h.v};
    };
    Row row = b.make_row(name, "", "tinybvh", best_build_ms);
    row.is_peer = true;
    row.memory_bytes = bvh.memory_bytes();
    row.mrays_1t = measure_mrays(b.rays.size(), b.o.min_time, [&] { run_serial(b.rays, query); });
    std::vector<accel::Hit> hits;
    row.mrays_mt = measure_mrays(b.rays.size(), b.o.min_time, [&] {
      hits = run_parallel(b.rays.size(), b.plan.threads, [&](size_t i) { return query(b.rays[i]); });
    });
    if (interrupted()) return false;
    b.keep(row, hits);
  }
  return true;
}

/// The best of kBuildReps builds of structure `k` (one in memory at a time: the terrain's
/// are large), the last one kept: the kernel only changes the queries. Built in an arena of
/// `threads` so a parallel builder uses what Embree used. Its stats carry the best time.
accel::Result<std::unique_ptr<accel::Structure>> best_structure_build(const SceneBench& b, size_t k,
                                                                      accel::BuildStats* stats) {
  const std::string name = b.plan.structures[k]->name;
  std::unique_ptr<accel::Structure> structure;
  double best_build_ms = std::numeric_limits<double>::infinity();
  tbb::task_arena build_arena(b.plan.threads);
  for (int rep = 0; rep < kBuildReps; ++rep) {
    structure.reset();
    accel::BuildControl control;
    control.set_memory_limit(b.plan.limits.memory_limit());
    control.set_time_limit(b.o.time_limit);
    control.set_cancel_flag(interrupt_flag());
    auto built = build_arena.execute([&] {
      return accel::build_structure(*b.plan.structures[k], b.scene, b.plan.param_sets[k], accel::Kernel::Watertight,
                                    &control);
    });
    if (interrupted()) return accel::cancelled_error();
    if (!built) return build_error(built.error(), name, control);
    structure = std::move(built.value());
    best_build_ms = std::min(best_build_ms, structure->build_stats().build_ms);
  }
  *stats = structure->build_stats();
  stats->build_ms = best_build_ms;
  return structure;
}

/// Structure `k`'s rows, one per kernel, each compared with Embree's and the fastest peer's
/// rates (`peer_mt`, `peer_1t`). Returns an exit code when the benchmark must stop.
std::optional<int> structure_rows(SceneBench& b, size_t k, std::optional<double> peer_mt,
                                  std::optional<double> peer_1t) {
  const std::string name = b.plan.structures[k]->name;
  progress(b.step, b.total_steps, b.spec + ": " + name + " build");
  accel::BuildStats stats;
  auto built = best_structure_build(b, k, &stats);
  if (interrupted()) return interrupted_exit();
  if (!built) return fail(built.error().message);
  accel::Structure& structure = *built.value();
  for (accel::Kernel requested : b.plan.kernels) {
    // A 2D scene has one hit rule, whatever --kernel says (build_structure() set it).
    const accel::Kernel kernel = b.scene.planar() ? accel::Kernel::Planar : requested;
    progress(b.step, b.total_steps, b.spec + ": " + name + " " + std::string(accel::kernel_name(kernel)));
    structure.set_kernel(kernel);
    Row row = b.make_row(name, b.plan.param_sets[k].to_string(), std::string(accel::kernel_name(kernel)), stats.build_ms);
    if (std::isfinite(stats.sah_cost)) row.sah_cost = stats.sah_cost;
    row.memory_bytes = stats.memory_bytes;
    row.mrays_1t = measure_mrays(b.rays.size(), b.o.min_time, [&] {
      if (accel::answered_in_batches(structure))
        accel::trace_all(structure, b.rays, 1, nullptr, interrupt_flag());
      else
        run_serial(b.rays, [&](const accel::Ray& r) { return structure.intersect(r); });
    });
    // One call a ray, as the peers' rows make theirs (rtcIntersect1, tinybvh's Intersect):
    // not trace_all(), whose batch calls (Structure::intersect_batch) the peers' rows lack.
    std::vector<accel::Hit> hits;
    row.mrays_mt = measure_mrays(b.rays.size(), b.o.min_time, [&] {
      if (accel::answered_in_batches(structure))
        hits = accel::trace_all(structure, b.rays, b.plan.threads, nullptr, interrupt_flag());
      else
        hits = run_parallel(b.rays.size(), b.plan.threads, [&](size_t i) { return structure.intersect(b.rays[i]); });
    });
    if (interrupted()) return interrupted_exit();
    if (peer_mt && *peer_mt > 0.0) row.peer_ratio_mt = row.mrays_mt / *peer_mt;
    if (peer_1t && *peer_1t > 0.0) row.peer_ratio_1t = row.mrays_1t / *peer_1t;
    b.keep(row, hits);
  }
  return std::nullopt;
}

/// Every row of one scene: the reference answers, the peers, then each structure. Returns
/// an exit code when the benchmark must stop.
std::optional<int> bench_scene(const BenchOptions& o, const BenchPlan& plan, const std::string& spec, size_t& step,
                               size_t total_steps, std::vector<Row>& rows) {
  auto input = load_input(spec, o.rays);
  if (!input) return fail(input.error().message);
  const std::vector<accel::Ray>& rays = input.value().rays;
  const accel::Scene& s = input.value().scene;
  progress(step, total_steps, spec + ": reference (double kernel)");
  const auto ref = reference_hits(s, rays, plan.threads, plan.limits);
  if (interrupted()) return interrupted_exit();
  if (!ref) return fail(ref.error().message);
  ++step;
  SceneBench b{o, plan, spec, s, rays, ref.value(), step, total_steps, {}, {}, {}, {}};
  if (plan.with_embree && !embree_rows(b)) return interrupted_exit();
  if (plan.with_tinybvh && !tinybvh_rows(b)) return interrupted_exit();
  std::optional<double> peer_mt, peer_1t;  // the fastest peer row's, each measure on its own
  for (const Row& r : b.rows) {
    peer_mt = std::max(peer_mt.value_or(0.0), r.mrays_mt);
    peer_1t = std::max(peer_1t.value_or(0.0), r.mrays_1t);
  }
  for (size_t k = 0; k < plan.structures.size(); ++k)
    if (auto stop = structure_rows(b, k, peer_mt, peer_1t)) return stop;
  rows.insert(rows.end(), b.rows.begin(), b.rows.end());
  return std::nullopt;
}

}  // namespace

int run_bench(const BenchOptions& o) {
  BenchPlan p;
  if (auto planned = plan_bench(o, p); !planned) return fail(planned.error().message);
  std::vector<Row> rows;
  const size_t steps_per_scene = p.structures.size() * p.kernels.size() +
                                 (p.with_embree ? embree_qualities(o).size() : 0) +
                                 (p.with_tinybvh ? std::size(kTinyBvhRows) : 0) + 1;
  const size_t total_steps = o.scenes.size() * steps_per_scene;
  size_t step = 0;
  for (const std::string& scene_spec : o.scenes)
    if (auto stop = bench_scene(o, p, scene_spec, step, total_steps, rows)) return *stop;
  progress(total_steps, total_steps, "done");

  const std::string md = markdown(rows);
  std::fputs(md.c_str(), stdout);
  for (const auto& [path, content] : {std::pair{o.out_md, md}, std::pair{o.out_csv, csv(rows)},
                                      std::pair{o.out_json, json(rows)}}) {
    if (path.empty()) continue;
    auto written = accel::write_file_atomic(path, content, interrupt_flag());
    if (!written) return interrupted() ? interrupted_exit() : fail(written.error().message);
  }
  return 0;
}

}  // namespace cli
