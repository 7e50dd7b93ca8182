#include "tools/heatmap_tool.h"

#include <algorithm>
#include <cfloat>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "panels.h"
#include "registry.h"
#include "structure_view.h"
#include "tools/heatmap_verbs.h"
#include "tools/structure_session.h"
#include "tools/ui_colors.h"
#include "window_layout.h"

namespace viz {
using ui::fmt;
HeatmapTool::Inputs HeatmapTool::inputs(const HeatmapView& view) const {
  Inputs in;
  in.camera = view.camera;
  in.built = view.built.get();
  in.metric = metric_;
  const int d = std::max(divisor_, 1);
  in.size = glm::max(view.view_size / d, glm::ivec2(1));
  in.other_version = other_ ? other_version_ : 0;
  return in;
}

void HeatmapTool::set_difference(std::optional<StructureRequest> other) {
  other_ = std::move(other);
  ++other_version_;
  other_built_.reset();
  error_.clear();
}

HeatmapTool::Images HeatmapTool::compute(const BuiltPtr& built, const Inputs& in,
                                         const std::optional<StructureRequest>& other, BuiltPtr other_built,
                                         const std::atomic<bool>* cancel) {
  Images out;
  out.image = accel::compute_cost_image(*built->structure, in.camera, in.size.x, in.size.y, in.metric, cancel);
  if (!other) return out;
  out.difference = true;
  if (!other_built || other_built->scene != built->scene) {
    auto b = build_structure_now(built->scene, *other);
    if (!b) {
      out.error = "difference: " + b.error().message;
      return out;
    }
    other_built = b.value();
  }
  out.other_built = other_built;
  out.other = accel::compute_cost_image(*other_built->structure, in.camera, in.size.x, in.size.y, in.metric, cancel);
  return out;
}

void HeatmapTool::take(Images images) {
  if (!images.image.complete) return;
  error_ = images.error;
  if (images.difference && error_.empty()) {
    other_built_ = images.other_built;
    image_ = difference_image(images.image, images.other, &error_);
  } else {
    image_ = std::move(images.image);
  }
  has_image_ = true;
  uploaded_ = false;
}

void HeatmapTool::update_image(float dt, const HeatmapView& view) {
  if (job_.ready()) {
    Images images = job_.take();
    if (images.image.complete) shown_ = running_;
    take(std::move(images));
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
    BuiltPtr built = view.built, other_built = other_built_;
    job_.start([built, now, other = other_, other_built](const std::atomic<bool>& cancel) {
      return compute(built, now, other, other_built, &cancel);
    });
  }
}

void HeatmapTool::compute_now(const HeatmapView& view) {
  const Inputs now = inputs(view);
  if (!now.built) return;
  job_.wait();
  take(compute(view.built, now, other_, other_built_, nullptr));
  shown_ = now;
  last_ = now;
}

void HeatmapTool::settings_section() {
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
  // The colour scale: fixed, it stays when the structure changes, so images compare.
  ImGui::Checkbox("fixed scale", &scale_.fixed);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("keep the range when the structure, its parameters or the view change, so the images of "
                      "two structures compare");
  if (!scale_.fixed && has_image_) {
    const ScaleRange r = heatmap_range(scale_, image_);
    scale_.lo = r.lo;  // what "fixed" starts from
    scale_.hi = r.hi;
  }
  ImGui::BeginDisabled(!scale_.fixed);
  ImGui::SetNextItemWidth(12.0f * em);
  ImGui::DragFloatRange2("range", &scale_.lo, &scale_.hi, 0.25f, 0.0f, 100000.0f, "%.0f", "%.0f",
                         ImGuiSliderFlags_AlwaysClamp);
  ImGui::EndDisabled();
  // The difference view: this structure minus another, per pixel.
  static const std::vector<std::string> names = accel::structure_names();
  bool diff = other_.has_value();
  if (ImGui::Checkbox("difference with", &diff)) {
    if (diff) {
      StructureRequest r;
      r.name = "bvh";
      set_difference(r);
    } else {
      set_difference(std::nullopt);
    }
  }
  if (other_) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(7.0f * em);
    if (ImGui::BeginCombo("##other", other_->name.c_str())) {
      for (const std::string& n : names)
        if (ImGui::Selectable(n.c_str(), n == other_->name)) {
          StructureRequest r;
          r.name = n;
          set_difference(r);
        }
      ImGui::EndCombo();
    }
    if (!error_.empty()) ImGui::TextColored(ui::miss_text(), "%s", error_.c_str());
  }
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
  const bool diff = other_.has_value() && error_.empty();
  if (diff)
    ImGui::TextColored(ui::kCurrentText, "difference: %s - %s (blue: %s cheaper)",
                       view.built ? view.built->request.name.c_str() : "?", other_->name.c_str(),
                       view.built ? view.built->request.name.c_str() : "?");
  if (!error_.empty()) ImGui::TextColored(ui::miss_text(), "%s", error_.c_str());
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float bar_w = 16.0f * em, bar_h = 1.0f * em;
  for (int i = 0; i < 64; ++i) {
    const float t0 = static_cast<float>(i) / 64.0f, t1 = static_cast<float>(i + 1) / 64.0f;
    const glm::vec3 c = diff ? diverging(t0) : colormap(t0);
    dl->AddRectFilled(ImVec2(p.x + t0 * bar_w, p.y), ImVec2(p.x + t1 * bar_w + 0.5f, p.y + bar_h),
                      ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
  }
  ImGui::Dummy(ImVec2(bar_w, bar_h));
  const ScaleRange range = diff ? difference_range(scale_, img) : heatmap_range(scale_, img);
  const std::string lo = fmt(img.min_value < range.lo ? "<= %.0f" : "%.0f", static_cast<double>(range.lo));
  const std::string hi = fmt(img.max_value > range.hi ? ">= %.0f" : "%.0f", static_cast<double>(range.hi));
  ImGui::TextUnformatted(lo.c_str());
  ImGui::SameLine(bar_w - ImGui::CalcTextSize(hi.c_str()).x + ImGui::GetStyle().WindowPadding.x);
  ImGui::TextUnformatted(hi.c_str());
  // The histogram over the same range, under the colour bar: how many pixels have each cost.
  const std::vector<float> counts = cost_histogram(img, range, 32);
  ImGui::PlotHistogram("##histogram", counts.data(), static_cast<int>(counts.size()), 0, nullptr, 0.0f, FLT_MAX,
                       ImVec2(bar_w, 2.5f * em));
  ImGui::TextDisabled("min %.0f  mean %.1f  max %.0f  (scale %s)", static_cast<double>(img.min_value), img.mean_value,
                      static_cast<double>(img.max_value),
                      scale_.fixed ? (diff ? "fixed, +-HI" : "fixed") : (diff ? "auto, +-p99 of |A-B|" : "auto, 0..p99"));
  ImGui::TextDisabled("%dx%d rays (1/%d resolution), %.0f ms", img.width, img.height, divisor_, img.compute_ms);
  if (!(shown_ == inputs(view))) ImGui::TextColored(ui::kCurrentText, "view changed: recomputing ...");
  ImGui::End();
}

std::string HeatmapTool::summary() const {
  if (!has_image_) return "heat map: no image";
  if (!error_.empty()) return "heat map: " + error_;
  const bool diff = other_.has_value();
  const ScaleRange r = diff ? difference_range(scale_, image_) : heatmap_range(scale_, image_);
  char buf[256];
  std::snprintf(buf, sizeof buf, "heat map: %s%s%s %dx%d, scale %g..%g (%s), mean %.3f, max %g",
                metric_ == accel::CostMetric::NodesVisited ? "nodes" : "prims", diff ? " minus " : "",
                diff ? other_->name.c_str() : "", image_.width, image_.height,
                static_cast<double>(r.lo), static_cast<double>(r.hi), scale_.fixed ? "fixed" : "auto",
                image_.mean_value, static_cast<double>(image_.max_value));
  return buf;
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

void HeatmapTool::upload_image() {
  if (!texture_ || uploaded_ || !has_image_) return;
  texture_->upload(image_.values.data(), image_.width, image_.height);
  uploaded_ = true;
}

void HeatmapTool::draw_image(Renderer& renderer, const HeatmapView& view) {
  if (!texture_ || !on_ || !has_image_ || !(shown_ == inputs(view))) return;
  OverlayStyle overlay;
  const bool diff = other_.has_value() && error_.empty();
  const ScaleRange range = diff ? difference_range(scale_, image_) : heatmap_range(scale_, image_);
  overlay.scale_min = range.lo;
  overlay.scale_max = range.hi;
  const auto diverging_palette = diverging_samples();
  if (diff) overlay.palette = diverging_palette.data();
  overlay.alpha = alpha_;
  renderer.draw_overlay(*texture_, overlay);
}

void HeatmapTool::release_gl() { texture_.reset(); }

// ---------------------------------------------------------------------------------------
// Keys and script verbs (the verbs registered in tools/heatmap_verbs.h)

std::vector<KeyBinding> HeatmapTool::keys(ToolHost&) {
  return {{GLFW_KEY_M, "M", "heat map: off, nodes visited, triangles tested, off", [this](const KeyPress&) {
             cycle();
             return true;
           }}};
}

void HeatmapTool::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<HeatmapTool> verbs(table, *this, host);
  heatmap_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void HeatmapTool::on_event(ToolEvent event, ToolHost&) {
  if (event == ToolEvent::SceneLoaded || event == ToolEvent::SceneEdited) invalidate();
  if (event == ToolEvent::PlaylistReset) set_on(false);
}

void HeatmapTool::update(ToolHost& host, float dt) { update_image(dt, host.heatmap_view()); }

void HeatmapTool::section(ToolHost&, PanelSection section) {
  if (section == PanelSection::Own && ImGui::CollapsingHeader("Cost heat map")) settings_section();
}

void HeatmapTool::panels(ToolHost& host) {
  WindowLayout& layout = host.layout();
  if (!layout.panels().legend || !on_) return;
  const BuiltStructure* shown = host.session().shown();
  const std::string noun = shown ? shown->info->node_noun : "nodes";
  legend(layout.place({layout.rects().legend.pos, {0.0f, 0.0f}}, false), noun, host.heatmap_view());
}

void HeatmapTool::draw(Renderer& renderer, ToolHost& host, DrawLayer layer) {
  if (layer == DrawLayer::Over) draw_image(renderer, host.heatmap_view());
}

}  // namespace viz
