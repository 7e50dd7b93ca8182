#pragma once
// The structure session's script verbs (commands.h): the scene, the structure and how it is
// built. GL-free: the catalogue (script_verbs.h) reads them without their runs;
// StructureSession::add_verbs() binds them to the session.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "batch.h"
#include "commands.h"
#include "geometry.h"
#include "memory_budget.h"
#include "presets.h"
#include "ray_gen.h"
#include "registry.h"

namespace viz {

struct StructureArgs {
  std::string name;
  std::vector<std::string> params;  ///< key=value
  /// The N of a `construct-until N` after it (a failed build's replay: its build stops
  /// there too), else 0; set by parse_script().
  size_t calls = 0;
};

struct KernelArgs {
  accel::Kernel kernel = accel::Kernel::Watertight;
};

struct MemoryLimitArgs {
  size_t bytes = 0;  ///< 0: the default
};

/// After a change of scene or structure: the other tools hear of it, and in script mode the
/// structure must be there before the next command.
template <class Host>
accel::Status session_changed(Host& host, const accel::Status& st) {
  host.sync_session();
  return st ? host.loaded() : st;
}

template <class Verbs>
void structure_session_verbs(Verbs& verbs) {
  verbs.template add<Word>("scene", "scene PATH | scene procedural:NAME", "load a scene", parse_one_word,
                           [](auto& session, auto& host, const Word& spec, ScriptHost&) -> accel::Status {
                             return session_changed(host, session.load_scene(spec.word));
                           });
  verbs.template add<Word>(
      "preset", "preset NAME", "a preset: scene, camera, ray", parse_one_word,
      [](auto& session, auto& host, const Word& name, ScriptHost& script) -> accel::Status {
        const Preset* preset = find_preset(session.presets(), name.word);
        if (!preset) {
          std::string names;
          for (const Preset& q : session.presets()) names += (names.empty() ? "" : ", ") + q.name;
          return accel::make_error("unknown preset '" + name.word + "' (valid: " + names + ")");
        }
        script.render(1);  // the current layout: the preset's centre ray goes through the 3D view's centre
        if (auto st = host.apply_preset(*preset); !st) return st;
        return host.loaded();
      });
  verbs.template add<StructureArgs>(
      "structure", "structure NAME [key=value ...]", "as `accelviz-cli --structure NAME --param key=value`",
      [](const VerbArgs& a, StructureArgs& s) -> std::string {
        if (a.size() < 1) return a.usage_error();
        s.name = a[0];
        s.params.assign(a.words().begin() + 1, a.words().end());
        auto choice = accel::parse_structure(s.name, s.params);
        return choice ? "" : choice.error().message;
      },
      [](auto& session, auto& host, const StructureArgs& s, ScriptHost&) -> accel::Status {
        session.switch_structure(s.name, s.params, s.calls);
        if (s.calls == 0) return session_changed(host, {});
        // A failed build's replay (construct-until follows): its build stopped, so there is
        // no structure to wait for; the construct-until says how the replay went.
        host.sync_session();
        return {};
      });
  verbs.template add<KernelArgs>(
      "kernel", "kernel watertight|moller|double", "the ray/triangle test",
      [](const VerbArgs& a, KernelArgs& s) -> std::string {
        if (a.size() != 1 || !accel::parse_kernel(a[0], &s.kernel)) return a.usage_error();
        return "";
      },
      [](auto& session, auto& host, const KernelArgs& s, ScriptHost&) -> accel::Status {
        session.set_kernel(s.kernel);
        return session_changed(host, {});
      });
  verbs.template add<MemoryLimitArgs>(
      "memory-limit", "memory-limit SIZE | memory-limit default",
      "the builds' memory budget (512M, 4G, 25%), as `accelviz-cli --memory-limit`; a build over it is a script "
      "error",
      [](const VerbArgs& a, MemoryLimitArgs& s) -> std::string {
        if (a.size() != 1) return a.usage_error() + " (SIZE: 512M, 4G, 25%)";
        if (a[0] == "default") return "";
        auto bytes = accel::parse_memory_size(a[0], "memory-limit");
        if (!bytes) return bytes.error().message;
        s.bytes = bytes.value();
        return "";
      },
      [](auto& session, auto& host, const MemoryLimitArgs& s, ScriptHost&) -> accel::Status {
        session.set_memory_limit(s.bytes);
        return session_changed(host, {});
      });
  verbs.template add<NoArgs>(
      "print-stats", "print-stats", "the build statistics of the current structure, one line", parse_no_words,
      [](auto& session, auto&, const NoArgs&, ScriptHost&) -> accel::Status {
        if (auto st = session.need_structure(); !st) return st;
        const auto& b = *session.current();
        const accel::BuildStats& s = b.stats;
        std::printf("stats %s %s nodes %zu leaves %zu depth %d memory %zu build_ms %.3f sah %.4g\n",
                    b.request.name.c_str(), b.params_text.c_str(), s.nodes, s.leaves, s.max_depth, s.memory_bytes,
                    s.build_ms, s.sah_cost);
        std::fflush(stdout);
        return {};
      });
  verbs.template add<Word>(
      "trace-rays", "trace-rays random:N:SEED|primary:W:H|FILE",
      "trace a batch of rays (SPEC as `accelviz-cli --rays` takes it) through the current structure on one thread; "
      "prints `trace-rays SPEC: N rays, H hits, T ms (1 thread)`",
      parse_one_word, [](auto& session, auto&, const Word& spec, ScriptHost&) -> accel::Status {
        if (auto st = session.need_structure(); !st) return st;
        auto rays = accel::make_rays(spec.word, session.scene());
        if (!rays) return accel::make_error("trace-rays: " + rays.error().message);
        // One thread: the same work natively and in the page, which has only one.
        const auto start = std::chrono::steady_clock::now();
        const std::vector<accel::Hit> hits = accel::trace_all(*session.current()->structure, rays.value(), 1);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        const size_t hit_count =
            size_t(std::count_if(hits.begin(), hits.end(), [](const accel::Hit& h) { return h.valid(); }));
        std::printf("trace-rays %s: %zu rays, %zu hits, %.1f ms (1 thread)\n", spec.word.c_str(), hits.size(),
                    hit_count, ms);
        std::fflush(stdout);
        return {};
      });
}

}  // namespace viz
