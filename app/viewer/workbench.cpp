#include "workbench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "batch.h"
#include "registry.h"

namespace viz {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::string number_text(double v, bool integer) {
  char buf[32];
  if (integer) std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(std::llround(v)));
  else std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// Structures

std::vector<std::string> with_param(std::vector<std::string> params, const std::string& key, const std::string& value) {
  const std::string prefix = key + "=";
  for (std::string& p : params) {
    if (p.starts_with(prefix)) {
      p = prefix + value;
      return params;
    }
  }
  params.push_back(prefix + value);
  return params;
}

std::string param_value(const std::vector<std::string>& params, const std::string& key, const std::string& fallback) {
  const std::string prefix = key + "=";
  for (const std::string& p : params)
    if (p.starts_with(prefix)) return p.substr(prefix.size());
  return fallback;
}

accel::Result<BuiltPtr> build_structure_now(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                                            accel::BuildControl* control) {
  auto choice = accel::parse_structure(request.name, request.params);
  if (!choice) return choice.error();
  const accel::StructureInfo* info = choice.value().info;
  const accel::ParamSet& params = choice.value().params;
  auto built = std::make_shared<BuiltStructure>();
  built->scene = std::move(scene);
  built->request = request;
  built->params_text = params.to_string_all();
  auto structure = accel::build_structure(*info, *built->scene, params, request.kernel, control);
  if (!structure) return structure.error();
  // Listing a big structure's nodes takes a while too: no point once superseded.
  if (accel::build_cancelled(control)) return accel::cancelled_error();
  built->structure = std::move(structure.value());
  built->stats = built->structure->build_stats();
  built->geometry = structure_geometry(*built->structure, request.geometry);
  if (params.has("traversal")) built->traversal = params.get_choice("traversal");
  built->info = info;
  built->kind = traversal_kind(info->traversal, built->traversal);
  if (built->kind == TraversalKind::Grid && built->scene->planar()) built->kind = TraversalKind::Grid2d;
  return BuiltPtr(std::move(built));
}

BuildRunner::BuildRunner() : BuildRunner(BuildFn(build_structure_now)) {}

BuildRunner::BuildRunner(BuildFn build) : build_(std::move(build)) {}

BuildRunner::~BuildRunner() { wait(); }

void BuildRunner::request(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                          bool synchronous) {
  Pending pending{std::move(scene), request};
  if (job_.busy() && !synchronous) {
    // Only the newest request matters: stop the running build rather than finish it.
    if (control_) control_->cancel();
    next_ = std::move(pending);
    return;
  }
  next_.reset();
  start(std::move(pending), synchronous);
}

void BuildRunner::start(Pending pending, bool synchronous) {
  control_ = std::make_shared<accel::BuildControl>();
  control_->set_memory_limit(memory_limit_);
  job_.start(
      [build = build_, control = control_, pending = std::move(pending)](const std::atomic<bool>&) {
        return build(pending.scene, pending.request, control.get());
      },
      synchronous);
}

std::optional<accel::Result<BuiltPtr>> BuildRunner::poll() {
  if (!job_.ready()) return std::nullopt;
  accel::Result<BuiltPtr> result = job_.take();
  // Cancelled means superseded: even a build that finished before it noticed is stale.
  const bool superseded = control_ && control_->cancelled();
  if (next_) {
    Pending next = std::move(*next_);
    next_.reset();
    start(std::move(next), false);
  }
  if (superseded) return std::nullopt;
  return result;
}

double BuildRunner::fraction() const {
  if (!control_ || control_->cancelled()) return 0.0;
  return control_->fraction();
}

void BuildRunner::wait() {
  cancel();
  job_.wait();
}

void BuildRunner::cancel() {
  next_.reset();
  if (control_) control_->cancel();
}

// ---------------------------------------------------------------------------------------
// The debug ray

void DebugRay::record(const accel::Structure& s, bool keep_step) {
  accel::TraceRecorder recorder;
  hit = s.intersect_traced(ray, recorder);
  truncated = recorder.truncated();
  // A truncated recording lacks steps to count: the same query through the counting sink.
  if (truncated)
    s.intersect(ray, &stats);
  else
    stats = recorder.stats();
  vars = recorder.recorded_vars();
  player.load(recorder.events(), keep_step);
}

float ray_draw_length(const accel::Ray& ray, const accel::Hit& hit, const accel::Aabb& bounds) {
  if (hit.valid()) return hit.t;
  const float diag = bounds.empty() ? 1.0f : glm::length(bounds.extent());
  accel::Aabb grown = bounds;
  if (!grown.empty()) {
    grown.min -= glm::vec3(0.05f * diag);
    grown.max += glm::vec3(0.05f * diag);
  }
  const accel::BoxTester tester(ray);
  float t0 = 0.0f, t1 = 0.0f;
  const float len = glm::length(ray.dir);
  if (!grown.empty() && tester.intersect(grown, ray.tmin, accel::kInf, &t0, &t1) && std::isfinite(t1)) return t1;
  return len > 0.0f ? 2.0f * diag / len : 1.0f;
}

// ---------------------------------------------------------------------------------------
// Compare

std::vector<CompareRow> compare_structures(std::shared_ptr<const accel::Scene> scene, const accel::Ray& ray,
                                           const StructureRequest& current, const std::atomic<bool>& cancel,
                                           std::atomic<int>* progress) {
  std::vector<CompareRow> rows;
  for (const accel::StructureInfo& info : accel::structure_registry()) {
    // Students' structures other than the one shown stay out: their code is not this
    // comparison's to run (it may be half-written, or crash).
    if (info.student && info.name != current.name) continue;
    const std::vector<std::string> base = info.name == current.name ? current.params : std::vector<std::string>{};
    std::vector<std::string> traversals;
    std::string default_traversal;
    for (const accel::ParamSpec& spec : info.params) {
      if (spec.name == "traversal" && spec.type == accel::ParamSpec::Type::Choice) {
        traversals = spec.choices;
        default_traversal = spec.default_value;
      }
    }
    if (traversals.empty()) traversals.push_back("");
    for (const std::string& traversal : traversals) {
      CompareRow row;
      row.structure = info.name;
      row.label = info.name + (traversal.empty() ? "" : " (" + traversal + ")");
      row.params = traversal.empty() ? base : with_param(base, "traversal", traversal);
      row.current = info.name == current.name &&
                    (traversal.empty() || param_value(current.params, "traversal", default_traversal) == traversal);
      rows.push_back(std::move(row));
    }
  }
  for (CompareRow& row : rows) {
    if (cancel.load()) break;
    const auto start = std::chrono::steady_clock::now();
    auto built = accel::build_structure(row.structure, *scene, row.params, current.kernel);
    row.build_ms = ms_since(start);
    if (!built) {
      row.error = built.error().message;
    } else {
      row.hit = built.value()->intersect(ray, &row.stats);
      accel::TraceRecorder recorder;
      built.value()->intersect_traced(ray, recorder);
      row.steps = recorder.events().size();
      row.ok = true;
    }
    if (progress) progress->fetch_add(1);
  }
  return rows;
}

// ---------------------------------------------------------------------------------------
// Sweep

std::vector<double> sweep_values(const accel::ParamSpec& spec, double lo, double hi, int steps, bool log_scale) {
  std::vector<double> values;
  lo = std::clamp(lo, spec.min, spec.max);
  hi = std::clamp(hi, spec.min, spec.max);
  if (hi < lo) std::swap(lo, hi);
  steps = std::max(steps, 1);
  const bool geometric = log_scale && lo > 0.0;
  for (int i = 0; i < steps; ++i) {
    const double f = steps == 1 ? 0.0 : double(i) / double(steps - 1);
    double v = geometric ? lo * std::pow(hi / lo, f) : lo + f * (hi - lo);
    if (spec.type == accel::ParamSpec::Type::Int) v = std::round(v);
    v = std::clamp(v, spec.min, spec.max);
    if (values.empty() || v != values.back()) values.push_back(v);
  }
  return values;
}

accel::Status run_sweep(std::shared_ptr<const accel::Scene> scene, const SweepRequest& request,
                              SweepProgress& progress, const std::atomic<bool>& cancel) {
  auto info = accel::find_structure(request.base.name);
  if (!info) return info.error();
  const accel::ParamSpec* spec = nullptr;
  for (const accel::ParamSpec& s : info.value()->params)
    if (s.name == request.param) spec = &s;
  if (!spec || (spec->type != accel::ParamSpec::Type::Int && spec->type != accel::ParamSpec::Type::Float))
    return accel::make_error("sweep: '" + request.param + "' is not a numeric parameter of " + request.base.name);
  const bool integer = spec->type == accel::ParamSpec::Type::Int;
  const std::vector<double> values = sweep_values(*spec, request.lo, request.hi, request.steps, request.log_scale);
  {
    std::lock_guard lock(progress.mutex);
    progress.points.clear();
    progress.total = int(values.size());
  }
  const std::vector<accel::Ray> rays = accel::primary_rays(request.camera, request.width, request.height);
  for (double v : values) {
    if (cancel.load()) break;
    SweepPoint point;
    point.value = v;
    point.text = number_text(v, integer);  // the label; the parameter gets the exact value
    const auto params =
        with_param(request.base.params, request.param, integer ? point.text : accel::format_param_number(v));
    const auto start = std::chrono::steady_clock::now();
    auto built = accel::build_structure(request.base.name, *scene, params, request.base.kernel);
    point.build_ms = ms_since(start);
    if (!built) {
      point.error = built.error().message;
    } else {
      const accel::Structure& s = *built.value();
      const accel::BuildStats stats = s.build_stats();
      point.build_ms = stats.build_ms;
      point.nodes = stats.nodes;
      point.sah_cost = stats.sah_cost;
      // Best of three: the machine is shared, the minimum is the least disturbed run.
      point.trace_ms = 1e300;
      accel::QueryStats total;
      for (int rep = 0; rep < 3 && !cancel.load(); ++rep) {
        accel::QueryStats q;
        const auto t = std::chrono::steady_clock::now();
        accel::trace_all(s, rays, 0, &q);
        point.trace_ms = std::min(point.trace_ms, ms_since(t));
        total = q;
      }
      const double n = double(std::max<size_t>(rays.size(), 1));
      point.nodes_per_ray = double(total.nodes_visited) / n;
      point.prims_per_ray = double(total.prims_tested) / n;
      point.ok = true;
    }
    std::lock_guard lock(progress.mutex);
    progress.points.push_back(std::move(point));
  }
  return {};
}

}  // namespace viz
