// libFuzzer target: `--param` values and whole parameter sets (core/params.cpp), the
// memory sizes of `--memory-limit` (core/memory_budget.cpp), and the build they configure.
// Input: a first line "STRUCTURE [MEMORY-LIMIT]", then one key=value per line. An unknown
// structure name picks one by its first byte, so mutations keep reaching the builders.
//
// Values valid one by one can explode together (a fine grid over slivers, a deep octree
// over identical triangles); every accepted set is built on a small adversarial scene under
// a 64 MiB budget and a 1 s time limit, so a builder that ignores the budget shows up as the
// fuzzer's out-of-memory report (-rss_limit_mb) and one that ignores the clock as a timeout.
#include <sstream>

#include "fuzz_support.h"
#include "memory_budget.h"

namespace {

/// Identical triangles, long overlapping slivers and a few small ones: the shapes whose
/// references multiply in grids, octrees and kd-trees.
accel::Scene adversarial_scene() {
  std::vector<accel::Vec3> p;
  std::vector<accel::UVec3> t;
  auto tri = [&](accel::Vec3 a, accel::Vec3 b, accel::Vec3 c) {
    const uint32_t i = uint32_t(p.size());
    p.insert(p.end(), {a, b, c});
    t.push_back({i, i + 1, i + 2});
  };
  for (int i = 0; i < 48; ++i) tri({0, 0, 0}, {1, 0, 0}, {0, 1, 0});  // identical
  for (int i = 0; i < 48; ++i) {                                     // slivers across the box
    const float y = 0.01f * float(i);
    tri({-4, y, 0.5f}, {4, y + 0.001f, 0.5f}, {4, y, 0.501f});
  }
  for (int i = 0; i < 32; ++i) {  // small ones in a corner
    const float x = 3.0f + 0.02f * float(i);
    tri({x, 3, 3}, {x + 0.01f, 3, 3}, {x, 3.01f, 3});
  }
  return accel::Scene(std::move(p), std::move(t), "adversarial");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::string first, line;
  std::getline(in, first);
  std::istringstream head(first);
  std::string name, limit_text;
  head >> name >> limit_text;

  const auto& registry = accel::structure_registry();
  auto found = accel::find_structure(name);
  const accel::StructureInfo& info = found ? *found.value() : registry[data[0] % registry.size()];

  size_t limit = size_t(64) << 20;
  if (!limit_text.empty()) {
    auto parsed = accel::parse_memory_size(limit_text, "--memory-limit");
    if (parsed) limit = std::min(limit, parsed.value());
    else if (parsed.error().message.find("--memory-limit") == std::string::npos) std::abort();
  }

  std::vector<std::string> key_values;
  while (std::getline(in, line) && key_values.size() < 16) key_values.push_back(line);
  auto params = accel::ParamSet::parse(info.params, key_values, info.name);
  if (!params) {
    if (params.error().message.find('\n') != std::string::npos) std::abort();
    return 0;
  }
  // What the CLI echoes must parse back to the same set.
  auto again = accel::ParamSet::parse(info.params, params.value().explicit_key_values(), info.name);
  if (!again || again.value().to_string() != params.value().to_string()) std::abort();

  static const accel::Scene scene = adversarial_scene();
  static const std::vector<accel::Ray> rays = accel::random_rays(scene.bounds(), 64, 3);
  accel::BuildControl control;
  control.set_memory_limit(limit);
  control.set_time_limit(1.0);
  auto built = accel::build_structure(info, scene, params.value(), accel::Kernel::Watertight, &control);
  if (!built) {
    if (built.error().message.find('\n') != std::string::npos) std::abort();
    return 0;
  }
  (void)accel::trace_all(*built.value(), rays, 1);
  return 0;
}
