#include "tools/trap_tool.h"

#include <imgui.h>

#include "panels.h"
#include "tools/ui_colors.h"

namespace viz {
namespace {

const ImVec4 kNaiveText(1.0f, 0.35f, 0.85f, 1.0f);  // as on the t-axis strip

void answer_row(const char* who, bool hit, int32_t prim, double t, const ImVec4& color, const char* note) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextColored(color, "%s", who);
  ImGui::TableSetColumnIndex(1);
  if (hit) ImGui::TextColored(color, "triangle %d", prim);
  else ImGui::TextColored(color, "miss");
  ImGui::TableSetColumnIndex(2);
  if (hit) ImGui::TextColored(color, "t = %.6g", t);
  ImGui::TableSetColumnIndex(3);
  ImGui::TextColored(ui::kDimText, "%s", note);
}

}  // namespace

void TrapTool::update(const DebugRay& ray, const accel::Scene& scene) {
  const auto& events = ray.player.events();
  const bool same = computed_ && ray.ray.org == ray_.org && ray.ray.dir == ray_.dir && events.data() == events_ &&
                    events.size() == event_count_ && &scene == scene_;
  if (same) return;
  computed_ = true;
  ray_ = ray.ray;
  events_ = events.data();
  event_count_ = events.size();
  scene_ = &scene;
  brute_.reset();
  naive_ = accel::naive_first_leaf_hit(events);
  misleads_ = !events.empty() &&
              (naive_.hit != ray.hit.valid() || (naive_.hit && naive_.prim != ray.hit.prim && naive_.t != ray.hit.t));
  // Brute force is one pass over every triangle: only for a ray the window shows.
  if (ray.active && (demo_ || misleads_)) brute_ = accel::reference_closest(scene, ray.ray);
}

std::optional<size_t> TrapTool::marked_step() const {
  if (!computed_ || !naive_.hit || !(demo_ || misleads_)) return std::nullopt;
  return naive_.stop_step;
}

std::string TrapTool::section() const {
  std::string pressed;
  ImGui::TextDisabled("where a naive traversal goes wrong");
  for (const std::string& name : accel::trap_names()) {
    auto demo = accel::trap_demo(name);
    if (!demo) continue;
    if (ImGui::Button(("trap " + name).c_str())) pressed = name;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", demo.value().title.c_str());
    ImGui::SameLine();
  }
  ImGui::NewLine();
  return pressed;
}

void TrapTool::window(const PanelPlace& where, const DebugRay& ray, accel::TracePlayer& player) {
  if (!open_ || !ray.active || player.empty() || !(demo_ || misleads_)) return;
  const float em = ImGui::GetFontSize();
  ui::place(where);
  ImGui::SetNextWindowBgAlpha(0.9f);
  ImGui::SetNextWindowSizeConstraints(ImVec2(20.0f * em, 0.0f), ImVec2(34.0f * em, 40.0f * em));
  if (!ImGui::Begin("Lecture trap", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::End();
    return;
  }
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + 32.0f * em);
  if (demo_) {
    ImGui::TextColored(ui::kCurrentText, "%s", demo_->title.c_str());
    ImGui::TextWrapped("%s", demo_->explanation.c_str());
  } else {
    ImGui::TextColored(ui::kCurrentText, "On this ray a naive traversal would be wrong");
  }
  ImGui::PopTextWrapPos();
  if (ImGui::BeginTable("answers", 4, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_BordersInnerH)) {
    char note[96];
    std::snprintf(note, sizeof note, "stops at step %zu", naive_.stop_step + 1);
    answer_row("naive", naive_.hit, naive_.prim, static_cast<double>(naive_.t), kNaiveText,
               naive_.hit ? note : "no leaf hit");
    answer_row("traversal", ray.hit.valid(), ray.hit.prim, static_cast<double>(ray.hit.t), ui::kHitText, "the answer");
    if (brute_) answer_row("brute force", brute_->prim >= 0, brute_->prim, brute_->t, ui::kHitText, "double precision");
    ImGui::EndTable();
  }
  ImGui::TextDisabled("naive: stop at the first leaf (cell) with a hit, take its closest");
  if (naive_.hit && ImGui::Button("go to the naive stop")) {
    player.pause();
    player.seek(naive_.stop_step);
  }
  ImGui::End();
}

}  // namespace viz
