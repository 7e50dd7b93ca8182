#include "tools/sweep_model.h"

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
        accel::with_param(request.base.params, request.param, integer ? point.text : accel::format_param_number(v));
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
