#include "tools/compare_model.h"

#include <chrono>

#include "params.h"
#include "registry.h"

namespace viz {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

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
      row.params = traversal.empty() ? base : accel::with_param(base, "traversal", traversal);
      row.current =
          info.name == current.name &&
          (traversal.empty() || accel::param_value(current.params, "traversal", default_traversal) == traversal);
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

}  // namespace viz
