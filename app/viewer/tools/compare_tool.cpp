#include "tools/compare_tool.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include <imgui.h>

#include "panels.h"
#include "tools/ui_colors.h"

namespace viz {

using ui::kCullText;
using ui::miss_text;

void CompareTool::start(std::shared_ptr<const accel::Scene> scene, const accel::Ray& ray,
                        const StructureRequest& current, bool synchronous) {
  ray_ = ray;
  progress_ = std::make_shared<std::atomic<int>>(0);
  auto progress = progress_;
  job_.start(
      [scene, ray, current, progress](const std::atomic<bool>& cancel) {
        return compare_structures(scene, ray, current, cancel, progress.get());
      },
      synchronous);
  if (synchronous) poll();
}

void CompareTool::poll() {
  if (job_.ready()) rows_ = job_.take();
}

void CompareTool::print_rows() const {
  for (const CompareRow& r : rows_) {
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
  if (rows_.empty()) {
    ImGui::TextDisabled("shoot a ray, then press Compare (C)");
    ImGui::End();
    return choice;
  }
  if (ray_.org != ray.org || ray_.dir != ray.dir)
    ImGui::TextDisabled("(for the previous ray; press C to update)");
  const int32_t reference = rows_.front().hit.prim;
  if (ImGui::BeginTable("compare", 8,
                        ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                            ImGuiTableFlags_ScrollY)) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* h : {"structure (traversal)", "nodes", "skipped", "triangles", "steps", "hit", "build ms", ""})
      ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < rows_.size(); ++i) {
      const CompareRow& r = rows_[i];
      const bool current = built && r.structure == built->request.name &&
                           (r.params == built->request.params ||
                            param_value(r.params, "traversal") == built->traversal);
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

}  // namespace viz
