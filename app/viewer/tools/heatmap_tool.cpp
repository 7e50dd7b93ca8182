#include "tools/heatmap_tool.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "panels.h"
#include "structure_view.h"
#include "tools/ui_colors.h"

namespace viz {
using ui::fmt;
HeatmapTool::Inputs HeatmapTool::inputs(const HeatmapView& view) const {
  Inputs in;
  in.camera = view.camera;
  in.built = view.built.get();
  in.metric = metric_;
  const int d = std::max(divisor_, 1);
  in.size = glm::max(view.view_size / d, glm::ivec2(1));
  return in;
}

void HeatmapTool::update(float dt, const HeatmapView& view) {
  if (job_.ready()) {
    accel::CostImage image = job_.take();
    if (image.complete) {
      image_ = std::move(image);
      shown_ = running_;
      has_image_ = true;
      uploaded_ = false;
    }
  }
  if (!on_) {
    job_.cancel();
    return;
  }
  const Inputs now = inputs(view);
  if (now == last_) {
    still_ += static_cast<double>(dt);
  } else {
    still_ = 0.0;
    last_ = now;
  }
  if (job_.busy() && !(running_ == now)) job_.cancel();  // stale: stop early
  // Debounce: recompute once the view has been still for a moment, not while dragging.
  constexpr double kStillSeconds = 0.25;
  if (!job_.busy() && now.built && !(shown_ == now) && still_ >= kStillSeconds) {
    running_ = now;
    BuiltPtr built = view.built;
    job_.start([built, now](const std::atomic<bool>& cancel) {
      return accel::compute_cost_image(*built->structure, now.camera, now.size.x, now.size.y, now.metric, &cancel);
    });
  }
}

void HeatmapTool::compute_now(const HeatmapView& view) {
  const Inputs now = inputs(view);
  if (!now.built) return;
  job_.wait();
  image_ = accel::compute_cost_image(*view.built->structure, now.camera, now.size.x, now.size.y, now.metric);
  shown_ = now;
  last_ = now;
  has_image_ = true;
  uploaded_ = false;
}

void HeatmapTool::section() {
  const float em = ImGui::GetFontSize();
  ImGui::Checkbox("show (M)", &on_);
  int metric = static_cast<int>(metric_);
  ImGui::SameLine();
  ImGui::RadioButton("nodes", &metric, 0);
  ImGui::SameLine();
  ImGui::RadioButton("triangles", &metric, 1);
  metric_ = static_cast<accel::CostMetric>(metric);
  static const char* kRes[] = {"1/1", "1/2", "1/4", "1/8"};
  int res = divisor_ >= 8 ? 3 : divisor_ >= 4 ? 2 : divisor_ >= 2 ? 1 : 0;
  ImGui::SetNextItemWidth(6.0f * em);
  if (ImGui::Combo("resolution", &res, kRes, 4)) divisor_ = 1 << res;
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::SliderFloat("overlay opacity", &alpha_, 0.1f, 1.0f, "%.2f");
  ImGui::TextDisabled("per pixel: the primary ray's cost, from the");
  ImGui::TextDisabled("core's real queries, computed on all cores");
}

void HeatmapTool::legend(const PanelPlace& where, const std::string& node_noun, const HeatmapView& view) {
  const float em = ImGui::GetFontSize();
  ui::place(where);
  ImGui::SetNextWindowBgAlpha(0.88f);
  ImGui::Begin("Heat map", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
  const bool nodes = metric_ == accel::CostMetric::NodesVisited;
  const std::string visited = node_noun + " visited";
  ImGui::Text("%s per primary ray", nodes ? visited.c_str() : "triangles tested");
  if (!has_image_) {
    ImGui::TextDisabled("computing ...");
    ImGui::End();
    return;
  }
  const accel::CostImage& img = image_;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float bar_w = 16.0f * em, bar_h = 1.0f * em;
  for (int i = 0; i < 64; ++i) {
    const float t0 = static_cast<float>(i) / 64.0f, t1 = static_cast<float>(i + 1) / 64.0f;
    const glm::vec3 c = colormap(t0);
    dl->AddRectFilled(ImVec2(p.x + t0 * bar_w, p.y), ImVec2(p.x + t1 * bar_w + 0.5f, p.y + bar_h),
                      ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
  }
  ImGui::Dummy(ImVec2(bar_w, bar_h));
  const float top = std::max(img.p99_value, 1.0f);
  const std::string lo = "0", hi = fmt(img.max_value > top ? ">= %.0f" : "%.0f", static_cast<double>(top));
  ImGui::TextUnformatted(lo.c_str());
  ImGui::SameLine(bar_w - ImGui::CalcTextSize(hi.c_str()).x + ImGui::GetStyle().WindowPadding.x);
  ImGui::TextUnformatted(hi.c_str());
  ImGui::TextDisabled("min %.0f  mean %.1f  max %.0f", static_cast<double>(img.min_value), img.mean_value,
                      static_cast<double>(img.max_value));
  ImGui::TextDisabled("%dx%d rays (1/%d resolution), %.0f ms", img.width, img.height, divisor_, img.compute_ms);
  if (!(shown_ == inputs(view))) ImGui::TextColored(ui::kCurrentText, "view changed: recomputing ...");
  ImGui::End();
}

void HeatmapTool::cycle() {
  // Cycle: off -> nodes -> triangles -> off.
  if (!on_) {
    on_ = true;
    metric_ = accel::CostMetric::NodesVisited;
  } else if (metric_ == accel::CostMetric::NodesVisited) {
    metric_ = accel::CostMetric::PrimsTested;
  } else {
    on_ = false;
  }
}

void HeatmapTool::init_gl() {
  texture_.emplace();
  uploaded_ = false;
}

void HeatmapTool::sync_gl() {
  if (!texture_ || uploaded_ || !has_image_) return;
  texture_->upload(image_.values.data(), image_.width, image_.height);
  uploaded_ = true;
}

void HeatmapTool::draw(Renderer& renderer, const HeatmapView& view) {
  if (!texture_ || !on_ || !has_image_ || !(shown_ == inputs(view))) return;
  OverlayStyle overlay;
  overlay.scale_max = std::max(image_.p99_value, 1.0f);
  overlay.alpha = alpha_;
  renderer.draw_overlay(*texture_, overlay);
}

void HeatmapTool::release_gl() { texture_.reset(); }

}  // namespace viz
