#pragma once
// The Tree window's colours, shared by its panel (tree_diagram.cpp: the legend, the cell
// walk) and its canvas (tree_diagram_canvas.cpp: the nodes and edges), so the legend always
// says what the diagram draws.
#include <imgui.h>

#include "tools/tree_layout.h"
#include "tools/ui_colors.h"

namespace viz::tree_colors {

/// `c` with its alpha scaled by `alpha_scale`, for ImDrawList.
inline ImU32 color_u32(const ImVec4& c, float alpha_scale = 1.0f) {
  return ImGui::GetColorU32(ImVec4(c.x, c.y, c.z, c.w * alpha_scale));
}

/// A node's colour in its state at the step (culled nodes by their reason); grey when not reached.
inline ImVec4 state_color(const TreeNodeStatus& s) {
  switch (s.state) {
    case TreeNodeState::Current: return ui::kCurrentText;
    case TreeNodeState::Visited: return ui::kVisitedText;
    case TreeNodeState::OnStack: return ui::kQueueText;
    case TreeNodeState::Culled:
      return s.reason == accel::CullReason::MissedBounds ? ui::kCullMissedText : ui::kCullText;
    case TreeNodeState::NotReached: break;
  }
  return ImVec4(0.42f, 0.45f, 0.52f, 1.0f);
}

}  // namespace viz::tree_colors
