#pragma once
// Text colours of the ray debugger's panels and the compare table: the same meaning as the
// 3D highlights (tools/highlights.cpp). Shared by the tools' panels, hence one header.
#include <imgui.h>

#include "color_scheme.h"

namespace viz::ui {

inline const ImVec4 kCurrentText(1.0f, 0.85f, 0.1f, 1.0f);
inline const ImVec4 kCullText(1.0f, 0.55f, 0.3f, 1.0f);
/// A triangle test that hits / misses: the colour scheme's pair (blue / orange by default,
/// colour-blind safe; color_scheme.h), lightened a little for text.
inline ImVec4 hit_text() {
  const glm::vec3 c = glm::mix(hit_rgb(), glm::vec3(1.0f), 0.1f);
  return ImVec4(c.r, c.g, c.b, 1.0f);
}
inline ImVec4 miss_text() {
  const glm::vec3 c = glm::mix(miss_rgb(), glm::vec3(1.0f), 0.1f);
  return ImVec4(c.r, c.g, c.b, 1.0f);
}
inline const ImVec4 kQueueText(0.35f, 0.85f, 1.0f, 1.0f);
inline const ImVec4 kDimText(0.62f, 0.65f, 0.72f, 1.0f);
// The tree diagram's node states, as the 3D highlights draw them (trail, missed, selection).
inline const ImVec4 kVisitedText(0.85f, 0.88f, 0.95f, 1.0f);
inline const ImVec4 kCullMissedText(0.7f, 0.55f, 1.0f, 1.0f);
inline const ImVec4 kSelectedText(1.0f, 0.3f, 0.9f, 1.0f);
/// A student's logged claim that the geometry contradicts (tools/false_claims.h): a red apart
/// from the skipped nodes' orange, so a false skip never reads as an ordinary one.
inline const ImVec4 kFalseClaimText(1.0f, 0.3f, 0.3f, 1.0f);

}  // namespace viz::ui
