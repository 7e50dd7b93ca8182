#include "commands.h"

#include <chrono>
#include <cstdio>
#include <thread>
#include <memory>
#include <sstream>

#include "batch.h"
#include "interrupt.h"
#include "ray_gen.h"
#include "rays_io.h"
#include "registry.h"
#include "stats_format.h"

namespace cli {
namespace {

int fail(const std::string& message) {
  std::fprintf(stderr, "accelviz-cli: %s\n", message.c_str());
  return kExitBadInput;
}

/// Loads the scene and builds the structure; on error prints it and returns false.
struct Built {
  accel::Scene scene;
  double load_ms = 0.0;  ///< the scene's load (or generation) time
  std::unique_ptr<accel::Structure> structure;
  std::string params;
  accel::ParamSet param_set;
  accel::Kernel kernel = accel::Kernel::Watertight;
  const accel::StructureInfo* info = nullptr;
};

}  // namespace

accel::Status apply_build_limits(const std::string& memory_limit, double time_limit, accel::BuildControl* control) {
  if (!memory_limit.empty()) {
    auto bytes = accel::parse_memory_size(memory_limit, "--memory-limit");
    if (!bytes) return bytes.error();
    control->set_memory_limit(bytes.value());
  }
  control->set_time_limit(time_limit);
  return {};
}

accel::Error build_error(const accel::Error& error, const std::string& structure, const accel::BuildControl& control) {
  if (!control.timed_out()) return error;
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%g", control.time_limit());
  return accel::make_error(structure + ": the build stopped at --time-limit " + seconds +
                           " s; lower its parameters or raise --time-limit");
}

namespace {

accel::Result<std::unique_ptr<Built>> load_and_build(const StructureOptions& o) {
  accel::Kernel kernel;
  if (!accel::parse_kernel(o.kernel, &kernel))
    return accel::make_error("--kernel '" + o.kernel + "' is invalid (valid: " + accel::kernel_names_text() + ")");
  // Validate the structure name and parameters before the (possibly slow) scene load.
  auto choice = accel::parse_structure(o.structure, o.params);
  if (!choice) return choice.error();
  const accel::StructureInfo* info = choice.value().info;
  const accel::ParamSet& params = choice.value().params;
  accel::BuildControl control;
  if (auto limits = apply_build_limits(o.memory_limit, o.time_limit, &control); !limits) return limits.error();
  control.set_cancel_flag(interrupt_flag());  // SIGINT stops the build at its next check
  const auto load_start = std::chrono::steady_clock::now();
  auto scene = [&] {
    ExitOnInterrupt reading;  // nothing to clean up yet; a FIFO may block
    return accel::load_scene(o.scene);
  }();
  if (!scene) return scene.error();
  auto built = std::make_unique<Built>();
  built->load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();
  built->scene = std::move(scene.value());
  built->params = params.to_string();
  built->param_set = params;
  built->kernel = kernel;
  built->info = info;
  control.set_time_limit(o.time_limit);  // from the build's start, not the load's
  auto structure = accel::build_structure(*info, built->scene, params, kernel, &control);
  if (!structure) return build_error(structure.error(), o.structure, control);
  built->structure = std::move(structure.value());
  return built;
}

/// make_rays, where a signal ends the process at once (a rays file may be a FIFO).
accel::Result<std::vector<accel::Ray>> read_rays_input(const std::string& spec, const accel::Scene& scene) {
  ExitOnInterrupt reading;
  return accel::make_rays(spec, scene);
}

}  // namespace

int run_trace(const TraceOptions& o) {
  // An output that cannot be created fails now, not after the build and the queries.
  if (auto writable = accel::check_writable(o.out); !writable) return fail(writable.error().message);
  auto built = load_and_build(o.build);
  if (interrupted()) return interrupted_exit();
  if (!built) return fail(built.error().message);
  auto rays = read_rays_input(o.rays, built.value()->scene);
  if (!rays) return fail(rays.error().message);
  const auto hits = accel::trace_all(*built.value()->structure, rays.value(), o.threads, nullptr, interrupt_flag());
  if (interrupted()) return interrupted_exit();
  // Once the file is renamed into place the run is complete: a signal after it changes nothing.
  auto written = accel::write_hits_csv(o.out, hits, interrupt_flag());
  if (!written) return interrupted() ? interrupted_exit() : fail(written.error().message);
  return 0;
}

int run_stats(const StatsOptions& o) {
  if (!o.build_trace.empty())
    if (auto writable = accel::check_writable(o.build_trace); !writable) return fail(writable.error().message);
  auto built = load_and_build(o.build);
  if (interrupted()) return interrupted_exit();
  if (!built) return fail(built.error().message);
  const Built& b = *built.value();
  accel::BuildStats stats = b.structure->build_stats();
  if (o.digest) {  // of the tree as built: the refit below may change its boxes
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(accel::structure_digest(*b.structure)));
    stats.extra.push_back({"digest", hex});
  }
  QueryReport q;
  if (!o.rays.empty()) {
    auto rays = read_rays_input(o.rays, b.scene);
    if (!rays) return fail(rays.error().message);
    // Timed twice: the fast path (no counters, as `trace` and `bench` run it), then with the
    // counters that give the per-ray figures.
    const auto fast_start = std::chrono::steady_clock::now();
    (void)accel::trace_all(*b.structure, rays.value(), o.threads);
    q.trace_fast_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - fast_start).count();
    accel::QueryStats total;
    const auto start = std::chrono::steady_clock::now();
    const auto hits = accel::trace_all(*b.structure, rays.value(), o.threads, &total, interrupt_flag());
    if (interrupted()) return interrupted_exit();
    q.trace_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    q.present = true;
    q.rays = o.rays;
    q.n_rays = hits.size();
    for (const auto& h : hits) q.hits += h.valid();
    const double n = double(std::max<size_t>(1, hits.size()));
    q.nodes_per_ray = double(total.nodes_visited) / n;
    q.culled_per_ray = double(total.nodes_culled) / n;
    q.prims_per_ray = double(total.prims_tested) / n;
    q.threads = o.threads > 0 ? o.threads : int(std::thread::hardware_concurrency());
  }
  // What a refit costs next to the build: once, on the unmoved scene, for the structures that
  // can refit (the others print no refit_ms); after the queries, because a refit of bvh
  // builder=sbvh replaces its clipped boxes by the triangles' whole boxes (Structure::refit).
  if (b.structure->refit(b.scene)) stats.refit_ms = b.structure->build_stats().refit_ms;
  if (!o.build_trace.empty()) {
    // A second, recorded build (single-threaded): the statistics above are the normal one's.
    accel::BuildControl control;
    control.set_cancel_flag(interrupt_flag());
    auto recorded = accel::build_structure_recorded(*b.info, b.scene, b.param_set, b.kernel,
                                                    size_t(o.build_trace_budget_mb) << 20, &control);
    if (interrupted()) return interrupted_exit();
    if (!recorded) return fail(recorded.error().message);
    std::ostringstream out;
    accel::write_build_trace_jsonl(recorded.value().trace, out);
    auto written = accel::write_file_atomic(o.build_trace, out.str(), interrupt_flag());
    if (!written) return interrupted() ? interrupted_exit() : fail(written.error().message);
    std::fprintf(stderr, "build trace: %zu steps (%s) written to %s\n", recorded.value().trace.events.size(),
                 recorded.value().trace.coverage().c_str(), o.build_trace.c_str());
  }
  const std::string text = o.json ? stats_json(o.build.scene, o.build.structure, b.params, b.scene, b.load_ms, stats, q)
                                  : stats_text(o.build.scene, o.build.structure, b.params, b.scene, b.load_ms, stats, q);
  std::fputs(text.c_str(), stdout);
  return 0;
}

}  // namespace cli
