#include "panels.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

#include "text_format.h"
#include "tools/ui_colors.h"

namespace viz::ui {
namespace {

// Red that stays legible on the dark panel background, also through a projector.
const ImVec4 kErrorColor(1.0f, 0.42f, 0.38f, 1.0f);

}  // namespace

std::string with_separators(size_t n) { return accel::with_separators(n); }

std::string fmt(const char* format, double v) {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

std::string format_vec(const accel::Vec3& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "(%.4g, %.4g, %.4g)", v.x, v.y, v.z);
  return text;
}

std::string format_bytes(size_t bytes) {
  char text[32];
  const double b = static_cast<double>(bytes);
  if (b >= 1e9) std::snprintf(text, sizeof text, "%.2f GB", b / 1e9);
  else if (b >= 1e6) std::snprintf(text, sizeof text, "%.1f MB", b / 1e6);
  else if (b >= 1e3) std::snprintf(text, sizeof text, "%.1f kB", b / 1e3);
  else std::snprintf(text, sizeof text, "%zu B", bytes);
  return text;
}

void stat_row(const char* label, const std::string& value) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextDisabled("%s", label);
  ImGui::TableSetColumnIndex(1);
  ImGui::TextUnformatted(value.c_str());
}

void path_row(const char* label, const std::string& path) {
  // Long paths would stretch an auto-sized panel across the screen: keep the tail, which
  // names the file, and show the whole path as a tooltip.
  constexpr size_t kMaxChars = 32;
  if (path.size() <= kMaxChars) {
    stat_row(label, path);
    return;
  }
  stat_row(label, "..." + path.substr(path.size() - (kMaxChars - 3)));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", path.c_str());
}

void text_row(const char* label, const std::string& value, size_t max_chars) {
  if (value.size() <= max_chars) {
    stat_row(label, value);
    return;
  }
  stat_row(label, value.substr(0, max_chars - 3) + "...");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", value.c_str());
}

void help_marker(const char* text) {
  ImGui::TextDisabled("(?)");
  if (ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
    ImGui::TextUnformatted(text);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
}

void error_text(const std::string& text, float width) {
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
  ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
  ImGui::PopTextWrapPos();
}

void place(const PanelPlace& where) {
  const ImGuiCond cond = where.apply ? ImGuiCond_Always : ImGuiCond_FirstUseEver;
  ImGui::SetNextWindowPos(ImVec2(where.rect.pos.x, where.rect.pos.y), cond);
  if (where.rect.size.x > 0.0f) ImGui::SetNextWindowSize(ImVec2(where.rect.size.x, where.rect.size.y), cond);
}

void note_docked(const PanelPlace& where) {
  if (where.dock == nullptr) return;
  const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  viz::note_docked(*where.dock, ImGui::GetIO().DisplaySize.x, {pos.x, pos.y}, {size.x, size.y});
}

bool begin_panel(const PanelPlace& where, const char* title) {
  place(where);
  ImGui::SetNextWindowBgAlpha(0.9f);
  if (!ImGui::Begin(title)) {
    ImGui::End();
    return false;
  }
  note_docked(where);
  return true;
}

void code_listing(const char* id, const std::vector<std::string>& lines, int current, ImFont* mono,
                  int& scrolled) {
  ImGui::BeginChild(id, ImVec2(0, 0), false, ImGuiWindowFlags_HorizontalScrollbar);
  if (mono) ImGui::PushFont(mono);
  const float row_h = ImGui::GetTextLineHeightWithSpacing();
  if (current >= 0 && current != scrolled) {
    // Keep the current line in view (some listings are longer than the panel).
    const float y = static_cast<float>(current) * row_h;
    if (y < ImGui::GetScrollY() + row_h || y > ImGui::GetScrollY() + ImGui::GetWindowHeight() - 2.0f * row_h)
      ImGui::SetScrollY(std::max(0.0f, y - 0.4f * ImGui::GetWindowHeight()));
    scrolled = current;
  }
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (size_t i = 0; i < lines.size(); ++i) {
    const bool is_current = static_cast<int>(i) == current;
    const ImVec2 p = ImGui::GetCursorScreenPos();
    if (is_current) {
      dl->AddRectFilled(ImVec2(p.x - 4.0f, p.y - 1.0f),
                        ImVec2(p.x + ImGui::GetContentRegionAvail().x + ImGui::GetScrollX(), p.y + row_h - 1.0f),
                        ImGui::ColorConvertFloat4ToU32(ImVec4(kCurrentText.x, kCurrentText.y, kCurrentText.z, 0.9f)));
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0, 0, 0, 1));
    }
    ImGui::TextUnformatted(lines[i].empty() ? " " : lines[i].c_str());
    if (is_current) ImGui::PopStyleColor();
  }
  if (mono) ImGui::PopFont();
  ImGui::EndChild();
}

}  // namespace viz::ui
