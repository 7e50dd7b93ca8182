#include "tools/compare_tool.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "panels.h"
#include "params.h"
#include "tools/compare_verbs.h"
#include "tools/ray_debugger.h"
#include "tools/structure_session.h"
#include "tools/ui_colors.h"
#include "window_layout.h"

namespace viz {

using ui::kCullText;
using ui::miss_text;

void CompareTool::start(std::shared_ptr<const accel::Scene> scene, const accel::Ray& ray,
                        const StructureRequest& current, BuiltPtr shown, bool synchronous) {
  ray_ = ray;
  progress_ = std::make_shared<std::atomic<int>>(0);
  auto progress = progress_;
  job_.start(
      [scene, ray, current, shown, progress](const std::atomic<bool>& cancel) {
        CompareResult result;
        result.rows = compare_structures(scene, ray, current, cancel, progress.get());
        auto info = accel::find_structure(current.name);
        if (!info || !info.value()->student || !shown || cancel) return result;
        // A student's structure: the same ray through the built-in of its kind, step by step.
        result.peer = info.value()->builtin_peer;
        // Set up like the student's (its split rule and leaf size, from its build log): the
        // difference found is then the bug, not the other tree's split planes.
        const std::vector<std::string> peer_params =
            accel::builtin_compare_params(result.peer, shown->structure.get(), scene.get());
        for (const std::string& p : peer_params) result.peer_params += (result.peer_params.empty() ? "" : " ") + p;
        auto peer = accel::build_structure(result.peer, *scene, peer_params, current.kernel);
        if (!peer) {
          result.builtin_error = peer.error().message;
          return result;
        }
        // The student's structure as shown (its queries are const): the steps compared are the
        // steps of the trace on screen, so "go to your step" lands on the same event.
        result.builtin = accel::compare_with_builtin(*scene, ray, *shown->structure, *peer.value());
        return result;
      },
      synchronous);
  if (synchronous) poll();
}

void CompareTool::poll() {
  if (job_.ready()) result_ = job_.take();
}

void CompareTool::print_rows() const {
  if (result_.builtin) {
    std::printf("compare-builtin %s %s\n", result_.peer.c_str(), result_.peer_params.c_str());
    std::printf("compare-builtin %s\n", result_.builtin->difference_line().c_str());
    std::printf("compare-builtin %s\n", result_.builtin->answers_line().c_str());
  } else if (!result_.builtin_error.empty()) {
    std::printf("compare-builtin error %s\n", result_.builtin_error.c_str());
  }
  for (const CompareRow& r : result_.rows) {
    if (!r.ok) {
      std::printf("compare %s error %s\n", r.label.c_str(), r.error.c_str());
      continue;
    }
    std::printf("compare %-22s nodes %6" PRIu64 " skipped %6" PRIu64 " triangles %7" PRIu64 " steps %7zu %s\n",
                r.label.c_str(), r.stats.nodes_visited, r.stats.nodes_culled, r.stats.prims_tested, r.steps,
                r.hit.valid() ? ("hit " + std::to_string(r.hit.prim)).c_str() : "miss");
  }
  std::fflush(stdout);
}

std::optional<StructureChoice> CompareTool::panel(const PanelPlace& where, const BuiltStructure* built,
                                                  const accel::Ray& ray) {
  std::optional<StructureChoice> choice;
  ui::place(where);
  ImGui::SetNextWindowBgAlpha(0.97f);
  if (!ImGui::Begin("Same ray, every structure", &open_)) {
    ImGui::End();
    return choice;
  }
  if (job_.busy()) {
    const int done = progress_ ? progress_->load() : 0;
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "building and tracing: %d rows done", done);
    ImGui::ProgressBar(std::fmod(static_cast<float>(job_.seconds()) * 0.7f, 1.0f), ImVec2(-1, 0), overlay);
  }
  const std::vector<CompareRow>& rows = result_.rows;
  if (rows.empty()) {
    ImGui::TextDisabled("shoot a ray, then press Compare (C)");
    ImGui::End();
    return choice;
  }
  if (ray_.org != ray.org || ray_.dir != ray.dir)
    ImGui::TextDisabled("(for the previous ray; press C to update)");
  builtin_lines();
  const int32_t reference = rows.front().hit.prim;
  if (ImGui::BeginTable("compare", 8,
                        ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                            ImGuiTableFlags_ScrollY)) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* h : {"structure (traversal)", "nodes", "skipped", "triangles", "steps", "hit", "build ms", ""})
      ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < rows.size(); ++i) {
      const CompareRow& r = rows[i];
      const bool current = built && r.structure == built->request.name &&
                           (r.params == built->request.params ||
                            accel::param_value(r.params, "traversal") == built->traversal);
      ImGui::TableNextRow();
      if (current)
        ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg0, ImGui::ColorConvertFloat4ToU32(ImVec4(0.45f, 0.38f, 0.05f, 0.9f)));
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(r.label.c_str());
      if (!r.ok) {
        ImGui::TableSetColumnIndex(1);
        ImGui::TextColored(miss_text(), "%s", r.error.c_str());
        continue;
      }
      ImGui::TableSetColumnIndex(1);
      ImGui::Text("%llu", static_cast<unsigned long long>(r.stats.nodes_visited));
      ImGui::TableSetColumnIndex(2);
      ImGui::Text("%llu", static_cast<unsigned long long>(r.stats.nodes_culled));
      ImGui::TableSetColumnIndex(3);
      ImGui::Text("%llu", static_cast<unsigned long long>(r.stats.prims_tested));
      ImGui::TableSetColumnIndex(4);
      ImGui::Text("%zu", r.steps);
      ImGui::TableSetColumnIndex(5);
      if (r.hit.valid())
        ImGui::TextColored(r.hit.prim == reference ? ImVec4(1, 1, 1, 1) : kCullText, "%d @ %.4g", r.hit.prim,
                           static_cast<double>(r.hit.t));
      else
        ImGui::TextUnformatted("miss");
      ImGui::TableSetColumnIndex(6);
      ImGui::Text("%.1f", r.build_ms);
      ImGui::TableSetColumnIndex(7);
      ImGui::PushID(static_cast<int>(i));
      if (!current && ImGui::SmallButton("show")) choice = StructureChoice{r.structure, r.params};
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  ImGui::End();
  return choice;
}

