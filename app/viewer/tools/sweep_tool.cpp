#include "tools/sweep_tool.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <mutex>

#include <imgui.h>

#include "panels.h"
#include "tools/compare_tool.h"
#include "tools/structure_session.h"
#include "tools/sweep_verbs.h"
#include "tools/ui_colors.h"
#include "window_layout.h"

namespace viz {
using ui::fmt;
namespace {


bool numeric(const accel::ParamSpec& spec) {
  return spec.type == accel::ParamSpec::Type::Int || spec.type == accel::ParamSpec::Type::Float;
}

}  // namespace

accel::Status SweepTool::configure(const accel::StructureInfo& info, const std::string& param, float lo, float hi,
                                   int steps) {
  int index = -1, count = 0;
  for (const auto& spec : info.params) {
    if (!numeric(spec)) continue;
    if (spec.name == param) index = count;
    ++count;
  }
  if (index < 0) return accel::make_error("sweep: '" + param + "' is not a numeric parameter of " + info.name);
  param_ = index;
  lo_ = lo;
  hi_ = hi;
  steps_ = steps;
  return {};
}

accel::Status SweepTool::start(const accel::StructureInfo& info, std::shared_ptr<const accel::Scene> scene,
                               const StructureRequest& base, const accel::PinholeCamera& camera, bool synchronous) {
  std::vector<const accel::ParamSpec*> numeric;
  for (const auto& spec : info.params)
    if (spec.type == accel::ParamSpec::Type::Int || spec.type == accel::ParamSpec::Type::Float) numeric.push_back(&spec);
  if (numeric.empty()) {
    error_ = info.name + " has no numeric parameter to sweep";
    return accel::make_error(error_);
  }
  param_ = std::clamp(param_, 0, static_cast<int>(numeric.size()) - 1);
  SweepRequest r;
  r.base = base;
  r.param = numeric[static_cast<size_t>(param_)]->name;
  r.lo = lo_;
  r.hi = hi_;
  r.steps = steps_;
  r.log_scale = log_;
  r.camera = camera;
  request_ = r;
  error_.clear();
  progress_ = std::make_shared<SweepProgress>();
  auto progress = progress_;
  job_.start([scene, r, progress](const std::atomic<bool>& cancel) { return run_sweep(scene, r, *progress, cancel); },
                   synchronous);
  open_ = true;
  if (synchronous) {
    auto done = job_.take();
    if (!done) error_ = done.error().message;
  }
  if (!error_.empty()) return accel::make_error(error_);
  return {};
}

bool SweepTool::settings_section(const accel::StructureInfo& info) {
  bool run = false;
  const float em = ImGui::GetFontSize();
  std::vector<const accel::ParamSpec*> numeric;
  for (const auto& spec : info.params)
    if (spec.type == accel::ParamSpec::Type::Int || spec.type == accel::ParamSpec::Type::Float) numeric.push_back(&spec);
  if (numeric.empty()) {
    ImGui::TextDisabled("%s has no numeric parameter", info.name.c_str());
    return false;
  }
  param_ = std::clamp(param_, 0, static_cast<int>(numeric.size()) - 1);
  ImGui::SetNextItemWidth(10.0f * em);
  if (ImGui::BeginCombo("parameter", numeric[static_cast<size_t>(param_)]->name.c_str())) {
    for (int i = 0; i < static_cast<int>(numeric.size()); ++i) {
      if (ImGui::Selectable(numeric[static_cast<size_t>(i)]->name.c_str(), i == param_)) {
        param_ = i;
        // A range around the default, inside the spec's range.
        const accel::ParamSpec& s = *numeric[static_cast<size_t>(i)];
        const double d = s.type == accel::ParamSpec::Type::Int ? double(std::get<int>(s.default_typed))
                                                               : std::get<double>(s.default_typed);
        lo_ = static_cast<float>(std::max(s.min, d > 0.0 ? d / 4.0 : s.min));
        hi_ = static_cast<float>(std::min(s.max, d > 0.0 ? d * 4.0 : s.min + 10.0));
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", numeric[static_cast<size_t>(i)]->doc.c_str());
    }
    ImGui::EndCombo();
  }
  const accel::ParamSpec& spec = *numeric[static_cast<size_t>(param_)];
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::DragFloatRange2("range", &lo_, &hi_, 0.01f * static_cast<float>(spec.max - spec.min),
                         static_cast<float>(spec.min), static_cast<float>(spec.max), "%.3g", "%.3g",
                         ImGuiSliderFlags_AlwaysClamp);
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::SliderInt("steps", &steps_, 2, 24);
  ImGui::Checkbox("log spacing", &log_);
  ImGui::SameLine();
  ImGui::BeginDisabled(job_.busy());
  if (ImGui::Button("Run sweep")) run = true;
  ImGui::EndDisabled();
  ImGui::TextDisabled("build + trace 128x96 primary rays per value");
  if (!error_.empty()) ui::error_text(error_, 19.0f * em);
  return run;
}

void SweepTool::panel(const PanelPlace& where) {
  const float em = ImGui::GetFontSize();
  ui::place(where);
  ImGui::SetNextWindowBgAlpha(0.97f);
  if (!ImGui::Begin("Parameter sweep", &open_)) {
    ImGui::End();
    return;
  }
  std::vector<SweepPoint> points;
  int total = 0;
  if (progress_) {
    std::lock_guard lock(progress_->mutex);
    points = progress_->points;
    total = progress_->total;
  }
  ImGui::Text("%s: %s from %.3g to %.3g, %dx%d primary rays per value", request_.base.name.c_str(),
              request_.param.c_str(), request_.lo, request_.hi, request_.width,
              request_.height);
  if (job_.busy()) {
    ImGui::SameLine();
    ImGui::TextColored(ui::kCurrentText, "  running %zu/%d", points.size(), total);
  }
  std::vector<const SweepPoint*> ok;
  for (const SweepPoint& p : points)
    if (p.ok) ok.push_back(&p);
  if (ok.empty()) {
    ImGui::TextDisabled(job_.busy() ? "building ..." : "no results yet: Parameter sweep > Run sweep");
    ImGui::End();
    return;
  }
  // Two plots side by side, each with its own y axis: build ms and trace ms against the value.
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 avail = ImGui::GetContentRegionAvail();
  const float plot_w = 0.5f * avail.x - 0.5f * em, plot_h = avail.y - 0.2f * em;
  double x_lo = ok.front()->value, x_hi = ok.front()->value;
  for (const SweepPoint* p : ok) {
    x_lo = std::min(x_lo, p->value);
    x_hi = std::max(x_hi, p->value);
  }
  const bool log_x = request_.log_scale && x_lo > 0.0;
  auto x_of = [&](double v) {
    if (x_hi <= x_lo) return 0.5;
    return log_x ? std::log(v / x_lo) / std::log(x_hi / x_lo) : (v - x_lo) / (x_hi - x_lo);
  };
  const ImU32 axis = ImGui::GetColorU32(ImGuiCol_TextDisabled);
  auto plot = [&](const char* title, double SweepPoint::*field, ImVec4 color, ImVec2 origin) {
    double y_hi = 0.0;
    for (const SweepPoint* p : ok) y_hi = std::max(y_hi, p->*field);
    y_hi = y_hi > 0.0 ? y_hi * 1.1 : 1.0;
    const float left = 4.0f * em, bottom = 2.6f * em, top = 1.4f * em;
    const ImVec2 a(origin.x + left, origin.y + top), b(origin.x + plot_w - 0.5f * em, origin.y + plot_h - bottom);
    dl->AddText(ImVec2(origin.x + left, origin.y), ImGui::ColorConvertFloat4ToU32(color), title);
    dl->AddLine(ImVec2(a.x, b.y), b, axis, 1.5f);
    dl->AddLine(a, ImVec2(a.x, b.y), axis, 1.5f);
    for (double f : {0.0, 0.5, 1.0}) {
      const float y = b.y - static_cast<float>(f) * (b.y - a.y);
      const std::string label = fmt("%.3g", f * y_hi);
      dl->AddText(ImVec2(origin.x + left - ImGui::CalcTextSize(label.c_str()).x - 0.3f * em, y - 0.5f * em), axis,
                  label.c_str());
      dl->AddLine(ImVec2(a.x - 0.25f * em, y), ImVec2(a.x, y), axis);
    }
    ImVec2 prev;
    for (size_t i = 0; i < ok.size(); ++i) {
      const ImVec2 q(a.x + static_cast<float>(x_of(ok[i]->value)) * (b.x - a.x),
                     b.y - static_cast<float>(ok[i]->*field / y_hi) * (b.y - a.y));
      if (i) dl->AddLine(prev, q, ImGui::ColorConvertFloat4ToU32(color), 2.5f);
      dl->AddCircleFilled(q, 0.22f * em, ImGui::ColorConvertFloat4ToU32(color));
      prev = q;
      // x labels: first, last and every other value in between (they would overlap).
      if (i == 0 || i + 1 == ok.size() || (ok.size() <= 8) || i % 2 == 0) {
        const std::string text = fmt("%.3g", ok[i]->value);
        const float tw = ImGui::CalcTextSize(text.c_str()).x;
        dl->AddText(ImVec2(q.x - 0.5f * tw, b.y + 0.2f * em), axis, text.c_str());
      }
    }
    dl->AddText(ImVec2(0.5f * (a.x + b.x) - 2.0f * em, b.y + 1.3f * em), axis, request_.param.c_str());
  };
  const ImVec2 o = ImGui::GetCursorScreenPos();
  plot("build ms", &SweepPoint::build_ms, ImVec4(0.35f, 0.8f, 1.0f, 1.0f), o);
  const std::string trace_title =
      "trace ms (" + ui::with_separators(static_cast<size_t>(request_.width * request_.height)) + " rays)";
  plot(trace_title.c_str(), &SweepPoint::trace_ms, ImVec4(1.0f, 0.7f, 0.2f, 1.0f), ImVec2(o.x + plot_w + em, o.y));
  ImGui::Dummy(ImVec2(avail.x, plot_h));
  ImGui::End();
}

// ---------------------------------------------------------------------------------------
// Script verbs (tools/sweep_verbs.h)

void SweepTool::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<SweepTool> verbs(table, *this, host);
  sweep_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void SweepTool::on_event(ToolEvent event, ToolHost&) {
  if (event == ToolEvent::PlaylistReset) set_open(false);
}

void SweepTool::section(ToolHost& host, PanelSection section) {
  if (section != PanelSection::Own || !ImGui::CollapsingHeader("Parameter sweep")) return;
  if (settings_section(host.session().editor_info())) (void)host.start_sweep();  // errors shown in the section
}

void SweepTool::panels(ToolHost& host) {
  if (!open_) return;
  WindowLayout& layout = host.layout();
  WindowRect rect = layout.rects().bottom;
  if (host.tool<CompareTool>().open()) rect.pos.y -= rect.size.y + 0.4f * ImGui::GetFontSize();  // stacked above the compare table
  panel(layout.place(rect, false));
}

bool SweepTool::set_panel(const std::string& name, bool on) {
  if (name != "sweep") return false;
  set_open(on);
  return true;
}

}  // namespace viz
