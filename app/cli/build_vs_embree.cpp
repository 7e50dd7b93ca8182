// accelviz-cli build-vs-embree: the default BVH's cold build against Embree medium's, each the
// first build of a fresh process (issue #51). A cold build is what every CLI run and the
// viewer's first build of a scene pay: TBB's threads start, the allocator's first pages are
// faulted in. Timing both in one process would hand the second one a warm start, so every
// build runs in a child of its own (this program again, with the hidden --child option), the
// two sides alternating which goes first, and the parent keeps each side's median.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "embree_baseline.h"
#include "parallel.h"
#include "registry.h"
#include "rays_io.h"
#include "scene.h"
#include "text_format.h"

extern char** environ;

namespace cli {

using accel::fixed;

namespace {

int fail(const std::string& message) {
  std::fprintf(stderr, "accelviz-cli: build-vs-embree: %s\n", message.c_str());
  return kExitBadInput;
}

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// The child: loads the scene (not timed), times its side's first build, then two more in
/// the same process (the warm figure, as `bench` takes it), and prints one JSON line.
int run_child(const BuildVsEmbreeOptions& o) {
  auto scene = accel::load_scene(o.scenes.front());
  if (!scene) return fail(scene.error().message);
  nlohmann::json out;
  out["triangles"] = scene.value().triangle_count();
  std::vector<double> builds;
  if (o.child == "embree") {
    for (int i = 0; i < 3; ++i) {
      // The device is made before EmbreeScene's clock starts (as in `bench`); its time is
      // reported beside the build, not in it.
      const auto start = std::chrono::steady_clock::now();
      EmbreeScene embree(scene.value(), "medium", o.threads);
      if (i == 0) out["device_ms"] = ms_since(start) - embree.build_ms();
      builds.push_back(embree.build_ms());
    }
  } else {
    auto choice = accel::parse_structure("bvh", {});
    if (!choice) return fail(choice.error().message);
    accel::par::task_arena arena(o.threads > 0 ? o.threads : accel::par::task_arena::automatic);
    for (int i = 0; i < 3; ++i) {
      accel::Result<std::unique_ptr<accel::Structure>> built = accel::make_error("not built");
      const auto start = std::chrono::steady_clock::now();
      arena.execute([&] {
        built = accel::build_structure(*choice.value().info, scene.value(), choice.value().params,
                                       accel::Kernel::Watertight);
      });
      builds.push_back(ms_since(start));
      if (!built) return fail(built.error().message);
    }
  }
  out["cold_ms"] = builds.front();
  out["warm_ms"] = *std::min_element(builds.begin() + 1, builds.end());
  std::printf("%s\n", out.dump().c_str());
  return 0;
}

/// Runs this program as a child for one side's builds; its one JSON line, or an error that
/// carries the child's own message.
accel::Result<nlohmann::json> spawn_child(const std::string& scene, const std::string& side, int threads) {
  const std::string threads_text = std::to_string(threads);
  std::vector<std::string> args = {"accelviz-cli", "build-vs-embree", "--scene", scene,
                                   "--threads", threads_text, "--child", side};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int out_pipe[2];
  if (pipe(out_pipe) != 0) return accel::make_error(std::string("pipe: ") + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, out_pipe[0]);
  posix_spawn_file_actions_addclose(&actions, out_pipe[1]);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out_pipe[1]);
  if (spawned != 0) {
    close(out_pipe[0]);
    return accel::make_error(std::string("cannot start a child: ") + std::strerror(spawned));
  }
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = read(out_pipe[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) break;
    text.append(buffer, size_t(n));
  }
  close(out_pipe[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  // The child has already printed its one-line error on the shared stderr.
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return accel::make_error("");
  auto parsed = nlohmann::json::parse(text, nullptr, false);
  if (parsed.is_discarded() || !parsed.contains("cold_ms"))
    return accel::make_error("a child's output is not its JSON line: '" + text + "'");
  return parsed;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int run_build_vs_embree(const BuildVsEmbreeOptions& o) {
  if (!o.child.empty()) return run_child(o);
  if (!embree_available()) return fail("this accelviz-cli was built without Embree (libembree-dev)");
  for (const auto* out : {&o.out_json, &o.out_md})
    if (!out->empty())
      if (auto writable = accel::check_writable(*out); !writable) return fail(writable.error().message);
  nlohmann::json rows = nlohmann::json::array();
  std::ostringstream md;
  const int threads = o.threads > 0 ? o.threads : int(std::thread::hardware_concurrency());
  md << "| scene | triangles | accelviz cold ms | Embree medium cold ms | Embree / accelviz cold | accelviz warm ms "
        "| Embree warm ms | Embree / accelviz warm |\n|---|---:|---:|---:|---:|---:|---:|---:|\n";
  // The header comes with the first row: a scene that fails first leaves stdout empty.
  bool header_printed = false;
  for (const auto& scene : o.scenes) {
    std::vector<double> ours_cold, ours_warm, embree_cold, embree_warm, embree_device;
    size_t triangles = 0;
    for (int run = 0; run < o.runs; ++run) {
      // Alternating which side goes first, so neither always meets the other's file cache.
      for (int k = 0; k < 2; ++k) {
        const bool ours = (run + k) % 2 == 0;
        auto child = spawn_child(scene, ours ? "accelviz" : "embree", o.threads);
        if (!child) {
          if (child.error().message.empty()) return kExitBadInput;  // the child said why
          return fail(child.error().message);
        }
        const auto& j = child.value();
        triangles = j.value("triangles", size_t(0));
        (ours ? ours_cold : embree_cold).push_back(j["cold_ms"].get<double>());
        (ours ? ours_warm : embree_warm).push_back(j["warm_ms"].get<double>());
        if (!ours) embree_device.push_back(j.value("device_ms", 0.0));
      }
    }
    const double oc = median(ours_cold), ec = median(embree_cold);
    const double ow = median(ours_warm), ew = median(embree_warm);
    const double cold_ratio = oc > 0 ? ec / oc : 0.0, warm_ratio = ow > 0 ? ew / ow : 0.0;
    if (!header_printed) {
      std::printf("cold builds, each the first build of a fresh process, median of %d; %d threads\n", o.runs, threads);
      std::printf("%-34s %9s %12s %12s %8s   %s\n", "scene", "triangles", "accelviz ms", "Embree ms", "ratio",
                  "warm: accelviz ms, Embree ms, ratio");
      header_printed = true;
    }
    std::printf("%-34s %9zu %12.1f %12.1f %8.2f   %.1f, %.1f, %.2f\n", scene.c_str(), triangles, oc, ec, cold_ratio,
                ow, ew, warm_ratio);
    std::fflush(stdout);
    rows.push_back({{"scene", scene}, {"triangles", triangles}, {"threads", threads},
                    {"accelviz_cold_ms", ours_cold}, {"embree_cold_ms", embree_cold},
                    {"accelviz_cold_median_ms", oc}, {"embree_cold_median_ms", ec},
                    {"embree_over_accelviz_cold", cold_ratio}, {"accelviz_warm_median_ms", ow},
                    {"embree_warm_median_ms", ew}, {"embree_over_accelviz_warm", warm_ratio},
                    {"embree_device_median_ms", median(embree_device)}});
    md << "| " << scene << " | " << triangles << " | " << fixed(oc, "%.1f") << " | " << fixed(ec, "%.1f") << " | "
       << fixed(cold_ratio, "%.2f") << " | " << fixed(ow, "%.1f") << " | " << fixed(ew, "%.1f") << " | "
       << fixed(warm_ratio, "%.2f") << " |\n";
  }
  if (!o.out_json.empty())
    if (auto w = accel::write_file_atomic(o.out_json, rows.dump(1) + "\n"); !w) return fail(w.error().message);
  if (!o.out_md.empty())
    if (auto w = accel::write_file_atomic(o.out_md, md.str()); !w) return fail(w.error().message);
  return 0;
}

}  // namespace cli
