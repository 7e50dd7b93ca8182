// App, part 3: the panels (one member function each) and the lecture mode.
// Index:
//   [SECTION] Layout and lecture mode
//   [SECTION] Main panel: scene, structure + parameters, display, heat map, sweep
//   [SECTION] Debug ray panel, step list, pseudo code
//   [SECTION] Compare table, sweep plot, heat map legend, status
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <imgui.h>
#include <imgui_stdlib.h>

#include "app.h"
#include "bench_chart_panel.h"
#include "registry.h"

namespace viz {
namespace {

// Colours of the step list and the code panel (the same meaning as the 3D highlights).
const ImVec4 kCurrentText(1.0f, 0.85f, 0.1f, 1.0f);
const ImVec4 kCullText(1.0f, 0.55f, 0.3f, 1.0f);
const ImVec4 kHitText(0.35f, 0.95f, 0.45f, 1.0f);
const ImVec4 kMissText(1.0f, 0.45f, 0.45f, 1.0f);
const ImVec4 kQueueText(0.35f, 0.85f, 1.0f, 1.0f);
const ImVec4 kDimText(0.62f, 0.65f, 0.72f, 1.0f);

ImVec2 to_im(glm::vec2 v) { return {v.x, v.y}; }

/// Places the next window at `pos` (and `size`, if given) when the layout is (re)applied,
/// and the first time it appears; otherwise the user may move it.
void place(const glm::vec2& pos, const glm::vec2& size, bool apply) {
  const ImGuiCond cond = apply ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(to_im(pos), cond);
  if (size.x > 0.0f) ImGui::SetNextWindowSize(to_im(size), cond);
}

ImVec4 event_color(const accel::TraceEvent& e) {
  switch (e.kind) {
    case accel::TraceEventKind::Visit:
    case accel::TraceEventKind::EnterCell: return kCurrentText;
    case accel::TraceEventKind::Cull: return kCullText;
    case accel::TraceEventKind::Push:
    case accel::TraceEventKind::Pop: return kQueueText;
    case accel::TraceEventKind::TestPrim: return e.hit ? kHitText : kMissText;
    case accel::TraceEventKind::NewClosest:
    case accel::TraceEventKind::Done: return ImVec4(1.0f, 1.0f, 1.0f, 1.0f);
  }
  return kDimText;
}

std::string fmt(const char* format, double v) {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

long to_long(const std::string& s) { return std::strtol(s.c_str(), nullptr, 10); }
double to_double(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

}  // namespace

// ============================================================================
// [SECTION] Layout and lecture mode
// ============================================================================

void App::apply_lecture_mode() {
  if (lecture_mode_ == lecture_mode_applied_) return;
  lecture_mode_applied_ = lecture_mode_;
  ImGuiIO& io = ImGui::GetIO();
  io.FontDefault = lecture_mode_ ? fonts_.ui_large : fonts_.ui;
  ImGuiStyle& style = ImGui::GetStyle();
  ImGui::StyleColorsDark(&style);
  if (lecture_mode_) {
    // High contrast for a projector: black panels, white text, a black 3D background and
    // a brighter mesh; strong borders so panels separate from the scene.
    style.Colors[ImGuiCol_WindowBg] = ImVec4(0.0f, 0.0f, 0.0f, 0.94f);
    style.Colors[ImGuiCol_Text] = ImVec4(1.0f, 1.0f, 1.0f, 1.0f);
    style.Colors[ImGuiCol_TextDisabled] = ImVec4(0.78f, 0.8f, 0.85f, 1.0f);
    style.Colors[ImGuiCol_Border] = ImVec4(0.85f, 0.85f, 0.9f, 0.8f);
    style.Colors[ImGuiCol_FrameBg] = ImVec4(0.18f, 0.2f, 0.26f, 1.0f);
    style.WindowBorderSize = 2.0f;
    background_ = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    mesh_style_.color = glm::vec4(0.82f, 0.86f, 0.94f, 1.0f);
    node_alpha_ = std::max(node_alpha_, 0.8f);
  } else {
    style.WindowBorderSize = 1.0f;
    background_ = glm::vec4(0.075f, 0.085f, 0.105f, 1.0f);
    mesh_style_.color = glm::vec4(0.70f, 0.77f, 0.88f, 1.0f);
  }
  // The font takes effect at the next frame: lay out again then.
  layout_frames_ = 2;
}

void App::layout_windows() {
  const ImGuiIO& io = ImGui::GetIO();
  const glm::vec2 display(io.DisplaySize.x, io.DisplaySize.y);
  if (display != layout_size_) {
    layout_size_ = display;
    layout_frames_ = 2;
  }
  layout_.apply = layout_frames_ > 0;
  if (layout_frames_ > 0) --layout_frames_;
  const float em = ImGui::GetFontSize();
  const float pad = 0.4f * em;
  const float w = display.x, h = display.y;
  // Left: controls (collapsed in lecture mode, for a bigger view). Right: the debug ray, the
  // pseudo code and the step list, wide enough for the lecture's code lines.
  const float left = std::min(21.0f * em, 0.3f * w);
  const float right = std::min(34.0f * em, (lecture_mode_ ? 0.42f : 0.4f) * w);
  layout_.main = {{pad, pad}, {left, h - 2.0f * pad}};
  const float rx = w - right - pad;
  const float ray_h = lecture_mode_ ? 0.4f * h : std::max(0.42f * h, 19.5f * em);
  const float code_h = lecture_mode_ ? 0.38f * h : 0.32f * h;
  layout_.ray = {{rx, pad}, {right, ray_h}};
  layout_.code = {{rx, 2.0f * pad + ray_h}, {right, code_h}};
  layout_.steps = {{rx, 3.0f * pad + ray_h + code_h}, {right, std::max(h - ray_h - code_h - 4.0f * pad, 4.0f * em)}};
  // Compare table and sweep plot: temporary, wide, over the lower left (they need the width).
  const float cx = left + 2.0f * pad;
  const float bottom_h = std::min(0.34f * h, 16.0f * em);
  layout_.bottom = {{pad, h - bottom_h - pad}, {std::max(rx - 2.0f * pad, 10.0f * em), bottom_h}};
  layout_.legend = {{cx, pad}, {0.0f, 0.0f}};
  // The bench chart needs room more than the debug ray does: everything right of the
  // controls (the whole width when they are hidden or collapsed).
  const float chart_x = panels_.main && !lecture_mode_ ? cx : pad;
  layout_.chart = {{chart_x, pad}, {w - chart_x - pad, h - 2.0f * pad}};
  layout_.status = {{cx, pad}, {0.0f, 0.0f}};
}

// ============================================================================
// [SECTION] Main panel: scene, structure + parameters, display, heat map, sweep
// ============================================================================

void App::main_panel() {
  place(layout_.main.pos, layout_.main.size, layout_.apply);
  if (layout_.apply) ImGui::SetNextWindowCollapsed(lecture_mode_, ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.9f);
  if (!ImGui::Begin("accelviz")) {
    ImGui::End();
    return;
  }
  note_docked_window();
  ImGui::Text("frame %.1f ms (%.0f fps)", timing_.frame_ms, timing_.fps);
  ImGui::SameLine();
  ImGui::Checkbox("lecture (L)", &lecture_mode_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("large fonts, high contrast, controls collapsed");
  if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) scene_section();
  if (ImGui::CollapsingHeader("Structure", ImGuiTreeNodeFlags_DefaultOpen)) structure_section();
  if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) display_section();
  if (ImGui::CollapsingHeader("Cost heat map")) heatmap_section();
  if (ImGui::CollapsingHeader("Parameter sweep")) sweep_section();
  if (ImGui::CollapsingHeader("Speed vs error chart")) bench_chart_section(chart_);
  if (ImGui::CollapsingHeader("Keys and mouse")) {
    ImGui::TextDisabled("left drag: orbit   right drag: pan   wheel: zoom");
    ImGui::TextDisabled("click: shoot a ray through that pixel");
    ImGui::TextDisabled("shift-click: from the saved view at that point");
    ImGui::TextDisabled("space: play/pause   left/right: step (shift: 10)");
    ImGui::TextDisabled("home/end: first/last step   J: jump to hit");
    ImGui::TextDisabled("[ ]: slower/faster   C: compare   M: heat map");
    ImGui::TextDisabled("F: frame scene   H: hide panels   L: lecture mode");
  }
  ImGui::End();
}

void App::scene_section() {
  const float em = ImGui::GetFontSize();
  if (!presets_.empty()) {
    preset_index_ = std::clamp(preset_index_, 0, static_cast<int>(presets_.size()) - 1);
    ImGui::SetNextItemWidth(12.0f * em);
    if (ImGui::BeginCombo("##preset", presets_[static_cast<size_t>(preset_index_)].name.c_str())) {
      for (int i = 0; i < static_cast<int>(presets_.size()); ++i) {
        const Preset& p = presets_[static_cast<size_t>(i)];
        if (ImGui::Selectable(p.name.c_str(), i == preset_index_)) preset_index_ = i;
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", p.description.c_str());
      }
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Button("Load preset")) apply_preset(presets_[static_cast<size_t>(preset_index_)]);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("scene, saved camera and saved ray");
  }
  ImGui::SetNextItemWidth(12.0f * em);
  const bool entered = ImGui::InputTextWithHint("##obj", "path/to/scene.obj", &panel_.obj_path,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  const bool clicked = ImGui::Button("Load OBJ");
  if ((entered || clicked) && !panel_.obj_path.empty()) load_scene(panel_.obj_path);
  if (!panel_.load_error.empty()) ui::error_text(panel_.load_error, 19.0f * em);

  if (ImGui::BeginTable("scene", 2, ImGuiTableFlags_SizingFixedFit)) {
    ui::path_row("scene", scene_info_.name.empty() ? scene_info_.spec : scene_info_.name);
    ui::stat_row("triangles", ui::with_separators(scene_info_.triangles) +
                                  (scene_info_.degenerate ? " (" + ui::with_separators(scene_info_.degenerate) +
                                                                " degenerate)"
                                                          : ""));
    ui::stat_row("size", scene_info_.bounds.empty() ? "(empty)" : ui::format_vec(scene_info_.bounds.extent()));
    ui::stat_row("load time", fmt("%.1f ms", scene_info_.load_ms));
    ImGui::EndTable();
  }
  if (ImGui::Button("Frame scene (F)")) frame_scene();
  ImGui::SameLine();
  if (ImGui::Button("Save view")) saved_view_ = camera_.pinhole();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("remember this camera (shift-click then shoots from it)");
  if (saved_view_) {
    ImGui::SameLine();
    if (ImGui::Button("Go to saved")) {
      camera_.look_at(saved_view_->eye, saved_view_->target, saved_view_->fovy_deg, scene_->bounds());
      frame_requested_ = false;
    }
  }
}

void App::structure_section() {
  const float em = ImGui::GetFontSize();
  const auto& registry = accel::structure_registry();
  editor_structure_ = std::clamp(editor_structure_, 0, static_cast<int>(registry.size()) - 1);
  ImGui::SetNextItemWidth(12.0f * em);
  if (ImGui::BeginCombo("structure", registry[static_cast<size_t>(editor_structure_)].name.c_str())) {
    for (int i = 0; i < static_cast<int>(registry.size()); ++i) {
      if (ImGui::Selectable(registry[static_cast<size_t>(i)].name.c_str(), i == editor_structure_) &&
          i != editor_structure_)
        switch_structure(registry[static_cast<size_t>(i)].name, {});
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", registry[static_cast<size_t>(i)].description.c_str());
    }
    ImGui::EndCombo();
  }
  static const char* kKernels[] = {"watertight", "moller", "double"};
  int kernel = static_cast<int>(editor_kernel_);
  ImGui::SetNextItemWidth(12.0f * em);
  if (ImGui::Combo("kernel", &kernel, kKernels, 3)) {
    editor_kernel_ = static_cast<accel::Kernel>(kernel);
    request_structure(request_from_editor());
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("ray/triangle test: watertight (Woop et al. 2013), Moller-Trumbore, or watertight in double");
  parameter_widgets();

  if (build_job_.busy()) {
    // Indeterminate: the core reports no progress; the bar sweeps while the build runs.
    const float phase = std::fmod(static_cast<float>(build_job_.seconds()) * 0.7f, 1.0f);
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, "building %s ... %.1f s", requested_.name.c_str(), build_job_.seconds());
    ImGui::ProgressBar(phase, ImVec2(-1.0f, 0.0f), overlay);
  }
  if (!build_error_.empty()) ui::error_text(build_error_, 19.0f * em);
  if (!built_) return;
  const accel::BuildStats& s = built_->stats;
  if (ImGui::BeginTable("build", 2, ImGuiTableFlags_SizingFixedFit)) {
    ui::stat_row("built", built_->request.name + (built_->scene == scene_ ? "" : " (old scene)"));
    ui::stat_row("build time", fmt("%.2f ms", s.build_ms));
    ui::stat_row("memory", ui::format_bytes(s.memory_bytes));
    ui::stat_row(built_->request.name == "grid" ? "cells" : "nodes",
                 ui::with_separators(s.nodes) + " (" + ui::with_separators(s.leaves) + " leaves)");
    if (s.empty_leaves) ui::stat_row("empty", ui::with_separators(s.empty_leaves));
    ui::stat_row("max depth", std::to_string(s.max_depth));
    ui::stat_row("refs / triangle", fmt("%.2f", s.refs_per_prim()));
    ui::stat_row("largest leaf", std::to_string(s.max_leaf_size));
    ui::stat_row("SAH cost", std::isnan(s.sah_cost) ? std::string("-") : fmt("%.2f", s.sah_cost));
    for (const auto& [key, value] : s.extra) ui::text_row(key.c_str(), value);
    ImGui::EndTable();
  }
}

void App::parameter_widgets() {
  const float em = ImGui::GetFontSize();
  const auto& specs = accel::structure_registry()[static_cast<size_t>(editor_structure_)].params;
  if (specs.empty()) {
    ImGui::TextDisabled("(no parameters)");
    return;
  }
  bool changed = false;
  for (size_t i = 0; i < specs.size() && i < editor_values_.size(); ++i) {
    const accel::ParamSpec& spec = specs[i];
    std::string& value = editor_values_[i];
    ImGui::PushID(static_cast<int>(i));
    ImGui::SetNextItemWidth(12.0f * em);
    bool edited = false;
    // Wide ranges (1..4096, 0.001..1000) get a logarithmic slider; every slider clamps to
    // the spec's range, the same the CLI validates against.
    const bool wide = spec.min > 0.0 && spec.max / spec.min >= 100.0;
    const ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (wide ? ImGuiSliderFlags_Logarithmic : 0);
    switch (spec.type) {
      case accel::ParamSpec::Type::Int: {
        int v = static_cast<int>(to_long(value));
        if (ImGui::SliderInt(spec.name.c_str(), &v, static_cast<int>(spec.min), static_cast<int>(spec.max), "%d",
                             flags)) {
          value = std::to_string(v);
          edited = true;
        }
        break;
      }
      case accel::ParamSpec::Type::Float: {
        float v = static_cast<float>(to_double(value));
        if (ImGui::SliderFloat(spec.name.c_str(), &v, static_cast<float>(spec.min), static_cast<float>(spec.max),
                               "%.3g", flags)) {
          value = fmt("%.4g", static_cast<double>(v));
          edited = true;
        }
        break;
      }
      case accel::ParamSpec::Type::Choice: {
        if (ImGui::BeginCombo(spec.name.c_str(), value.c_str())) {
          for (const std::string& c : spec.choices) {
            if (ImGui::Selectable(c.c_str(), c == value) && c != value) {
              value = c;
              edited = true;
            }
          }
          ImGui::EndCombo();
        }
        break;
      }
      case accel::ParamSpec::Type::Int3: {
        int v[3] = {1, 1, 1};
        std::sscanf(value.c_str(), "%d,%d,%d", &v[0], &v[1], &v[2]);
        if (ImGui::SliderInt3(spec.name.c_str(), v, static_cast<int>(spec.min), static_cast<int>(spec.max), "%d",
                              flags)) {
          value = std::to_string(v[0]) + "," + std::to_string(v[1]) + "," + std::to_string(v[2]);
          edited = true;
        }
        break;
      }
    }
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
      ImGui::TextUnformatted(spec.doc.c_str());
      ImGui::TextDisabled("%s; default %s%s", spec.range_text().c_str(), spec.default_value.c_str(),
                          editor_explicit_[i] ? "" : " (in use: not set explicitly)");
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
    if (edited) {
      editor_explicit_[i] = true;
      changed = true;
    }
    if (editor_explicit_[i]) {
      ImGui::SameLine();
      if (ImGui::SmallButton("x")) {
        value = spec.default_value;
        editor_explicit_[i] = false;
        changed = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("back to the default (%s)", spec.default_value.c_str());
    }
    ImGui::PopID();
  }
  // Every change rebuilds in the background; the old structure stays drawn meanwhile.
  if (changed) request_structure(request_from_editor());
}

void App::display_section() {
  const float em = ImGui::GetFontSize();
  static const char* kMesh[] = {"solid", "translucent", "wireframe", "hidden"};
  int mesh = static_cast<int>(mesh_style_.mode);
  ImGui::SetNextItemWidth(10.0f * em);
  if (ImGui::Combo("mesh", &mesh, kMesh, 4)) mesh_style_.mode = static_cast<MeshStyle::Mode>(mesh);
  ImGui::Checkbox("nodes", &show_nodes_);
  ImGui::SameLine();
  ImGui::Checkbox("x-ray", &xray_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("nodes behind the mesh drawn faintly");
  if (!geometry_.planes.empty()) {
    ImGui::SameLine();
    ImGui::Checkbox("split planes", &show_planes_);
  }
  static const char* kFilter[] = {"all depths", "leaves only", "one depth", "depth range"};
  int filter = static_cast<int>(depth_filter_);
  ImGui::SetNextItemWidth(10.0f * em);
  if (ImGui::Combo("show", &filter, kFilter, 4)) depth_filter_ = static_cast<DepthFilter>(filter);
  const int max_depth = std::max(geometry_.max_depth, 0);
  if (depth_filter_ == DepthFilter::One) {
    ImGui::SetNextItemWidth(10.0f * em);
    ImGui::SliderInt("depth", &depth_one_, 0, max_depth, "%d", ImGuiSliderFlags_AlwaysClamp);
  } else if (depth_filter_ == DepthFilter::Range) {
    ImGui::SetNextItemWidth(10.0f * em);
    if (ImGui::DragIntRange2("depths", &depth_lo_, &depth_hi_, 0.1f, 0, max_depth, "from %d", "to %d",
                             ImGuiSliderFlags_AlwaysClamp))
      depth_hi_ = std::max(depth_hi_, depth_lo_);
  }
  ImGui::TextDisabled("%s of %s nodes drawn", ui::with_separators(drawn_nodes_).c_str(),
                      ui::with_separators(geometry_.boxes.size() + geometry_.spheres.size()).c_str());
  if (depth_auto_limited_ && depth_filter_ == DepthFilter::Range)
    ImGui::TextDisabled("(a large structure: first shown to depth %d)", depth_hi_);
  static const char* kColor[] = {"auto", "depth", "triangles"};
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::Combo("colour by", &coloring_, kColor, 3);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("auto: triangle count for a grid (all cells at depth 0), else depth");
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::SliderFloat("opacity", &node_alpha_, 0.05f, 1.0f, "%.2f");
  ImGui::Checkbox("hide empty leaves", &hide_empty_leaves_);
  if (built_ && built_->request.name == "grid") {
    if (ImGui::Checkbox("empty cells", &empty_cells_)) refresh_geometry();
    if (geometry_.empty_cells_too_many) ImGui::TextDisabled("(too many cells to draw the empty ones)");
  }
  // The colour scale of the nodes.
  const bool by_count = coloring_ == 2 || (coloring_ == 0 && geometry_.uniform_depth);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float bar_w = 12.0f * em, bar_h = 0.7f * em;
  for (int i = 0; i < 32; ++i) {
    const float t0 = static_cast<float>(i) / 32.0f, t1 = static_cast<float>(i + 1) / 32.0f;
    const glm::vec3 c = turbo(by_count ? 0.15f + 0.85f * t0 : 0.12f + 0.86f * t0);
    dl->AddRectFilled(ImVec2(p.x + t0 * bar_w, p.y), ImVec2(p.x + t1 * bar_w, p.y + bar_h),
                      ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
  }
  ImGui::Dummy(ImVec2(bar_w, bar_h));
  if (by_count)
    ImGui::TextDisabled("triangles per cell: 1 .. %u (log)", geometry_.max_prims);
  else
    ImGui::TextDisabled("depth: 0 (root) .. %d", geometry_.max_depth);
  bool changed = ImGui::Checkbox("trail", &show_trail_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("nodes the ray visited before the current one");
  ImGui::SameLine();
  changed |= ImGui::Checkbox("skipped", &show_culled_);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("pending", &show_pending_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("nodes waiting on the stack / priority queue");
  if (changed) highlights_dirty_ = true;
}

void App::heatmap_section() {
  const float em = ImGui::GetFontSize();
  ImGui::Checkbox("show (M)", &heatmap_on_);
  int metric = static_cast<int>(heatmap_metric_);
  ImGui::SameLine();
  ImGui::RadioButton("nodes", &metric, 0);
  ImGui::SameLine();
  ImGui::RadioButton("triangles", &metric, 1);
  heatmap_metric_ = static_cast<accel::CostMetric>(metric);
  static const char* kRes[] = {"1/1", "1/2", "1/4", "1/8"};
  int res = heatmap_divisor_ >= 8 ? 3 : heatmap_divisor_ >= 4 ? 2 : heatmap_divisor_ >= 2 ? 1 : 0;
  ImGui::SetNextItemWidth(6.0f * em);
  if (ImGui::Combo("resolution", &res, kRes, 4)) heatmap_divisor_ = 1 << res;
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::SliderFloat("overlay opacity", &heatmap_alpha_, 0.1f, 1.0f, "%.2f");
  ImGui::TextDisabled("per pixel: the primary ray's cost, from the");
  ImGui::TextDisabled("core's real queries, computed on all cores");
}

void App::sweep_section() {
  const float em = ImGui::GetFontSize();
  const auto& info = accel::structure_registry()[static_cast<size_t>(editor_structure_)];
  std::vector<const accel::ParamSpec*> numeric;
  for (const auto& spec : info.params)
    if (spec.type == accel::ParamSpec::Type::Int || spec.type == accel::ParamSpec::Type::Float) numeric.push_back(&spec);
  if (numeric.empty()) {
    ImGui::TextDisabled("%s has no numeric parameter", info.name.c_str());
    return;
  }
  sweep_param_ = std::clamp(sweep_param_, 0, static_cast<int>(numeric.size()) - 1);
  ImGui::SetNextItemWidth(10.0f * em);
  if (ImGui::BeginCombo("parameter", numeric[static_cast<size_t>(sweep_param_)]->name.c_str())) {
    for (int i = 0; i < static_cast<int>(numeric.size()); ++i) {
      if (ImGui::Selectable(numeric[static_cast<size_t>(i)]->name.c_str(), i == sweep_param_)) {
        sweep_param_ = i;
        // A range around the default, inside the spec's range.
        const accel::ParamSpec& s = *numeric[static_cast<size_t>(i)];
        const double d = to_double(s.default_value);
        sweep_lo_ = static_cast<float>(std::max(s.min, d > 0.0 ? d / 4.0 : s.min));
        sweep_hi_ = static_cast<float>(std::min(s.max, d > 0.0 ? d * 4.0 : s.min + 10.0));
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", numeric[static_cast<size_t>(i)]->doc.c_str());
    }
    ImGui::EndCombo();
  }
  const accel::ParamSpec& spec = *numeric[static_cast<size_t>(sweep_param_)];
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::DragFloatRange2("range", &sweep_lo_, &sweep_hi_, 0.01f * static_cast<float>(spec.max - spec.min),
                         static_cast<float>(spec.min), static_cast<float>(spec.max), "%.3g", "%.3g",
                         ImGuiSliderFlags_AlwaysClamp);
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::SliderInt("steps", &sweep_steps_, 2, 24);
  ImGui::Checkbox("log spacing", &sweep_log_);
  ImGui::SameLine();
  ImGui::BeginDisabled(sweep_job_.busy());
  if (ImGui::Button("Run sweep")) start_sweep();
  ImGui::EndDisabled();
  ImGui::TextDisabled("build + trace 128x96 primary rays per value");
  if (!sweep_error_.empty()) ui::error_text(sweep_error_, 19.0f * em);
}

// ============================================================================
// [SECTION] Debug ray panel, step list, pseudo code
// ============================================================================

void App::ray_panel() {
  const float em = ImGui::GetFontSize();
  place(layout_.ray.pos, layout_.ray.size, layout_.apply);
  ImGui::SetNextWindowBgAlpha(0.9f);
  if (!ImGui::Begin("Debug ray")) {
    ImGui::End();
    return;
  }
  note_docked_window();
  if (!ray_.active) {
    ImGui::TextWrapped("Click into the scene to shoot a ray through that pixel.");
  } else {
    ImGui::TextDisabled("%s, %s", ray_.origin.c_str(), built_ ? built_->request.name.c_str() : "?");
    if (built_) {
      ImGui::SameLine();
      ImGui::TextDisabled("(%s)", traversal_label(built_->kind));
    }
  }
  // Playback.
  accel::TracePlayer& p = ray_.player;
  const bool has = !p.empty();
  ImGui::BeginDisabled(!has);
  if (ImGui::Button("|<")) { p.pause(); p.seek(0); }
  ImGui::SameLine();
  if (ImGui::Button("<")) { p.pause(); p.step_back(); }
  ImGui::SameLine();
  if (ImGui::Button(p.playing() ? "Pause" : "Play", ImVec2(4.0f * em, 0.0f))) p.toggle();
  ImGui::SameLine();
  if (ImGui::Button(">")) { p.pause(); p.step_forward(); }
  ImGui::SameLine();
  if (ImGui::Button(">|")) { p.pause(); p.jump_to_end(); }
  ImGui::SameLine();
  if (ImGui::Button("Jump to hit")) p.jump_to_hit();
  // Step and speed side by side.
  const float half = 0.5f * (ImGui::GetContentRegionAvail().x - ImGui::GetStyle().ItemSpacing.x);
  int step = static_cast<int>(p.step()) + 1;
  ImGui::SetNextItemWidth(half);
  char step_format[48];
  if (p.empty()) std::snprintf(step_format, sizeof step_format, "no trace");
  else std::snprintf(step_format, sizeof step_format, "step %%d of %zu", p.size());
  if (ImGui::SliderInt("##step", &step, 1, std::max(static_cast<int>(p.size()), 1), step_format,
                       ImGuiSliderFlags_AlwaysClamp)) {
    p.pause();
    p.seek(static_cast<size_t>(step - 1));
  }
  ImGui::SameLine();
  float speed = static_cast<float>(p.speed());
  ImGui::SetNextItemWidth(half);
  if (ImGui::SliderFloat("##speed", &speed, static_cast<float>(accel::TracePlayer::kMinSpeed),
                         static_cast<float>(accel::TracePlayer::kMaxSpeed), "speed %.3g steps/s",
                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp))
    p.set_speed(speed);
  ImGui::EndDisabled();

  if (has) {
    // The current step, large and in its colour.
    const accel::TraceEvent& e = *p.current();
    ImGui::PushStyleColor(ImGuiCol_Text, event_color(e));
    ImGui::TextWrapped("%s", accel::describe_event(e).c_str());
    ImGui::PopStyleColor();
    const accel::TraceHighlight& h = highlight_;
    // Counters of this ray: up to this step, and for the whole traversal.
    if (ImGui::BeginTable("counters", 5, ImGuiTableFlags_SizingStretchSame | ImGuiTableFlags_BordersInnerH)) {
      const bool grid = built_ && built_->kind == TraversalKind::Grid;
      for (const char* h_name : {"this ray", grid ? "cells" : "nodes", "skipped", "triangles", "steps"})
        ImGui::TableSetupColumn(h_name);
      ImGui::TableHeadersRow();
      auto row = [](const char* label, std::initializer_list<uint64_t> values) {
        ImGui::TableNextRow();
        ImGui::TableSetColumnIndex(0);
        ImGui::TextDisabled("%s", label);
        int column = 1;
        for (uint64_t v : values) {
          ImGui::TableSetColumnIndex(column++);
          ImGui::Text("%llu", static_cast<unsigned long long>(v));
        }
      };
      row("so far", {h.counters.nodes_visited, h.counters.nodes_culled, h.counters.prims_tested, p.step() + 1});
      row("total", {ray_.stats.nodes_visited, ray_.stats.nodes_culled, ray_.stats.prims_tested, p.size()});
      ImGui::EndTable();
    }
    if (h.closest_prim >= 0)
      ImGui::Text("closest so far: triangle %d at t=%.5g", h.closest_prim, static_cast<double>(h.closest_t));
    if (ray_.hit.valid())
      ImGui::Text("answer: triangle %d at t=%.5g", ray_.hit.prim, static_cast<double>(ray_.hit.t));
    else
      ImGui::TextUnformatted("answer: miss");
    // Stack / priority queue contents, reconstructed from the push/pop events so far.
    if (!h.pending.empty()) {
      const bool pq = built_ && built_->kind == TraversalKind::HierarchyPqueue;
      ImGui::PushStyleColor(ImGuiCol_Text, kQueueText);
      ImGui::Text("%s (%zu):", pq ? "priority queue, nearest first" : "stack, top first", h.pending.size());
      ImGui::PopStyleColor();
      std::vector<accel::PendingNode> list = pq ? accel::sorted_by_key(h.pending)
                                                : std::vector<accel::PendingNode>(h.pending.rbegin(), h.pending.rend());
      // "node @key" entries, wrapped between entries (never inside one).
      const float right_edge = ImGui::GetCursorPosX() + ImGui::GetContentRegionAvail().x;
      constexpr size_t kShown = 10;
      for (size_t i = 0; i < list.size() && i <= kShown; ++i) {
        const std::string item =
            i == kShown ? "..." : std::to_string(list[i].node) + fmt(" @%.3g", static_cast<double>(list[i].key));
        if (i > 0) {
          ImGui::SameLine(0.0f, em);
          if (ImGui::GetCursorPosX() + ImGui::CalcTextSize(item.c_str()).x > right_edge) ImGui::NewLine();
        }
        ImGui::TextUnformatted(item.c_str());
      }
    }
  }
  if (ImGui::Button("Compare structures (C)")) {
    panels_.compare = true;
    start_compare();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the same ray through every structure and traversal order");
  ImGui::SameLine();
  ImGui::Checkbox("from saved view", &shoot_from_saved_);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("a click aims from the saved viewpoint (Scene > Save view) at the point under the cursor");
  if (ImGui::TreeNode("Colours")) {
    ImGui::TextColored(kCurrentText, "current node and the ray's interval in it");
    ImGui::TextColored(ImVec4(0.85f, 0.88f, 0.95f, 1.0f), "nodes visited before (trail)");
    ImGui::TextColored(kQueueText, "pending on the stack / queue (thick: popped next)");
    ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.15f, 1.0f), "skipped: entered beyond the closest hit");
    ImGui::TextColored(ImVec4(0.7f, 0.55f, 1.0f, 1.0f), "skipped: the ray misses its bounds");
    ImGui::TextColored(kHitText, "triangle tested: hit");
    ImGui::SameLine();
    ImGui::TextColored(kMissText, "  miss");
    ImGui::TextColored(ImVec4(1.0f, 0.78f, 0.05f, 1.0f), "closest hit so far");
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(1.0f, 0.2f, 0.9f, 1.0f), "  hit point");
    ImGui::TreePop();
  }
  if (ImGui::TreeNode("Type a ray")) {
    ImGui::SetNextItemWidth(-4.0f * em);
    ImGui::InputFloat3("origin", typed_ray_, "%.4g");
    ImGui::SetNextItemWidth(-4.0f * em);
    ImGui::InputFloat3("dir", typed_ray_ + 3, "%.4g");
    if (ImGui::Button("Shoot")) {
      accel::Ray r;
      r.org = {typed_ray_[0], typed_ray_[1], typed_ray_[2]};
      r.dir = {typed_ray_[3], typed_ray_[4], typed_ray_[5]};
      if (r.dir != glm::vec3(0.0f)) set_ray(r, "typed");
    }
    ImGui::TreePop();
  }
  ImGui::End();
}

void App::steps_panel() {
  place(layout_.steps.pos, layout_.steps.size, layout_.apply);
  ImGui::SetNextWindowBgAlpha(0.9f);
  if (!ImGui::Begin("Traversal steps")) {
    ImGui::End();
    return;
  }
  note_docked_window();
  const auto& events = ray_.player.events();
  if (events.empty()) {
    ImGui::TextDisabled("no trace yet: click into the scene");
    ImGui::End();
    return;
  }
  ImGui::Checkbox("follow", &follow_step_);
  ImGui::SameLine();
  ImGui::TextDisabled("click a step to go there");
  ImGui::BeginChild("steps");
  const float row_h = ImGui::GetTextLineHeightWithSpacing();
  const size_t current = ray_.player.step();
  if (follow_step_ && current != steps_scrolled_) {
    ImGui::SetScrollY(std::max(0.0f, static_cast<float>(current) * row_h - 0.5f * ImGui::GetWindowHeight()));
    steps_scrolled_ = current;
  }
  ImGuiListClipper clipper;
  clipper.Begin(static_cast<int>(events.size()), row_h);
  while (clipper.Step()) {
    for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
      const accel::TraceEvent& e = events[static_cast<size_t>(i)];
      char label[256];
      std::snprintf(label, sizeof label, "%5d  %*s%s", i + 1, std::min<int>(e.depth, 24), "",
                    accel::describe_event(e).c_str());
      ImGui::PushStyleColor(ImGuiCol_Text, static_cast<size_t>(i) == current ? ImVec4(0, 0, 0, 1) : event_color(e));
      if (static_cast<size_t>(i) == current)
        ImGui::PushStyleColor(ImGuiCol_Header, ImVec4(kCurrentText.x, kCurrentText.y, kCurrentText.z, 0.95f));
      if (ImGui::Selectable(label, static_cast<size_t>(i) == current)) {
        ray_.player.pause();
        ray_.player.seek(static_cast<size_t>(i));
        steps_scrolled_ = static_cast<size_t>(i);
      }
      if (static_cast<size_t>(i) == current) ImGui::PopStyleColor();
      ImGui::PopStyleColor();
    }
  }
  ImGui::EndChild();
  ImGui::End();
}

void App::code_panel() {
  place(layout_.code.pos, layout_.code.size, layout_.apply);
  ImGui::SetNextWindowBgAlpha(0.9f);
  const TraversalKind kind = built_ ? built_->kind : TraversalKind::Unknown;
  if (!ImGui::Begin("Pseudo code")) {
    ImGui::End();
    return;
  }
  note_docked_window();
  const PseudoCode& code = pseudo_code(kind);
  ImGui::TextDisabled("%s", code.title.c_str());
  ImGui::BeginChild("code", ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar);
  ImFont* mono = lecture_mode_ ? fonts_.mono_large : fonts_.mono;
  if (mono) ImGui::PushFont(mono);
  const float row_h = ImGui::GetTextLineHeightWithSpacing();
  if (code_line_ >= 0 && code_line_ != code_scrolled_) {
    // Keep the current line in view (the grid's listing is longer than the panel).
    const float y = static_cast<float>(code_line_) * row_h;
    if (y < ImGui::GetScrollY() + row_h || y > ImGui::GetScrollY() + ImGui::GetWindowHeight() - 2.0f * row_h)
      ImGui::SetScrollY(std::max(0.0f, y - 0.4f * ImGui::GetWindowHeight()));
    code_scrolled_ = code_line_;
  }
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (size_t i = 0; i < code.lines.size(); ++i) {
    const bool current = static_cast<int>(i) == code_line_;
    const ImVec2 p = ImGui::GetCursorScreenPos();
    if (current) {
      dl->AddRectFilled(ImVec2(p.x - 4.0f, p.y - 1.0f),
                        ImVec2(p.x + ImGui::GetContentRegionAvail().x + ImGui::GetScrollX(), p.y + row_h - 1.0f),
                        ImGui::ColorConvertFloat4ToU32(ImVec4(kCurrentText.x, kCurrentText.y, kCurrentText.z, 0.9f)));
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0, 0, 0, 1));
    }
    ImGui::TextUnformatted(code.lines[i].empty() ? " " : code.lines[i].c_str());
    if (current) ImGui::PopStyleColor();
  }
  if (mono) ImGui::PopFont();
  ImGui::EndChild();
  ImGui::End();
}

// ============================================================================
// [SECTION] Compare table, sweep plot, heat map legend, status
// ============================================================================

void App::compare_panel() {
  place(layout_.bottom.pos, layout_.bottom.size, layout_.apply);
  ImGui::SetNextWindowBgAlpha(0.97f);
  if (!ImGui::Begin("Same ray, every structure", &panels_.compare)) {
    ImGui::End();
    return;
  }
  if (compare_job_.busy()) {
    const int done = compare_progress_ ? compare_progress_->load() : 0;
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "building and tracing: %d rows done", done);
    ImGui::ProgressBar(std::fmod(static_cast<float>(compare_job_.seconds()) * 0.7f, 1.0f), ImVec2(-1, 0), overlay);
  }
  if (compare_rows_.empty()) {
    ImGui::TextDisabled("shoot a ray, then press Compare (C)");
    ImGui::End();
    return;
  }
  if (compare_ray_.org != ray_.ray.org || compare_ray_.dir != ray_.ray.dir)
    ImGui::TextDisabled("(for the previous ray; press C to update)");
  const int32_t reference = compare_rows_.front().hit.prim;
  if (ImGui::BeginTable("compare", 8,
                        ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                            ImGuiTableFlags_ScrollY)) {
    ImGui::TableSetupScrollFreeze(0, 1);
    for (const char* h : {"structure (traversal)", "nodes", "skipped", "triangles", "steps", "hit", "build ms", ""})
      ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < compare_rows_.size(); ++i) {
      const CompareRow& r = compare_rows_[i];
      const bool current = built_ && r.structure == built_->request.name &&
                           (r.params == built_->request.params ||
                            param_value(r.params, "traversal") == built_->traversal);
      ImGui::TableNextRow();
      if (current)
        ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg0, ImGui::ColorConvertFloat4ToU32(ImVec4(0.45f, 0.38f, 0.05f, 0.9f)));
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(r.label.c_str());
      if (!r.ok) {
        ImGui::TableSetColumnIndex(1);
        ImGui::TextColored(kMissText, "%s", r.error.c_str());
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
      if (!current && ImGui::SmallButton("show")) switch_structure(r.structure, r.params);
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

void App::sweep_panel() {
  const float em = ImGui::GetFontSize();
  glm::vec2 pos = layout_.bottom.pos, size = layout_.bottom.size;
  if (panels_.compare) pos.y -= size.y + 0.4f * em;  // stacked above the compare table
  place(pos, size, layout_.apply);
  ImGui::SetNextWindowBgAlpha(0.97f);
  if (!ImGui::Begin("Parameter sweep", &panels_.sweep)) {
    ImGui::End();
    return;
  }
  std::vector<SweepPoint> points;
  int total = 0;
  if (sweep_progress_) {
    std::lock_guard lock(sweep_progress_->mutex);
    points = sweep_progress_->points;
    total = sweep_progress_->total;
  }
  ImGui::Text("%s: %s from %.3g to %.3g, %dx%d primary rays per value", sweep_request_.base.name.c_str(),
              sweep_request_.param.c_str(), sweep_request_.lo, sweep_request_.hi, sweep_request_.width,
              sweep_request_.height);
  if (sweep_job_.busy()) {
    ImGui::SameLine();
    ImGui::TextColored(kCurrentText, "  running %zu/%d", points.size(), total);
  }
  std::vector<const SweepPoint*> ok;
  for (const SweepPoint& p : points)
    if (p.ok) ok.push_back(&p);
  if (ok.empty()) {
    ImGui::TextDisabled(sweep_job_.busy() ? "building ..." : "no results yet: Parameter sweep > Run sweep");
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
  const bool log_x = sweep_request_.log_scale && x_lo > 0.0;
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
    dl->AddText(ImVec2(0.5f * (a.x + b.x) - 2.0f * em, b.y + 1.3f * em), axis, sweep_request_.param.c_str());
  };
  const ImVec2 o = ImGui::GetCursorScreenPos();
  plot("build ms", &SweepPoint::build_ms, ImVec4(0.35f, 0.8f, 1.0f, 1.0f), o);
  const std::string trace_title =
      "trace ms (" + ui::with_separators(static_cast<size_t>(sweep_request_.width * sweep_request_.height)) + " rays)";
  plot(trace_title.c_str(), &SweepPoint::trace_ms, ImVec4(1.0f, 0.7f, 0.2f, 1.0f), ImVec2(o.x + plot_w + em, o.y));
  ImGui::Dummy(ImVec2(avail.x, plot_h));
  ImGui::End();
}

void App::legend_panel() {
  const float em = ImGui::GetFontSize();
  place(layout_.legend.pos, {0.0f, 0.0f}, layout_.apply);
  ImGui::SetNextWindowBgAlpha(0.88f);
  ImGui::Begin("Heat map", nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
  const bool nodes = heatmap_metric_ == accel::CostMetric::NodesVisited;
  ImGui::Text("%s per primary ray", nodes ? (built_ && built_->kind == TraversalKind::Grid ? "cells visited" : "nodes visited")
                                          : "triangles tested");
  if (!heatmap_has_image_) {
    ImGui::TextDisabled("computing ...");
    ImGui::End();
    return;
  }
  const accel::CostImage& img = heatmap_image_;
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float bar_w = 16.0f * em, bar_h = 1.0f * em;
  for (int i = 0; i < 64; ++i) {
    const float t0 = static_cast<float>(i) / 64.0f, t1 = static_cast<float>(i + 1) / 64.0f;
    const glm::vec3 c = turbo(t0);
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
  ImGui::TextDisabled("%dx%d rays (1/%d resolution), %.0f ms", img.width, img.height, heatmap_divisor_, img.compute_ms);
  if (!(heatmap_shown_ == heatmap_inputs())) ImGui::TextColored(kCurrentText, "view changed: recomputing ...");
  ImGui::End();
}

void App::status_overlay() {
  if (!ui_visible_) return;
  const bool building = build_job_.busy();
  const bool waiting_heatmap = heatmap_on_ && heatmap_job_.busy();
  if (!building && !waiting_heatmap) return;
  const float em = ImGui::GetFontSize();
  glm::vec2 pos = layout_.status.pos;
  if (panels_.legend && heatmap_on_) pos.y += 7.5f * em;  // below the legend
  ImGui::SetNextWindowPos(to_im(pos), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.85f);
  ImGui::Begin("##status", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  if (building) {
    ImGui::TextColored(kCurrentText, "building %s ... %.1f s (the old structure stays until it is ready)",
                       requested_.name.c_str(), build_job_.seconds());
    ImGui::ProgressBar(std::fmod(static_cast<float>(build_job_.seconds()) * 0.7f, 1.0f), ImVec2(20.0f * em, 0.4f * em), "");
  }
  if (waiting_heatmap) ImGui::TextDisabled("heat map: tracing %dx%d rays ...", heatmap_running_.size.x, heatmap_running_.size.y);
  ImGui::End();
}

}  // namespace viz
