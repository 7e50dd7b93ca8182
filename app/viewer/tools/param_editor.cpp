#include "tools/param_editor.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <imgui.h>

namespace viz {
namespace {

long to_long(const std::string& s) { return std::strtol(s.c_str(), nullptr, 10); }
double to_double(const std::string& s) { return std::strtod(s.c_str(), nullptr); }

std::string fmt(const char* format, double v) {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

}  // namespace

void ParamEditor::set(const StructureRequest& request) {
  const auto& registry = accel::structure_registry();
  structure_ = 0;
  for (size_t i = 0; i < registry.size(); ++i)
    if (registry[i].name == request.name) structure_ = static_cast<int>(i);
  const auto& specs = registry[static_cast<size_t>(structure_)].params;
  values_.clear();
  explicit_.clear();
  for (const auto& spec : specs) {
    const std::string value = param_value(request.params, spec.name);
    values_.push_back(value.empty() ? spec.default_value : value);
    explicit_.push_back(!value.empty());
  }
  kernel_ = request.kernel;
}

StructureRequest ParamEditor::request() const {
  StructureRequest r;
  const accel::StructureInfo& spec = info();
  r.name = spec.name;
  for (size_t i = 0; i < spec.params.size() && i < values_.size(); ++i)
    if (explicit_[i]) r.params.push_back(spec.params[i].name + "=" + values_[i]);
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

bool ParamEditor::parameter_widgets() {
  const float em = ImGui::GetFontSize();
  const auto& specs = info().params;
  if (specs.empty()) {
    ImGui::TextDisabled("(no parameters)");
    return false;
  }
  bool changed = false;
  for (size_t i = 0; i < specs.size() && i < values_.size(); ++i) {
    const accel::ParamSpec& spec = specs[i];
    std::string& value = values_[i];
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
                          explicit_[i] ? "" : " (in use: not set explicitly)");
      ImGui::PopTextWrapPos();
      ImGui::EndTooltip();
    }
    if (edited) {
      explicit_[i] = true;
      changed = true;
    }
    if (explicit_[i]) {
      ImGui::SameLine();
      if (ImGui::SmallButton("x")) {
        value = spec.default_value;
        explicit_[i] = false;
        changed = true;
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("back to the default (%s)", spec.default_value.c_str());
    }
    ImGui::PopID();
  }
  return changed;
}

}  // namespace viz
