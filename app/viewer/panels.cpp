#include "panels.h"

#include <cstdio>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "scene.h"

namespace viz {
namespace {

// Red that stays legible on the dark panel background, also through a projector.
const ImVec4 kErrorColor(1.0f, 0.42f, 0.38f, 1.0f);

// 1234567 -> "1,234,567": triangle counts of real scenes are long numbers.
std::string with_separators(size_t n) {
  std::string digits = std::to_string(n);
  std::string out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string format_vec(const accel::Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%.4g, %.4g, %.4g)", v.x, v.y, v.z);
  return text;
}

// One label/value row of the statistics table.
void stat_row(const char* label, const std::string& value) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextDisabled("%s", label);
  ImGui::TableSetColumnIndex(1);
  ImGui::TextUnformatted(value.c_str());
}

// Long paths would stretch the auto-sized panel across the screen: keep the tail, which
// names the file, and show the whole path as a tooltip.
void path_row(const char* label, const std::string& path) {
  constexpr size_t kMaxChars = 40;
  if (path.size() <= kMaxChars) {
    stat_row(label, path);
    return;
  }
  stat_row(label, "..." + path.substr(path.size() - (kMaxChars - 3)));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", path.c_str());
}

}  // namespace

ScenePanelActions scene_panel(const SceneInfo& scene, const FrameTiming& timing,
                              ScenePanelState& state) {
  ScenePanelActions actions;
  const float em = ImGui::GetFontSize();
  ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.88f);
  if (!ImGui::Begin("Scene", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return actions;
  }

  if (ImGui::BeginTable("stats", 2, ImGuiTableFlags_SizingFixedFit)) {
    path_row("name", scene.name.empty() ? std::string("(unnamed)") : scene.name);
    path_row("source", scene.spec);
    stat_row("triangles", with_separators(scene.triangles));
    stat_row("vertices", with_separators(scene.vertices));
    stat_row("degenerate", with_separators(scene.degenerate));
    if (scene.bounds.empty()) {
      stat_row("bounds", "(empty)");
    } else {
      stat_row("bounds min", format_vec(scene.bounds.min));
      stat_row("bounds max", format_vec(scene.bounds.max));
      stat_row("size", format_vec(scene.bounds.extent()));
    }
    char text[64];
    std::snprintf(text, sizeof(text), "%.1f ms", scene.load_ms);
    stat_row("load time", text);
    std::snprintf(text, sizeof(text), "%.2f ms  (%.0f fps)", timing.frame_ms, timing.fps);
    stat_row("frame time", text);
    ImGui::EndTable();
  }
  if (ImGui::Button("Frame scene (F)")) actions.frame_scene = true;

  ImGui::Separator();
  ImGui::TextDisabled("Load");
  // Procedural presets: the scenes every lecture can rely on, with their description
  // as tooltip.
  if (!state.presets.empty()) {
    const int count = static_cast<int>(state.presets.size());
    if (state.preset < 0 || state.preset >= count) state.preset = 0;
    ImGui::SetNextItemWidth(14.0f * em);
    if (ImGui::BeginCombo("##preset", state.presets[static_cast<size_t>(state.preset)].c_str())) {
      for (int i = 0; i < count; ++i) {
        const std::string& name = state.presets[static_cast<size_t>(i)];
        if (ImGui::Selectable(name.c_str(), i == state.preset)) state.preset = i;
        if (ImGui::IsItemHovered()) {
          const std::string description = accel::procedural_scene_description(name);
          if (!description.empty()) ImGui::SetTooltip("%s", description.c_str());
        }
      }
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Button("Load preset"))
      actions.load = "procedural:" + state.presets[static_cast<size_t>(state.preset)];
  }

  ImGui::SetNextItemWidth(14.0f * em);
  const bool entered = ImGui::InputTextWithHint("##obj", "path/to/scene.obj", &state.obj_path,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  const bool clicked = ImGui::Button("Load OBJ");
  if ((entered || clicked) && !state.obj_path.empty()) actions.load = state.obj_path;
  ImGui::TextDisabled("or drop an .obj file onto the window");

  if (!state.load_error.empty()) {
    // Wrap at the panel's width so a long path cannot stretch the auto-sized window.
    ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 24.0f * em);
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", state.load_error.c_str());
    ImGui::PopStyleColor();
    ImGui::PopTextWrapPos();
  }

  ImGui::Separator();
  ImGui::TextDisabled("left drag: orbit   right/middle drag: pan");
  ImGui::TextDisabled("wheel: zoom   F: frame scene   H: hide panel");
  ImGui::End();
  return actions;
}

}  // namespace viz
