#include "tools/trap_tool.h"

#include <cstdio>

#include <imgui.h>

#include "panels.h"
#include "registry.h"
#include "tools/ray_debugger.h"
#include "tools/structure_session.h"
#include "tools/trap_verbs.h"
#include "tools/ui_colors.h"

namespace viz {
namespace {

const ImVec4 kNaiveText(1.0f, 0.35f, 0.85f, 1.0f);  // as on the t-axis strip

void answer_row(const char* who, bool hit, int32_t prim, double t, const ImVec4& color) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextColored(color, "%s", who);
  ImGui::TableSetColumnIndex(1);
  if (hit) ImGui::TextColored(color, "triangle %d", prim);
  else ImGui::TextColored(color, "miss");
  ImGui::TableSetColumnIndex(2);
  if (hit) ImGui::TextColored(color, "t = %.6g", t);
}

}  // namespace

void TrapTool::set_demo(const accel::TrapDemo& demo) {
  demo_ = demo;
  // As build_structure_now writes params_text: the demo's parameters and every default.
  auto choice = accel::parse_structure(demo.structure, demo.params);
  demo_params_ = choice ? choice.value().params.to_string_all() : "";
}

bool TrapTool::demo_applies(const BuiltStructure* built) const {
  // Another structure, or the same with other parameters (another split, another
  // resolution), has other numbers than the explanation's, or no such trap at all.
  return demo_ && built && built->request.name == demo_->structure && built->params_text == demo_params_;
}

std::string TrapTool::trap_line(const BuiltStructure* built) const {
  return demo_applies(built) ? "trap " + demo_->name + ": " + demo_->title : "trap: none";
}

void TrapTool::check_ray(const DebugRay& ray, const accel::Scene& scene, const BuiltStructure* built) {
  demo_applies_ = demo_applies(built);
  const auto& events = ray.player.events();
  const bool same = computed_ && ray.ray.org == ray_.org && ray.ray.dir == ray_.dir && events.data() == events_ &&
                    events.size() == event_count_ && &scene == scene_ && demo_applies_ == brute_for_demo_;
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
  brute_for_demo_ = demo_applies_;
  if (ray.active && (demo_applies_ || misleads_)) brute_ = accel::reference_closest(scene, ray.ray);
}

std::optional<size_t> TrapTool::marked_step() const {
  if (!computed_ || !naive_.hit || !(demo_applies_ || misleads_)) return std::nullopt;
  return naive_.stop_step;
}

std::string TrapTool::traps_section() const {
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

bool TrapTool::shown(const DebugRay& ray) const {
  return open_ && ray.active && !ray.player.empty() && (demo_applies_ || misleads_);
}

void TrapTool::block(const DebugRay& ray, accel::TracePlayer& player) {
  if (!shown(ray)) return;
  if (!ImGui::CollapsingHeader("Lecture trap", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (demo_applies_) {
    ImGui::PushStyleColor(ImGuiCol_Text, ui::kCurrentText);
    ImGui::TextWrapped("%s", demo_->title.c_str());
    ImGui::PopStyleColor();
    ImGui::TextWrapped("%s", demo_->explanation.c_str());
  } else {
    ImGui::PushStyleColor(ImGuiCol_Text, ui::kCurrentText);
    ImGui::TextWrapped("On this ray a naive traversal would be wrong");
    ImGui::PopStyleColor();
  }
  if (ImGui::BeginTable("answers", 3, ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_BordersInnerH)) {
    answer_row("naive", naive_.hit, naive_.prim, static_cast<double>(naive_.t), kNaiveText);
    answer_row("traversal", ray.hit.valid(), ray.hit.prim, static_cast<double>(ray.hit.t), ui::hit_text());
    if (brute_) answer_row("brute force", brute_->prim >= 0, brute_->prim, brute_->t, ui::hit_text());
    ImGui::EndTable();
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ui::kDimText);
  ImGui::TextWrapped("naive: stop at the first leaf (cell) with a hit and take its closest");
  ImGui::PopStyleColor();
  if (naive_.hit) {
    char label[64];
    std::snprintf(label, sizeof label, "go to the naive stop (step %zu)", naive_.stop_step + 1);
    if (ImGui::Button(label)) {
      player.pause();
      player.seek(naive_.stop_step);
    }
  }
  ImGui::Separator();
}

// ---------------------------------------------------------------------------------------
// Script verbs (tools/trap_verbs.h)

void TrapTool::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<TrapTool> verbs(table, *this, host);
  trap_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void TrapTool::on_event(ToolEvent event, ToolHost& host) {
  if (event == ToolEvent::SceneLoaded) on_scene_loaded(host.session().scene_info().spec);
  if (event == ToolEvent::PlaylistReset) set_open(true);
}

void TrapTool::update(ToolHost& host, float) {
  RayDebugger& ray = host.ray();
  check_ray(ray.ray(), host.session().scene(), host.session().current());
  ray.set_marked_step(marked_step(), "a naive traversal stops here");
}

void TrapTool::section(ToolHost& host, PanelSection section) {
  if (section != PanelSection::Own || !ImGui::CollapsingHeader("Lecture traps")) return;
  if (const std::string name = traps_section(); !name.empty()) (void)host.load_trap(name);  // errors: the scene section shows them
}

bool TrapTool::set_panel(const std::string& name, bool on) {
  if (name != "trap") return false;
  set_open(on);
  return true;
}

}  // namespace viz
