// App, part 2: the window layout, the panels shown, the main panel (each section belongs
// to a tool; the keys' help is made from their rows), the status overlay and the lecture
// mode.
#include <algorithm>
#include <cmath>

#include <imgui.h>

#include "app.h"
#include "bench_chart_panel.h"
#include "tools/ui_colors.h"

namespace viz {

void App::apply_lecture_mode() {
  if (lecture_mode_ == lecture_mode_applied_) return;
  lecture_mode_applied_ = lecture_mode_;
  ImGuiIO& io = ImGui::GetIO();
  io.FontDefault = lecture_mode_ ? fonts_.ui_large : fonts_.ui;
  ImGuiStyle& style = ImGui::GetStyle();
  ImGui::StyleColorsDark(&style);
  if (lecture_mode_) {
    // High contrast for a projector: black panels, white text, a black 3D background and
    // a brighter mesh; strong borders so panels separate from the scene.
    style.Colors[ImGuiCol_WindowBg] = ImVec4(0.0f, 0.0f, 0.0f, 0.94f);
    style.Colors[ImGuiCol_Text] = ImVec4(1.0f, 1.0f, 1.0f, 1.0f);
    style.Colors[ImGuiCol_TextDisabled] = ImVec4(0.78f, 0.8f, 0.85f, 1.0f);
    style.Colors[ImGuiCol_Border] = ImVec4(0.85f, 0.85f, 0.9f, 0.8f);
    style.Colors[ImGuiCol_FrameBg] = ImVec4(0.18f, 0.2f, 0.26f, 1.0f);
    style.WindowBorderSize = 2.0f;
    background_ = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  } else {
    style.WindowBorderSize = 1.0f;
    background_ = glm::vec4(0.075f, 0.085f, 0.105f, 1.0f);
  }
  nodes_.apply_lecture_colors(lecture_mode_);
  // The font takes effect at the next frame: lay out again then.
  layout_frames_ = 2;
}

void App::layout_windows() {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 display(io.DisplaySize.x, io.DisplaySize.y);
  if (display != layout_size_) {
    layout_size_ = display;
    layout_frames_ = 2;
  }
  layout_apply_ = layout_frames_ > 0;
  if (layout_frames_ > 0) --layout_frames_;
  layout_ = compute_layout(display, ImGui::GetFontSize(), lecture_mode_, panels_.main);
}

void App::set_panel(const std::string& name, bool on) {
  if (name == "all")
    ui_visible_ = on;
  else if (name == "scene")
    panels_.main = on;
  else if (name == "ray")
    panels_.ray = on;
  else if (name == "steps")
    panels_.steps = on;
  else if (name == "code")
    panels_.code = on;
  else if (name == "compare")
    compare_.set_open(on);
  else if (name == "sweep")
    sweep_.set_open(on);
  else if (name == "legend")
    panels_.legend = on;
  else if (name == "vars")
    vars_.set_shown(on);
  else if (name == "strip")
    vars_.set_strip_shown(on);
  else if (name == "trap")
    trap_.set_open(on);
  if (on && name != "all") ui_visible_ = true;
}

PanelPlace App::place(const WindowRect& rect, bool docks) { return {rect, layout_apply_, docks ? &dock_ : nullptr}; }

void App::main_panel() {
  WindowRect rect = layout_.main;
  if (!vars_column_) rect.size.y = layout_.vars.pos.y + layout_.vars.size.y - rect.pos.y;  // the whole column
  const PanelPlace where = place(rect);
  if (layout_apply_) ImGui::SetNextWindowCollapsed(lecture_mode_, ImGuiCond_Always);
  if (!ui::begin_panel(where, "accelviz")) return;
  ImGui::Text("frame %.1f ms (%.0f fps)", timing_.frame_ms, timing_.fps);
  ImGui::SameLine();
  ImGui::Checkbox("lecture (L)", &lecture_mode_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("large fonts, high contrast, controls collapsed");
  if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) {
    board_section();
    const SceneActions a = session_.scene_section(ray_.saved_view().has_value());
    if (a.load_preset >= 0) (void)apply_preset(session_.presets()[static_cast<size_t>(a.load_preset)]);  // shown in the panel
    if (a.frame) frame_scene();
    if (a.save_view) ray_.save_view(camera_.pinhole());
    if (a.go_to_saved && ray_.saved_view()) {
      const accel::PinholeCamera& v = *ray_.saved_view();
      camera_.look_at(v.eye, v.target, v.fovy_deg, session_.scene().bounds());
      frame_requested_ = false;
    }
  }
  if (ImGui::CollapsingHeader("Structure", ImGuiTreeNodeFlags_DefaultOpen)) {
    session_.structure_section();
    ImGui::BeginDisabled(!session_.current() || build_.recording());
    if (ImGui::Button("Construct (B)")) construct();
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("record the build and watch it step by step");
    ImGui::SameLine();
    bool mode = build_.active();
    if (ImGui::Checkbox("construction mode", &mode)) build_.set_active(mode);
  }
  if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (nodes_.section(session_.shown())) {
      session_.set_empty_cells(nodes_.empty_cells());
    }
    ray_.highlight_options();
    // Colours that carry meaning; the defaults are colour-blind safe (color_scheme.h).
    ColorScheme scheme = color_scheme();
    int map = static_cast<int>(scheme.map);
    const char* maps[] = {"viridis", "cividis", "turbo"};
    ImGui::SetNextItemWidth(8.0f * ImGui::GetFontSize());
    bool changed = ImGui::Combo("colour map", &map, maps, 3);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("depths, triangle counts and the heat map; viridis and cividis stay readable with "
                        "colour-vision deficiency and in greyscale");
    changed |= ImGui::Checkbox("hit/miss blue/orange", &scheme.cvd_safe_hits);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("colour-blind safe; off: green/red");
    if (changed) {
      scheme.map = static_cast<Colormap>(map);
      set_color_scheme(scheme);
      ray_.recolor();
    }
  }
  if (ImGui::CollapsingHeader("Lecture traps")) {
    if (const std::string name = trap_.section(); !name.empty()) (void)load_trap(name);  // errors: the scene section shows them
  }
  if (ImGui::CollapsingHeader("Playlist", playlist_.loaded() ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
    if (const auto state = playlist_.section()) go_to_state(*state);
  }
  if (ImGui::CollapsingHeader("Recording")) {
    if (recorder_.section()) (void)toggle_recording();  // the section shows the result
  }
  if (ImGui::CollapsingHeader("Cost heat map")) heatmap_.section();
  if (ImGui::CollapsingHeader("Parameter sweep")) {
    if (sweep_.section(session_.editor_info())) (void)start_sweep();  // errors shown in the section
  }
  if (ImGui::CollapsingHeader("Speed vs error chart")) bench_chart_section(chart_);
  if (ImGui::CollapsingHeader("Keys and mouse")) {
    // The mouse as it acts in this mode (the blackboard's or the 3D view's rows).
    for (const std::string& line : mouse_help_lines(mode_2d())) ImGui::TextDisabled("%s", line.c_str());
    // The keys from the tools' rows, as they are dispatched.
    for (const std::string& line : keys_help_lines(key_groups_)) ImGui::TextDisabled("%s", line.c_str());
  }
  ImGui::End();
}

void App::traversal_numbers() {
  // The t-axis strip along the bottom of the 3D view, between the docked panels (known
  // now: every docked panel of this frame has been drawn).
  const ImGuiIO& io = ImGui::GetIO();
  const float em = ImGui::GetFontSize(), pad = 0.4f * em;
  const float left = dock_.left > 0.0f ? dock_.left + pad : pad;
  const float right = (dock_.right < io.DisplaySize.x ? dock_.right : io.DisplaySize.x) - pad;
  const float h = VarsPanel::strip_height(em);
  if (right - left < 12.0f * em) return;  // no room beside the panels
  // Above the tree diagram when it is docked along the bottom.
  const float bottom = dock_.bottom > 0.0f ? dock_.bottom : io.DisplaySize.y;
  const WindowRect rect{{left, bottom - h - pad}, {right - left, h}};
  vars_.strip(rect, ray_.ray(), ray_.step_highlight(), trap_.misleads() || trap_.marked_step() ? &trap_.naive() : nullptr);
}

void App::status_overlay() {
  // The playlist's title, at the top of the 3D view (window coordinates), with or without
  // the panels.
  const float sx = ImGui::GetIO().DisplayFramebufferScale.x > 0.0f ? ImGui::GetIO().DisplayFramebufferScale.x : 1.0f;
  playlist_.overlay(glm::vec4(static_cast<float>(view_.x) / sx, 0.0f, static_cast<float>(view_.z) / sx, 0.0f),
                    ImGui::GetTime());
  if (!ui_visible_) return;
  const bool building = session_.building();
  const bool waiting_heatmap = heatmap_.computing();
  const bool recording = build_.recording();
  // A recording with the panels would record its own notice: the title says it instead.
  const std::string notice = recorder_.recording_ui() ? std::string() : recorder_.notice();
  if (!building && !waiting_heatmap && !recording && notice.empty()) return;
  const float em = ImGui::GetFontSize();
  glm::vec2 pos = layout_.status.pos;
  if (panels_.legend && heatmap_.on()) pos.y += 7.5f * em;  // below the legend
  ImGui::SetNextWindowPos(ImVec2(pos.x, pos.y), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  if (building) {
    ImGui::TextColored(ui::kCurrentText, "building %s ... %.1f s (the old structure stays until it is ready)",
                       session_.requested_name().c_str(), session_.build_seconds());
    ImGui::ProgressBar(static_cast<float>(session_.build_fraction()), ImVec2(20.0f * em, 0.4f * em), "");
  }
  if (recording) {
    ImGui::TextColored(ui::kCurrentText, "recording the construction ... %.1f s", build_.recording_seconds());
    ImGui::ProgressBar(static_cast<float>(build_.recording_fraction()), ImVec2(20.0f * em, 0.4f * em), "");
  }
  if (!notice.empty()) ImGui::TextColored(ui::kCurrentText, "%s", notice.c_str());
  if (waiting_heatmap) {
    const glm::ivec2 size = heatmap_.computing_size();
    ImGui::TextDisabled("heat map: tracing %dx%d rays ...", size.x, size.y);
  }
  ImGui::End();
}

}  // namespace viz
