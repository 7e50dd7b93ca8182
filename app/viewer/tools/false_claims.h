#pragma once
// The kit's reading of a student's walk, in the ray debugger's words (GL-free half; the ray
// debugger's panels and the Variables panel draw it). A student's traversal log makes claims
// -- a node skipped as beyond the closest hit, an early exit, a kd-tree case -- and the
// viewer narrates each step from them; core/student/walk_audit.h checks every claim against
// the geometry. Where one is false the step is said to be FALSE, with the truth beside it,
// never repeated as if it held. Built-in structures are never audited: their walk is the
// core's own. tests/app/test_false_claims.cpp drives it without a window.
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "student/walk_audit.h"
#include "trace.h"

namespace viz {

/// The false claims at event `step`, in the audit's order (an octree node's children can
/// make several); empty without an audit.
std::vector<const accel::FalseClaim*> claims_at(const std::optional<accel::WalkAudit>& audit, size_t step);

/// The event the variables shown at `step` were recorded after (accel::vars_at's choice),
/// or nothing when no variables are shown there. A kd-tree's early exit is recorded at the
/// pop and still shown at the cull that follows it: its claim belongs to the pop.
std::optional<size_t> shown_vars_event(std::span<const accel::TraceEvent> events,
                                       std::span<const accel::RecordedVars> vars, size_t step);

/// "FALSE: the log says \"CLAIM\"; true: TRUTH".
std::string false_claim_text(const accel::FalseClaim& claim);

/// One line for step `e` with its false claims: accel::describe_event's sentence when there
/// are none; otherwise the FALSE text, after the event's sentence unless the event is the
/// claim itself (a cull: "skip node 5: entry beyond the closest hit" would repeat it).
std::string step_text(const accel::TraceEvent& e, std::span<const accel::FalseClaim* const> claims);

/// Whether step `e` is itself the claim (a cull): its sentence is then left out.
bool event_is_claim(const accel::TraceEvent& e);

/// "the kit found N false claims in this walk (first at step K)" (K counted from 1, as the
/// steps are shown), or "... no false claim ...".
std::string claims_summary(const accel::WalkAudit& audit);

/// print-claims: one line per false claim, "claim STEP: CAUSE: CLAIM -- TRUTH" (STEP from 1,
/// CAUSE a cause id of walk_audit.h); "claims: none" when the kit found none; for a walk
/// that was not audited (a built-in structure) "claims: none (a built-in structure: not
/// audited)".
std::vector<std::string> claims_lines(const std::optional<accel::WalkAudit>& audit);

}  // namespace viz