void CompareTool::builtin_lines() {
  if (!result_.builtin_error.empty()) ImGui::TextColored(miss_text(), "built-in %s: %s", result_.peer.c_str(),
                                                         result_.builtin_error.c_str());
  if (!result_.builtin) return;
  const accel::TraceDifference& d = *result_.builtin;
  ImGui::Text("yours against the built-in %s (%s):", result_.peer.c_str(),
              result_.peer_params.empty() ? "its defaults" : result_.peer_params.c_str());
  if (d.differs) {
    if (ImGui::SmallButton("go to your step")) seek_ = d.mine_step;
    ImGui::SameLine();
  }
  ImGui::TextWrapped("%s", d.difference_line().c_str());
  const bool mine_right = d.mine_verdict == accel::HitVerdict::Correct;
  ImGui::TextColored(mine_right ? ImVec4(1, 1, 1, 1) : miss_text(), "%s", d.answers_line().c_str());
  ImGui::Separator();
}

// ---------------------------------------------------------------------------------------
// Keys and script verbs (the verbs registered in tools/compare_verbs.h)

std::vector<KeyBinding> CompareTool::keys(ToolHost& host) {
  return {{GLFW_KEY_C, "C", "Compare: the same ray through every structure and traversal order",
            [this, &host](const KeyPress&) {
              set_open(true);
              host.start_compare();
              return true;
            }}};
}

void CompareTool::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<CompareTool> verbs(table, *this, host);
  compare_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void CompareTool::on_event(ToolEvent event, ToolHost& host) {
  if (event == ToolEvent::SceneLoaded || event == ToolEvent::SceneEdited) clear();
  if (event == ToolEvent::RayChanged && open_) host.start_compare();
  if (event == ToolEvent::PlaylistReset) set_open(false);
}

void CompareTool::panels(ToolHost& host) {
  if (!open_) return;
  WindowLayout& layout = host.layout();
  RayDebugger& ray = host.ray();
  StructureSession& session = host.session();
  if (auto choice = panel(layout.place(layout.rects().bottom, false), session.shown(), ray.ray().ray))
    session.switch_structure(choice->name, choice->params);
  if (auto step = take_seek(); step && ray.ray().active) ray.player().seek(*step);
}

bool CompareTool::set_panel(const std::string& name, bool on) {
  if (name != "compare") return false;
  set_open(on);
  return true;
}

}  // namespace viz
