#include "tools/param_editor.h"

#include <algorithm>
#include <array>
#include <optional>

#include <imgui.h>

#include "params.h"

namespace viz {
namespace {

/// "default 8", or over a 2D scene with a default of its own "default 1 in 2D (3D: 8)".
std::string default_text(const accel::ParamSpec& spec, bool planar) {
  if (!planar || !spec.planar_default) return "default " + spec.default_value;
  return "default " + spec.text(*spec.planar_default) + " in 2D (3D: " + spec.default_value + ")";
}

}  // namespace

void ParamEditor::set(const StructureRequest& request) {
  const auto& registry = accel::structure_registry();
  structure_ = 0;
  for (size_t i = 0; i < registry.size(); ++i)
    if (registry[i].name == request.name) structure_ = static_cast<int>(i);
  const accel::StructureInfo& entry = registry[static_cast<size_t>(structure_)];
  params_ = accel::ParamSet(entry.params, entry.name);
  // Requests come validated (scripts, compare rows, the editor itself); a value that does
  // not parse keeps the default rather than half-applying.
  for (const auto& spec : entry.params) {
    const std::string value = accel::param_value(request.params, spec.name);
    if (!value.empty()) (void)params_.set(spec.name, value);
  }
  kernel_ = request.kernel;
}

StructureRequest ParamEditor::request() const {
  StructureRequest r;
  r.name = info().name;
  r.params = params_.explicit_key_values();  // shortest text that reads back exactly
  r.kernel = kernel_;
  return r;
}

const accel::StructureInfo& ParamEditor::info() const {
  const auto& registry = accel::structure_registry();
  return registry[static_cast<size_t>(std::clamp(structure_, 0, static_cast<int>(registry.size()) - 1))];
}

std::string ParamEditor::structure_combo() {
  const float em = ImGui::GetFontSize();
  const auto& registry = accel::structure_registry();
  structure_ = std::clamp(structure_, 0, static_cast<int>(registry.size()) - 1);
  std::string chosen;
  ImGui::SetNextItemWidth(12.0f * em);
  if (ImGui::BeginCombo("structure", registry[static_cast<size_t>(structure_)].name.c_str())) {
    for (int i = 0; i < static_cast<int>(registry.size()); ++i) {
      if (ImGui::Selectable(registry[static_cast<size_t>(i)].name.c_str(), i == structure_) && i != structure_)
        chosen = registry[static_cast<size_t>(i)].name;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", registry[static_cast<size_t>(i)].description.c_str());
    }
    ImGui::EndCombo();
  }
  return chosen;
}

bool ParamEditor::kernel_combo() {
  const float em = ImGui::GetFontSize();
  // The core's kernels, in its order (kAllKernels); the combo's index is the position.
  constexpr int kCount = static_cast<int>(std::size(accel::kAllKernels));
  std::string names[kCount];
  const char* labels[kCount];
  int kernel = 0;
  for (int i = 0; i < kCount; ++i) {
    names[i] = std::string(accel::kernel_name(accel::kAllKernels[i]));
    labels[i] = names[i].c_str();
    if (accel::kAllKernels[i] == kernel_) kernel = i;
  }
  ImGui::SetNextItemWidth(12.0f * em);
  const bool changed = ImGui::Combo("kernel", &kernel, labels, kCount);
  if (changed) kernel_ = accel::kAllKernels[kernel];
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("ray/triangle test: watertight (Woop et al. 2013), Moller-Trumbore, or watertight in double");
  return changed;
}

bool ParamEditor::parameter_widgets(bool planar) {
  const float em = ImGui::GetFontSize();
  const auto& specs = info().params;
  if (specs.empty()) {
    ImGui::TextDisabled("(no parameters)");
    return false;
  }
  params_.set_planar(planar);  // what Structure::build will use for the keys not set
  bool changed = false;
  std::string planar_defaults;  // "max_prims=1 ct=0": the 2D defaults in use
  for (size_t i = 0; i < specs.size(); ++i) {
    const accel::ParamSpec& spec = specs[i];
    if (!params_.has(spec.name)) continue;
    const bool is_set = params_.is_set(spec.name);
    ImGui::PushID(static_cast<int>(i));
    ImGui::SetNextItemWidth(12.0f * em);
    // The widget edits a typed copy; set_value validates it against the same spec the CLI
    // uses (the sliders clamp to its range, so it always passes).
    std::optional<accel::ParamValue> edited;
    // Wide ranges (1..4096, 0.001..1000) get a logarithmic slider.
    const bool wide = spec.min > 0.0 && spec.max / spec.min >= 100.0;
    const ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | (wide ? ImGuiSliderFlags_Logarithmic : 0);
    switch (spec.type) {
      case accel::ParamSpec::Type::Int: {
        int v = params_.get_int(spec.name);
        if (ImGui::SliderInt(spec.name.c_str(), &v, static_cast<int>(spec.min), static_cast<int>(spec.max), "%d",
                             flags))
          edited = accel::ParamValue(v);
        break;
      }
      case accel::ParamSpec::Type::Float: {
        double v = params_.get_float(spec.name);
        const double lo = spec.min, hi = spec.max;
        if (ImGui::SliderScalar(spec.name.c_str(), ImGuiDataType_Double, &v, &lo, &hi, "%.4g", flags))
          edited = accel::ParamValue(v);
        break;
      }
      case accel::ParamSpec::Type::Choice: {
        const int current = params_.get_choice_index(spec.name);
        if (ImGui::BeginCombo(spec.name.c_str(), params_.get_choice(spec.name).c_str())) {
          for (int c = 0; c < static_cast<int>(spec.choices.size()); ++c)
            if (ImGui::Selectable(spec.choices[static_cast<size_t>(c)].c_str(), c == current) && c != current)
              edited = accel::ParamValue(c);
          ImGui::EndCombo();
        }
        break;
      }
      case accel::ParamSpec::Type::Int3: {
        std::array<int, 3> v = params_.get_int3(spec.name);
        if (ImGui::SliderInt3(spec.name.c_str(), v.data(), static_cast<int>(spec.min), static_cast<int>(spec.max),
                              "%d", flags))
          edited = accel::ParamValue(v);
        break;
      }
    }
    if (ImGui::IsItemHovered()) {
      ImGui::BeginTooltip();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
      ImGui::TextUnformatted(spec.doc.c_str());
      ImGui::TextDisabled("%s; %s%s", spec.range_text().c_str(), default_text(spec, planar).c_str(),
                          is_set ? "" : " (in use: not set explicitly)");
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
    if (edited && params_.set_value(spec.name, *edited)) changed = true;
    if (params_.is_set(spec.name)) {
      ImGui::SameLine();
      if (ImGui::SmallButton("x")) {
        params_.reset(spec.name);
        changed = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("back to the %s", default_text(spec, planar).c_str());
    }
    if (planar && spec.planar_default && !params_.is_set(spec.name))
      planar_defaults += (planar_defaults.empty() ? "" : " ") + spec.name + "=" + params_.text(spec.name);
    ImGui::PopID();
  }
  if (!planar_defaults.empty()) {
    ImGui::TextDisabled("2D defaults: %s", planar_defaults.c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("on the blackboard these parameters have their own defaults (hover one for why); "
                        "set one to override it");
  }
  return changed;
}

}  // namespace viz
