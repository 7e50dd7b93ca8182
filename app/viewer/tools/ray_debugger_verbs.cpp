// The ray debugger's script verbs, GL-free half (script_verbs.h): the debug ray, stepping
// through its traversal, and what it prints. The run half is RayDebugger::script_verbs().
#include <cmath>
#include <limits>

#include "rays_io.h"
#include "script_verbs.h"

namespace viz {
namespace {

const ScriptVerb kVerbs[] = {
    {"ray-at-pixel", CommandKind::RayAtPixel, "ray-at-pixel X Y", "shoot like a click; pixel from the top-left",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 2) return a.usage_error();
       return a.finite_values(0, 2, c);
     }},
    {"ray", CommandKind::Ray, "ray OX OY OZ DX DY DZ [TMIN TMAX]", "shoot a given ray (TMAX may be `inf`)",
     [](const VerbArgs& a, ScriptCommand& c) -> std::string {
       if (a.size() != 6 && a.size() != 8) return a.usage_error();
       if (auto e = a.finite_values(0, 6, c); !e.empty()) return e;
       if (c.values[3] == 0.0f && c.values[4] == 0.0f && c.values[5] == 0.0f) return "ray: the direction is zero";
       c.values[6] = 0.0f;
       c.values[7] = std::numeric_limits<float>::infinity();
       if (a.size() == 8) {  // as in a rays file: TMAX may be inf; TMIN <= TMAX
         if (!parse_finite(a[6], &c.values[6])) return "'" + a[6] + "' is not a finite number (" + a.usage() + ")";
         if (!accel::parse_ray_number(a[7], &c.values[7]) || std::isnan(c.values[7]) || c.values[7] == -INFINITY)
           return "'" + a[7] + "' is not a number or inf (" + a.usage() + ")";
         if (!(c.values[6] <= c.values[7])) return "ray: TMIN is greater than TMAX";
       }
       return "";
     }},
    {"step", CommandKind::Step, "step N | step end | step back N | step hit | step start", "move the traversal player",
     [](const VerbArgs& a, ScriptCommand& c) { return parse_step_words(a, c, /*hit=*/true); }},
    {"frames", CommandKind::Frames, "frames PREFIX", "`PREFIX0000.png` ... one PNG per remaining step", parse_one_word},
    {"print-hit", CommandKind::PrintHit, "print-hit", "`hit PRIM T` or `miss`", parse_no_words},
    {"print-step", CommandKind::PrintStep, "print-step", "the current step as one line", parse_no_words},
    {"print-ray", CommandKind::PrintRay, "print-ray",
     "the ray as C99 hex floats, `ox oy oz dx dy dz` (a rays-file line)", parse_no_words},
    {"print-vars", CommandKind::PrintVars, "print-vars",
     "`vars: name=value ...` of the current step (the traversal's recorded variables, closest_hit, the stack or "
     "queue as NODE:KEY,...)",
     parse_no_words},
    {"print-claims", CommandKind::PrintClaims, "print-claims",
     "a student's structure: `claim STEP: CAUSE: CLAIM -- TRUTH` per logged claim the kit found false on this walk "
     "(STEP as print-step counts), or `claims: none`",
     parse_no_words},
};

}  // namespace

std::span<const ScriptVerb> ray_debugger_verbs() { return kVerbs; }

}  // namespace viz
