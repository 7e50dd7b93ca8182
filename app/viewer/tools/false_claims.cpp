#include "tools/false_claims.h"

namespace viz {

std::vector<const accel::FalseClaim*> claims_at(const std::optional<accel::WalkAudit>& audit, size_t step) {
  std::vector<const accel::FalseClaim*> found;
  if (!audit) return found;
  for (const accel::FalseClaim& c : audit->claims)
    if (c.step == step) found.push_back(&c);
  return found;
}

std::optional<size_t> shown_vars_event(std::span<const accel::TraceEvent> events,
                                       std::span<const accel::RecordedVars> vars, size_t step) {
  const accel::StepVars* shown = accel::vars_at(events, vars, step);
  if (!shown) return std::nullopt;
  for (const accel::RecordedVars& r : vars)
    if (&r.vars == shown) return r.event;
  return std::nullopt;
}

std::string false_claim_text(const accel::FalseClaim& claim) {
  return "FALSE: the log says \"" + claim.claim + "\"; true: " + claim.truth;
}

bool event_is_claim(const accel::TraceEvent& e) { return e.kind == accel::TraceEventKind::Cull; }

std::string step_text(const accel::TraceEvent& e, std::span<const accel::FalseClaim* const> claims) {
  if (claims.empty()) return accel::describe_event(e);
  std::string text = event_is_claim(e) ? "" : accel::describe_event(e) + " -- ";
  for (size_t i = 0; i < claims.size(); ++i) text += (i ? " / " : "") + false_claim_text(*claims[i]);
  return text;
}

std::string claims_summary(const accel::WalkAudit& audit) {
  const size_t n = audit.claims.size();
  if (n == 0) return "the kit found no false claim in this walk";
  // The audit keeps the first kMaxClaims: a walk that lies at every step says so.
  const std::string count = (n >= accel::WalkAudit::kMaxClaims ? "at least " : "") + std::to_string(n);
  return "the kit found " + count + (n == 1 ? " false claim" : " false claims") + " in this walk (first at step " +
         std::to_string(audit.claims.front().step + 1) + ")";
}

std::vector<std::string> claims_lines(const std::optional<accel::WalkAudit>& audit) {
  if (!audit) return {"claims: none (a built-in structure: not audited)"};
  if (audit->claims.empty()) return {"claims: none"};
  std::vector<std::string> lines;
  for (const accel::FalseClaim& c : audit->claims)
    lines.push_back("claim " + std::to_string(c.step + 1) + ": " + c.cause + ": " + c.claim + " -- " + c.truth);
  return lines;
}

}  // namespace viz
