// App, part 2: the main panel. Its sections belong to the tools (Tool::section), in the
// list's order under the shared headers, then each tool's own; the keys' help is made from
// their rows and the mouse's from input.h's.
#include <imgui.h>

#include "app.h"
#include "color_scheme.h"
#include "tools/structure_session.h"
#include "tools/ui_colors.h"

namespace viz {

void App::main_panel() {
  ToolHost& host = *this;
  const PanelLayout& rects = layout_.rects();
  WindowRect rect = rects.main;
  if (!layout_.vars_column()) rect.size.y = rects.vars.pos.y + rects.vars.size.y - rect.pos.y;  // the whole column
  const PanelPlace where = layout_.place(rect);
  if (layout_.applying()) ImGui::SetNextWindowCollapsed(layout_.lecture(), ImGuiCond_Always);
  if (!ui::begin_panel(where, "accelviz")) return;
  ImGui::Text("frame %.1f ms (%.0f fps)", timing_.frame_ms, timing_.fps);
  ImGui::SameLine();
  ImGui::Checkbox("lecture (L)", layout_.lecture_switch());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("large fonts, high contrast, controls collapsed");
  const struct {
    const char* title;
    PanelSection section;
  } shared[] = {{"Scene", PanelSection::Scene}, {"Structure", PanelSection::Structure}, {"Display", PanelSection::Display}};
  for (const auto& [title, section] : shared) {
    if (!ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen)) continue;
    for (Tool* tool : tool_list_) tool->section(host, section);
    if (section == PanelSection::Display) colors_widget();
  }
  for (Tool* tool : tool_list_) tool->section(host, PanelSection::Own);
  if (ImGui::CollapsingHeader("Keys and mouse")) {
    // The mouse as it acts in this mode (the blackboard's or the 3D view's rows).
    for (const std::string& line : mouse_help_lines(session().scene().planar())) ImGui::TextDisabled("%s", line.c_str());
    // The keys from the tools' rows, as they are dispatched.
    for (const std::string& line : keys_help_lines(key_groups_)) ImGui::TextDisabled("%s", line.c_str());
  }
  ImGui::End();
}

void App::set_panel(const std::string& name, bool on) {
  if (name == "all") {
    layout_.set_ui_visible(on);
    return;
  }
  if (bool* own = layout_.panels().find(name)) *own = on;
  else
    for (Tool* tool : tool_list_)
      if (tool->set_panel(name, on)) break;
  if (on) layout_.set_ui_visible(true);
}

void App::colors_widget() {
  // Colours that carry meaning; the defaults are colour-blind safe (color_scheme.h).
  ColorScheme scheme = color_scheme();
  int map = static_cast<int>(scheme.map);
  const char* maps[] = {"viridis", "cividis", "turbo"};
  ImGui::SetNextItemWidth(8.0f * ImGui::GetFontSize());
  bool changed = ImGui::Combo("colour map", &map, maps, 3);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("depths, triangle counts and the heat map; viridis and cividis stay readable with "
                      "colour-vision deficiency and in greyscale");
  changed |= ImGui::Checkbox("hit/miss blue/orange", &scheme.cvd_safe_hits);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("colour-blind safe; off: green/red");
  if (changed) {
    scheme.map = static_cast<Colormap>(map);
    set_color_scheme(scheme);
    notify(ToolEvent::ColorsChanged);
  }
}

}  // namespace viz
