#include "tools/transport_controls.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

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

}  // namespace viz
