#include "tools/playlist_tool.h"

#include <algorithm>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "tools/playlist_verbs.h"
#include "tools/ui_colors.h"
#include "tool_host.h"
#include "window_layout.h"

namespace viz {
namespace {
constexpr double kTitleSeconds = 2.5;
}

accel::Status PlaylistTool::load(const std::string& path) {
  auto parsed = load_playlist(path);
  if (!parsed) return parsed.error();
  playlist_ = std::move(parsed.value());
  cursor_.reset(playlist_.states.size());
  pending_.clear();
  error_.clear();
  return {};
}

bool PlaylistTool::go(size_t index) {
  bool from_scratch = false;
  const std::vector<size_t> states = cursor_.go_to(index, &from_scratch);
  if (states.empty()) return false;
  // Forward, the commands of the states before that have not run yet still must (PgDn
  // pressed again while a build of the last state runs, or --state N at start-up).
  if (from_scratch) pending_.clear();
  for (size_t s : states)
    for (const ScriptCommand& c : playlist_.states[s].commands) pending_.push_back({s, &c});
  error_.clear();
  shown_at_ = -1.0;
  return from_scratch;
}

void PlaylistTool::fail(const std::string& message) {
  error_ = message;
  pending_.clear();
  // Also where the lecturer started the viewer: the line to fix in the playlist.
  std::fprintf(stderr, "accelviz: %s\n", message.c_str());
}

void PlaylistTool::title_overlay(glm::vec4 view, double now) {
  if (!loaded()) return;
  if (shown_at_ < 0.0) shown_at_ = now;
  const bool title = now - shown_at_ < kTitleSeconds || has_pending();
  if (!title && error_.empty()) return;
  const float em = ImGui::GetFontSize();
  ImGui::SetNextWindowPos(ImVec2(view.x + 0.5f * view.z, view.y + 1.5f * em), ImGuiCond_Always, ImVec2(0.5f, 0.0f));
  ImGui::SetNextWindowBgAlpha(0.85f);
  // Within the 3D view: the panels beside it would cover the rest.
  const float max_w = std::max(view.z - 2.0f * em, 10.0f * em);
  ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f), ImVec2(max_w, 20.0f * em));
  ImGui::Begin("##playlist-title", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav);
  if (title) {
    const PlaylistState& s = playlist_.states[cursor_.current()];
    ImGui::PushTextWrapPos(max_w - 2.0f * em);
    ImGui::SetWindowFontScale(1.4f);
    ImGui::PushStyleColor(ImGuiCol_Text, ui::kCurrentText);
    ImGui::TextWrapped("%s", s.title.c_str());
    ImGui::PopStyleColor();
    ImGui::SetWindowFontScale(1.0f);
    ImGui::PopTextWrapPos();
    ImGui::TextDisabled("%zu / %zu%s", cursor_.current() + 1, playlist_.states.size(),
                        has_pending() ? "   loading ..." : "");
  }
  if (!error_.empty()) ImGui::TextColored(ui::miss_text(), "%s", error_.c_str());
  ImGui::End();
}

std::optional<size_t> PlaylistTool::states_section() {
  std::optional<size_t> clicked;
  if (!loaded()) {
    ImGui::TextDisabled("accelviz --playlist FILE (scenes/lecture.playlist)");
    return clicked;
  }
  ImGui::TextDisabled("%s", playlist_.name.c_str());
  if (ImGui::Button("< prev (PgUp)") && cursor_.current() > 0) clicked = prev_index();
  ImGui::SameLine();
  if (ImGui::Button("next (PgDn) >")) clicked = next_index();
  for (size_t i = 0; i < playlist_.states.size(); ++i) {
    char label[256];
    std::snprintf(label, sizeof label, "%2zu  %s", i + 1, playlist_.states[i].title.c_str());
    if (ImGui::Selectable(label, i == cursor_.current())) clicked = i;
  }
  if (!error_.empty()) ImGui::TextColored(ui::miss_text(), "%s", error_.c_str());
  return clicked;
}

// ---------------------------------------------------------------------------------------
// Keys and script verbs (the verbs registered in tools/playlist_verbs.h)

std::vector<KeyBinding> PlaylistTool::keys(ToolHost& host) {
  // A presenter's clicker sends PgDn / PgUp (some: the down and up arrows). Shift leaves
  // PgDn / PgUp to the construction's rows, as does having no playlist.
  auto move = [this, &host](bool forward, bool shift_passes) {
    return [this, &host, forward, shift_passes](const KeyPress& k) {
      if (!loaded() || (shift_passes && (k.mods & GLFW_MOD_SHIFT))) return false;
      host.go_to_state(forward ? next_index() : prev_index());
      return true;
    };
  };
  const char* keys = "PgDn / PgUp, down / up";
  const char* help = "with a playlist: next / previous state (a presenter's clicker sends these)";
  return {{GLFW_KEY_PAGE_DOWN, keys, help, move(true, true)},
          {GLFW_KEY_PAGE_UP, keys, help, move(false, true)},
          {GLFW_KEY_DOWN, keys, help, move(true, false)},
          {GLFW_KEY_UP, keys, help, move(false, false)}};
}

void PlaylistTool::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<PlaylistTool> verbs(table, *this, host);
  playlist_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void PlaylistTool::update(ToolHost& host, float) {
  if (!host.synchronous() && loaded()) host.run_playlist(nullptr);
}

void PlaylistTool::section(ToolHost& host, PanelSection section) {
  if (section != PanelSection::Own || !ImGui::CollapsingHeader("Playlist", loaded() ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    return;
  if (const auto state = states_section()) host.go_to_state(*state);
}

void PlaylistTool::overlay(ToolHost& host) {
  // At the top of the 3D view (window coordinates).
  const float sx = display_scale().x;
  const glm::ivec4 view = host.view_area();
  title_overlay(glm::vec4(static_cast<float>(view.x) / sx, 0.0f, static_cast<float>(view.z) / sx, 0.0f),
                ImGui::GetTime());
}

void PlaylistTool::window_title(std::string& title, const ToolHost&) const {
  if (!loaded()) return;
  title += " - " + state_line();
  if (has_pending()) title += " (loading)";
  else if (!error_.empty()) title += " (error)";
}

}  // namespace viz
