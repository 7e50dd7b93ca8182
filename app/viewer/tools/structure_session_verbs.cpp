// The structure session's script verbs, GL-free half (script_verbs.h): the scene, the
// structure and how it is built. The run half is StructureSession::script_verbs().
#include "geometry.h"
#include "memory_budget.h"
#include "registry.h"
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"scene", CommandKind::Scene, "scene PATH | scene procedural:NAME", "load a scene", parse_one_word},
    {"preset", CommandKind::Preset, "preset NAME", "a preset: scene, camera, ray", parse_one_word},
    {"structure", CommandKind::Structure, "structure NAME [key=value ...]",
     "as `accelviz-cli --structure NAME --param key=value`",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() < 1) return a.usage_error();
       c.name = a[0];
       c.params.assign(a.words().begin() + 1, a.words().end());
       auto choice = accel::parse_structure(c.name, c.params);
       return choice ? "" : choice.error().message;
     }},
    {"kernel", CommandKind::Kernel, "kernel watertight|moller|double", "the ray/triangle test",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       accel::Kernel k;
       if (a.size() != 1 || !accel::parse_kernel(a[0], &k)) return a.usage_error();
       c.name = a[0];
       return "";
     }},
    {"memory-limit", CommandKind::MemoryLimit, "memory-limit SIZE | memory-limit default",
     "the builds' memory budget (512M, 4G, 25%), as `accelviz-cli --memory-limit`; a build over it is a script "
     "error",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 1) return a.usage_error() + " (SIZE: 512M, 4G, 25%)";
       if (a[0] == "default") return "";
       auto bytes = accel::parse_memory_size(a[0], "memory-limit");
       if (!bytes) return bytes.error().message;
       c.bytes = bytes.value();
       return "";
     }},
    {"print-stats", CommandKind::PrintStats, "print-stats", "the build statistics of the current structure, one line",
     parse_no_words},
    {"trace-rays", CommandKind::TraceRays, "trace-rays random:N:SEED|primary:W:H|FILE",
     "trace a batch of rays (SPEC as `accelviz-cli --rays` takes it) through the current structure on one thread; "
     "prints `trace-rays SPEC: N rays, H hits, T ms (1 thread)`",
     parse_one_word},
};

}  // namespace

std::span<const ScriptVerb> structure_session_verbs() { return kVerbs; }

}  // namespace viz
