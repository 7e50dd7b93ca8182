#include "tools/status_overlay.h"

#include <imgui.h>

#include "tool_host.h"
#include "tools/build_player.h"
#include "tools/heatmap_tool.h"
#include "tools/recorder.h"
#include "tools/structure_session.h"
#include "tools/ui_colors.h"
#include "window_layout.h"

namespace viz {

void StatusOverlay::overlay(ToolHost& host) {
  const WindowLayout& layout = host.layout();
  if (!layout.ui_visible()) return;
  const StructureSession& session = host.session();
  const HeatmapTool& heatmap = host.tool<HeatmapTool>();
  const BuildPlayer& build = host.build();
  const bool building = session.building();
  const bool waiting_heatmap = heatmap.computing();
  const bool recording = build.recording();
  // A recording with the panels would record its own notice: the title says it instead.
  const Recorder& recorder = host.tool<Recorder>();
  const std::string notice = recorder.recording_ui() ? std::string() : recorder.notice();
  if (!building && !waiting_heatmap && !recording && notice.empty()) return;
  const float em = ImGui::GetFontSize();
  glm::vec2 pos = layout.rects().status.pos;
  if (layout.panels().legend && heatmap.on()) pos.y += 7.5f * em;  // below the legend
  ImGui::SetNextWindowPos(ImVec2(pos.x, pos.y), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  if (building) {
    ImGui::TextColored(ui::kCurrentText, "building %s ... %.1f s (the old structure stays until it is ready)",
                       session.requested_name().c_str(), session.build_seconds());
    ImGui::ProgressBar(static_cast<float>(session.build_fraction()), ImVec2(20.0f * em, 0.4f * em), "");
  }
  if (recording) {
    ImGui::TextColored(ui::kCurrentText, "recording the construction ... %.1f s", build.recording_seconds());
    ImGui::ProgressBar(static_cast<float>(build.recording_fraction()), ImVec2(20.0f * em, 0.4f * em), "");
  }
  if (!notice.empty()) ImGui::TextColored(ui::kCurrentText, "%s", notice.c_str());
  if (waiting_heatmap) {
    const glm::ivec2 size = heatmap.computing_size();
    ImGui::TextDisabled("heat map: tracing %dx%d rays ...", size.x, size.y);
  }
  ImGui::End();
}

}  // namespace viz
