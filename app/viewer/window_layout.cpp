#include "window_layout.h"

#include <algorithm>
#include <cmath>

#include <imgui.h>

namespace viz {

glm::vec2 display_scale() {
  const ImGuiIO& io = ImGui::GetIO();
  return {io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f,
          io.DisplayFramebufferScale.y > 0.0f ? io.DisplayFramebufferScale.y : 1.0f};
}

bool* PanelSwitches::find(const std::string& name) {
  const struct {
    const char* name;
    bool PanelSwitches::*flag;
  } kSwitches[] = {{"scene", &PanelSwitches::main},
                   {"ray", &PanelSwitches::ray},
                   {"steps", &PanelSwitches::steps},
                   {"code", &PanelSwitches::code},
                   {"legend", &PanelSwitches::legend}};
  for (const auto& s : kSwitches)
    if (name == s.name) return &(this->*s.flag);
  return nullptr;
}

void WindowLayout::set_vars_column(bool on) {
  if (on == vars_column_) return;
  vars_column_ = on;
  relayout();
}

void WindowLayout::reset() {
  panels_ = PanelSwitches{};
  ui_visible_ = true;
  relayout();
}

void WindowLayout::apply_lecture_mode() {
  if (lecture_ == lecture_applied_) return;
  lecture_applied_ = lecture_;
  ImGuiIO& io = ImGui::GetIO();
  io.FontDefault = lecture_ ? fonts_.ui_large : fonts_.ui;
  ImGuiStyle& style = ImGui::GetStyle();
  ImGui::StyleColorsDark(&style);
  if (lecture_) {
    // High contrast for a projector: black panels, white text, a black 3D background and
    // strong borders so panels separate from the scene (NodeDisplay brightens the mesh).
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
  // The font takes effect at the next frame: lay out again then.
  relayout();
}

void WindowLayout::begin_frame() {
  apply_lecture_mode();
  dock_ = {0.0f, ImGui::GetIO().DisplaySize.x};
}

void WindowLayout::layout_windows() {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 display(io.DisplaySize.x, io.DisplaySize.y);
  if (display != display_) {
    display_ = display;
    relayout();
  }
  apply_ = frames_left_ > 0;
  if (frames_left_ > 0) --frames_left_;
  rects_ = compute_layout(display, ImGui::GetFontSize(), lecture_, panels_.main);
}

PanelPlace WindowLayout::place(const WindowRect& rect, bool docks) { return {rect, apply_, docks ? &dock_ : nullptr}; }

void WindowLayout::end_frame() {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 scale = display_scale();
  view_ = view_rect(dock_, {io.DisplaySize.x, io.DisplaySize.y}, scale, ui_visible_);
  const glm::ivec2 fb(static_cast<int>(std::lround(io.DisplaySize.x * scale.x)),
                      static_cast<int>(std::lround(io.DisplaySize.y * scale.y)));
  if (fb.x > 0 && fb.y > 0) framebuffer_ = fb;
}

void WindowLayout::clamp_to(glm::ivec2 size) {
  framebuffer_ = size;
  view_.x = std::clamp(view_.x, 0, framebuffer_.x - 1);
  view_.z = std::clamp(view_.z, 1, framebuffer_.x - view_.x);
  view_.y = 0;
  view_.w = std::clamp(view_.w, 1, framebuffer_.y);  // shorter above a bottom panel (the tree)
}

}  // namespace viz
