#include "tools/transport_controls.h"

#include <algorithm>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "tools/ui_colors.h"

namespace viz {

void transport_controls(accel::PlaybackClock& clock, const TransportNumbers& numbers,
                        const std::function<void()>& more_buttons) {
  const float em = ImGui::GetFontSize();
  ImGui::BeginDisabled(clock.empty());
  if (ImGui::Button("|<")) {
    clock.pause();
    clock.seek(0);
  }
  ImGui::SameLine();
  if (ImGui::Button("<")) {
    clock.pause();
    clock.step_back();
  }
  ImGui::SameLine();
  if (ImGui::Button(clock.playing() ? "Pause" : "Play", ImVec2(4.0f * em, 0.0f))) clock.toggle();
  ImGui::SameLine();
  if (ImGui::Button(">")) {
    clock.pause();
    clock.step_forward();
  }
  ImGui::SameLine();
  if (ImGui::Button(">|")) {
    clock.pause();
    clock.jump_to_end();
  }
  if (more_buttons) {
    ImGui::SameLine();
    more_buttons();
  }
  // Step and speed side by side.
  const float half = 0.5f * (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x);
  const int first = static_cast<int>(numbers.first);
  const int last = static_cast<int>(clock.last_step()) + first;
  int step = static_cast<int>(clock.step()) + first;
  char step_format[48];
  if (clock.empty())
    std::snprintf(step_format, sizeof step_format, "%s", numbers.empty_text);
  else
    std::snprintf(step_format, sizeof step_format, "step %%d of %d", last);
  ImGui::SetNextItemWidth(half);
  if (ImGui::SliderInt("##step", &step, first, std::max(last, first), step_format, ImGuiSliderFlags_AlwaysClamp)) {
    clock.pause();
    clock.seek(static_cast<size_t>(step - first));
  }
  ImGui::SameLine();
  float speed = static_cast<float>(clock.speed());
  ImGui::SetNextItemWidth(half);
  if (ImGui::SliderFloat("##speed", &speed, static_cast<float>(accel::PlaybackClock::kMinSpeed),
                         static_cast<float>(accel::PlaybackClock::kMaxSpeed), "speed %.3g steps/s",
                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp))
    clock.set_speed(speed);
  ImGui::EndDisabled();
}

std::optional<size_t> step_list(size_t rows, std::optional<size_t> current, size_t scroll_to, StepListState& state,
                                const std::function<StepRow(size_t)>& row) {
  ImGui::Checkbox("follow", &state.follow);
  ImGui::SameLine();
  ImGui::TextDisabled("click a step to go there");
  ImGui::BeginChild("steps");
  const float row_h = ImGui::GetTextLineHeightWithSpacing();
  if (state.follow && scroll_to != state.scrolled) {
    ImGui::SetScrollY(std::max(0.0f, static_cast<float>(scroll_to) * row_h - 0.5f * ImGui::GetWindowHeight()));
    state.scrolled = scroll_to;
  }
  std::optional<size_t> clicked;
  ImGuiListClipper clipper;
  clipper.Begin(static_cast<int>(rows), row_h);
  while (clipper.Step()) {
    for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
      const size_t r = static_cast<size_t>(i);
      const StepRow step = row(r);
      char number[32];
      std::snprintf(number, sizeof number, "%5d  %*s", i + 1, std::min(step.depth, 24), "");
      const std::string label = number + step.text;
      const bool is_current = current == r;
      ImGui::PushStyleColor(ImGuiCol_Text, is_current ? ImVec4(0, 0, 0, 1) : step.color);
      if (is_current)
        ImGui::PushStyleColor(ImGuiCol_Header,
                              ImVec4(ui::kCurrentText.x, ui::kCurrentText.y, ui::kCurrentText.z, 0.95f));
      if (ImGui::Selectable(label.c_str(), is_current)) clicked = r;
      if (is_current) ImGui::PopStyleColor();
      ImGui::PopStyleColor();
    }
  }
  ImGui::EndChild();
  return clicked;
}

std::vector<KeyBinding> transport_keys(accel::PlaybackClock& clock, const TransportKeys& keys) {
  const std::string noun = keys.noun;
  // Shift moves ten steps: holding it with a step key crosses a long recording quickly.
  auto count = [](const KeyPress& k) -> size_t { return (k.mods & GLFW_MOD_SHIFT) ? 10 : 1; };
  auto pausing = [&clock](std::function<void(const KeyPress&)> move) {
    return [&clock, move](const KeyPress& k) {
      clock.pause();
      move(k);
      return true;
    };
  };
  const std::string steps = "one " + noun + " step back / forward (shift: 10)";
  const std::string ends = "first / last " + noun + " step" + keys.ends_note;
  const std::string speed = noun + " slower / faster";
  return {
      {keys.play, keys.play_label, "play / pause the " + noun,
       [&clock](const KeyPress&) {
         clock.toggle();
         return true;
       }},
      {keys.back, keys.step_label, steps, pausing([&clock, count](const KeyPress& k) { clock.step_back(count(k)); })},
      {keys.forward, keys.step_label, steps,
       pausing([&clock, count](const KeyPress& k) { clock.step_forward(count(k)); })},
      {keys.first, keys.ends_label, ends, pausing([&clock](const KeyPress&) { clock.seek(0); })},
      {keys.last, keys.ends_label, ends, pausing([&clock](const KeyPress&) { clock.jump_to_end(); })},
      {keys.slower, keys.speed_label, speed,
       [&clock](const KeyPress&) {
         clock.set_speed(clock.speed() / 1.5);
         return true;
       }},
      {keys.faster, keys.speed_label, speed,
       [&clock](const KeyPress&) {
         clock.set_speed(clock.speed() * 1.5);
         return true;
       }},
  };
}

void step_clock(accel::PlaybackClock& clock, StepMode mode, size_t count) {
  switch (mode) {
    case StepMode::Forward:
      clock.step_forward(count);
      break;
    case StepMode::Back:
      clock.step_back(count);
      break;
    case StepMode::End:
      clock.jump_to_end();
      break;
    case StepMode::Hit:
    case StepMode::Start:
      clock.seek(0);
      break;
  }
}

}  // namespace viz
