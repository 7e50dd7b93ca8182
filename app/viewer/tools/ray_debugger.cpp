#include "tools/ray_debugger.h"

#include <algorithm>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "camera_control.h"
#include "input.h"
#include "panels.h"
#include "rays_io.h"
#include "tools/build_player.h"
#include "tools/compare_tool.h"
#include "tools/false_claims.h"
#include "tools/ray_debugger_verbs.h"
#include "tools/structure_session.h"
#include "tools/transport_controls.h"
#include "tools/traversal_numbers.h"
#include "tools/ui_colors.h"
#include "window_layout.h"

namespace viz {
using ui::fmt;
namespace {

using ui::kCullText;
using ui::kCurrentText;
using ui::kDimText;
using ui::kFalseClaimText;
using ui::hit_text;
using ui::miss_text;
using ui::kQueueText;

ImVec4 event_color(const accel::TraceEvent& e) {
  switch (e.kind) {
    case accel::TraceEventKind::Visit:
    case accel::TraceEventKind::EnterCell: return kCurrentText;
    case accel::TraceEventKind::Cull: return kCullText;
    case accel::TraceEventKind::Push:
    case accel::TraceEventKind::Pop: return kQueueText;
    case accel::TraceEventKind::TestPrim: return e.hit ? hit_text() : miss_text();
    case accel::TraceEventKind::NewClosest:
    case accel::TraceEventKind::Done: return ImVec4(1.0f, 1.0f, 1.0f, 1.0f);
  }
  return kDimText;
}

/// Counters of this ray: up to this step (`so_far`, `steps`), and for the whole traversal
/// (`total`, `total_steps`); `noun` names the structure's nodes.
void counters_table(const char* noun, const accel::QueryStats& so_far, const accel::QueryStats& total,
                    uint64_t steps, uint64_t total_steps) {
  if (!ImGui::BeginTable("counters", 5, ImGuiTableFlags_SizingStretchSame | ImGuiTableFlags_BordersInnerH)) return;
  for (const char* h_name : {"this ray", noun, "skipped", "triangles", "steps"}) ImGui::TableSetupColumn(h_name);
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
  row("so far", {so_far.nodes_visited, so_far.nodes_culled, so_far.prims_tested, steps});
  row("total", {total.nodes_visited, total.nodes_culled, total.prims_tested, total_steps});
  ImGui::EndTable();
}

/// Stack / priority queue contents (`pq`), reconstructed from the push/pop events so far:
/// "node @key" entries, wrapped between entries (never inside one).
void pending_line(const std::vector<accel::PendingNode>& pending, bool pq) {
  const float em = ImGui::GetFontSize();
  ImGui::PushStyleColor(ImGuiCol_Text, kQueueText);
  ImGui::Text("%s (%zu):", pq ? "priority queue, nearest first" : "stack, top first", pending.size());
  ImGui::PopStyleColor();
  std::vector<accel::PendingNode> list =
      pq ? accel::sorted_by_key(pending) : std::vector<accel::PendingNode>(pending.rbegin(), pending.rend());
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

/// What the 3D highlights' colours mean.
void colours_legend() {
  if (!ImGui::TreeNode("Colours")) return;
  ImGui::TextColored(kCurrentText, "current node and the ray's interval in it");
  ImGui::TextColored(ImVec4(0.85f, 0.88f, 0.95f, 1.0f), "nodes visited before (trail)");
  ImGui::TextColored(kQueueText, "pending on the stack / queue (thick: popped next)");
  ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.15f, 1.0f), "skipped: entered beyond the closest hit");
  ImGui::TextColored(ImVec4(0.7f, 0.55f, 1.0f, 1.0f), "skipped: the ray misses its bounds");
  ImGui::TextColored(kFalseClaimText, "FALSE: a student's logged claim the geometry contradicts");
  ImGui::TextColored(hit_text(), "triangle tested: hit");
  ImGui::SameLine();
  ImGui::TextColored(miss_text(), "  miss");
  ImGui::TextColored(ImVec4(1.0f, 0.78f, 0.05f, 1.0f), "closest hit so far");
  ImGui::SameLine();
  ImGui::TextColored(ImVec4(1.0f, 0.2f, 0.9f, 1.0f), "  hit point");
  ImGui::TreePop();
}

}  // namespace

// ---------------------------------------------------------------------------------------
// The ray and its trace

void RayDebugger::shoot(const accel::PinholeCamera& camera, glm::ivec4 view, float px, float py, bool from_saved_view,
                        const BuiltStructure* built) {
  // The core's camera model: the same ray the heat map and `accel::primary_rays` use for
  // this pixel, and the one through what is drawn there (Camera::pinhole()).
  // (px, py) are framebuffer pixels from the window's top-left; the camera images the view.
  accel::Ray ray = accel::camera_ray(camera, px - static_cast<float>(view.x),
                                     py - static_cast<float>(view.y), view.z, view.w);
  std::string origin = "click";
  if (from_saved_view && saved_view_ && built) {
    // From the saved viewpoint towards the surface point under the cursor.
    const accel::Hit h = built->structure->intersect(ray);
    if (h.valid() && ray.at(h.t) != saved_view_->eye) {
      const glm::vec3 target = ray.at(h.t);
      ray.org = saved_view_->eye;
      ray.dir = glm::normalize(target - ray.org);
      origin = "click from saved view";
    }
  }
  set_ray(ray, origin, built);
}

void RayDebugger::set_ray(const accel::Ray& ray, const std::string& origin, const BuiltStructure* built) {
  ray_.active = true;
  ray_.ray = ray;
  ray_.origin = origin;
  for (int i = 0; i < 3; ++i) {
    typed_ray_[i] = ray.org[i];
    typed_ray_[3 + i] = ray.dir[i];
  }
  if (built) {
    ray_.record(*built->structure, /*keep_step=*/false, built->scene.get());
  } else {
    ray_.hit = accel::Hit{};
    ray_.vars.clear();
    ray_.audit.reset();
    ray_.player.clear();
  }
  dirty_ = true;
}

void RayDebugger::replay(const BuiltStructure* built) {
  if (!ray_.active) return;
  if (built) {
    // Same ray, new structure: the step index stays, clamped to the new trace.
    ray_.record(*built->structure, /*keep_step=*/true, built->scene.get());
  }
  dirty_ = true;
}

std::string RayDebugger::hit_line() const {
  char text[96];
  if (ray_.hit.valid()) std::snprintf(text, sizeof text, "hit %d %.9g", ray_.hit.prim, static_cast<double>(ray_.hit.t));
  else std::snprintf(text, sizeof text, "miss");
  return text;
}

std::string RayDebugger::step_line() const {
  const accel::TraceEvent* e = ray_.player.current();
  if (!e) return "no trace";
  char text[64];
  std::snprintf(text, sizeof text, "step %zu/%zu: ", ray_.player.step() + 1, ray_.player.size());
  return text + step_text(*e, claims_at(ray_.audit, ray_.player.step()));
}

void RayDebugger::reset() {
  ray_ = DebugRay{};
  dirty_ = true;
}

void RayDebugger::advance(double seconds) {
  if (ray_.player.advance(seconds)) dirty_ = true;
}

void RayDebugger::refresh(const accel::Scene& scene, const BuiltStructure* built) {
  if (!dirty_ && highlight_step_ == ray_.player.step()) return;
  dirty_ = false;
  highlight_step_ = ray_.player.step();
  highlights_ = build_highlights(ray_, scene, built, options_);
  gl_.changed();
}

accel::Status RayDebugger::need_ray() const {
  if (!ray_.active) return accel::make_error("no debug ray yet (use ray-at-pixel or ray first)");
  return {};
}

accel::Status RayDebugger::need_trace() const {
  if (!ray_.active) return accel::make_error("no debug ray yet (use ray-at-pixel or ray first)");
  if (ray_.player.empty()) return accel::make_error("the ray has no recorded trace (no structure built)");
  return {};
}

std::string RayDebugger::ray_line() const { return accel::format_ray_line(ray_.ray, false); }

// ---------------------------------------------------------------------------------------
// Panels

bool RayDebugger::ray_panel(const PanelPlace& where, const BuiltStructure* built, bool board) {
  if (!ui::begin_panel(where, "Debug ray")) return false;
  bool compare = false;
  if (!ray_.active) {
    ImGui::TextWrapped("No debug ray yet: %s.", shoot_hint(board));
  } else {
    ImGui::TextDisabled("%s, %s", ray_.origin.c_str(), built ? built->request.name.c_str() : "?");
    if (built) {
      ImGui::SameLine();
      ImGui::TextDisabled("(%s)", traversal_label(built->kind));
    }
  }
  // Playback.
  accel::TracePlayer& p = ray_.player;
  const bool has = !p.empty();
  transport_controls(p, {1, "no trace"}, [&p] {
    if (ImGui::Button("Jump to hit")) p.jump_to_hit();
  });
  if (has) trace_lines(built);
  if (ImGui::Button("Compare structures (C)")) {
    compare = true;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the same ray through every structure and traversal order");
  if (!board) {  // the blackboard's clicks place corners: no viewpoint to shoot from
    ImGui::SameLine();
    ImGui::Checkbox("from saved view", &shoot_from_saved_);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("a click aims from the saved viewpoint (Scene > Save view) at the point under the cursor");
  }
  colours_legend();
  typed_ray(built);
  ImGui::End();
  return compare;
}

void RayDebugger::trace_lines(const BuiltStructure* built) {
  const accel::TracePlayer& p = ray_.player;
  // The current step, large and in its colour; a false claim of a student's log in the
  // warning colour with the truth, instead of the log's sentence when the step is the claim.
  const accel::TraceEvent& e = *p.current();
  const std::vector<const accel::FalseClaim*> claims = claims_at(ray_.audit, p.step());
  if (claims.empty() || !event_is_claim(e)) {
    ImGui::PushStyleColor(ImGuiCol_Text, event_color(e));
    ImGui::TextWrapped("%s", accel::describe_event(e).c_str());
    ImGui::PopStyleColor();
  }
  ImGui::PushStyleColor(ImGuiCol_Text, kFalseClaimText);
  for (const accel::FalseClaim* c : claims) ImGui::TextWrapped("%s", false_claim_text(*c).c_str());
  ImGui::PopStyleColor();
  const accel::TraceHighlight& h = highlights_.step;
  counters_table(built ? built->info->node_noun.c_str() : "nodes", h.counters, ray_.stats, p.step() + 1, p.size());
  if (ray_.truncated)
    ImGui::TextWrapped("The traversal made more steps than a recording keeps (%zu MiB): the first %zu steps and the "
                       "answer are shown; the totals count every step.",
                       accel::TraceRecorder::kDefaultBudgetBytes >> 20, p.size() - 1);
  if (h.closest_prim >= 0)
    ImGui::Text("closest so far: triangle %d at t=%.5g", h.closest_prim, static_cast<double>(h.closest_t));
  if (ray_.hit.valid())
    ImGui::Text("answer: triangle %d at t=%.5g", ray_.hit.prim, static_cast<double>(ray_.hit.t));
  else
    ImGui::TextUnformatted("answer: miss");
  // A student's walk: how much of its log the kit found false (the steps say which).
  if (ray_.audit) {
    ImGui::PushStyleColor(ImGuiCol_Text, ray_.audit->claims.empty() ? kDimText : kFalseClaimText);
    ImGui::TextWrapped("%s", claims_summary(*ray_.audit).c_str());
    ImGui::PopStyleColor();
  }
  if (!h.pending.empty()) pending_line(h.pending, built && built->kind == TraversalKind::HierarchyPqueue);
}

void RayDebugger::typed_ray(const BuiltStructure* built) {
  if (!ImGui::TreeNode("Type a ray")) return;
  const float em = ImGui::GetFontSize();
  ImGui::SetNextItemWidth(-4.0f * em);
  ImGui::InputFloat3("origin", typed_ray_, "%.4g");
  ImGui::SetNextItemWidth(-4.0f * em);
  ImGui::InputFloat3("dir", typed_ray_ + 3, "%.4g");
  if (ImGui::Button("Shoot")) {
    accel::Ray r;
    r.org = {typed_ray_[0], typed_ray_[1], typed_ray_[2]};
    r.dir = {typed_ray_[3], typed_ray_[4], typed_ray_[5]};
    if (r.dir != glm::vec3(0.0f)) set_ray(r, "typed", built);
  }
  ImGui::TreePop();
}

void RayDebugger::steps_panel(const PanelPlace& where, bool board) {
  if (!ui::begin_panel(where, "Traversal steps")) return;
  const auto& events = ray_.player.events();
  if (events.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("no trace yet: %s", shoot_hint(board));
    ImGui::PopStyleColor();
    ImGui::End();
    return;
  }
  const size_t current = ray_.player.step();
  const auto clicked = step_list(events.size(), current, current, steps_, [&](size_t i) {
    const accel::TraceEvent& e = events[i];
    const bool marked = marked_step_ && *marked_step_ == i;
    const std::vector<const accel::FalseClaim*> claims = claims_at(ray_.audit, i);
    // The marked step (a naive traversal's stop) in the trap window's colour; a student's
    // false claim in the warning colour.
    std::string text = step_text(e, claims);
    if (marked) text += "   <- " + marked_note_;
    const ImVec4 color = marked ? ImVec4(1.0f, 0.35f, 0.85f, 1.0f) : !claims.empty() ? kFalseClaimText : event_color(e);
    return StepRow{e.depth, text, color};
  });
  if (clicked) {
    ray_.player.pause();
    ray_.player.seek(*clicked);
    steps_.scrolled = *clicked;
  }
  ImGui::End();
}

void RayDebugger::code_panel(const PanelPlace& where, const BuiltStructure* built, ImFont* mono) {
  const TraversalKind kind = built ? built->kind : TraversalKind::Unknown;
  if (!ui::begin_panel(where, "Pseudo code")) return;
  const PseudoCode& code = pseudo_code(kind);
  ImGui::TextDisabled("%s", code.title.c_str());
  ui::code_listing("code", code.lines, highlights_.code_line, mono, code_scrolled_);
  ImGui::End();
}

void RayDebugger::highlight_options() {
  bool changed = ImGui::Checkbox("trail", &options_.trail);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("nodes the ray visited before the current one");
  ImGui::SameLine();
  changed |= ImGui::Checkbox("skipped", &options_.culled);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("pending", &options_.pending);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("nodes waiting on the stack / priority queue");
  if (changed) dirty_ = true;
}

// ---------------------------------------------------------------------------------------
// Keys and script verbs (the verbs registered in tools/ray_debugger_verbs.h)

std::vector<KeyBinding> RayDebugger::keys(ToolHost&) {
  std::vector<KeyBinding> rows = transport_keys(
      ray_.player, {"traversal", GLFW_KEY_SPACE, "space", GLFW_KEY_LEFT, GLFW_KEY_RIGHT, "left / right", GLFW_KEY_HOME,
                    GLFW_KEY_END, "Home / End", GLFW_KEY_LEFT_BRACKET, GLFW_KEY_RIGHT_BRACKET, "[ / ]"});
  // The jump to the hit after the transport's first / last step rows.
  rows.insert(rows.begin() + 5, {GLFW_KEY_J, "J", "jump to the hit", [this](const KeyPress&) {
                                   ray_.player.jump_to_hit();
                                   return true;
                                 }});
  return rows;
}

void RayDebugger::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<RayDebugger> verbs(table, *this, host);
  ray_debugger_verbs(verbs);
}

accel::Status RayDebugger::ray_at_pixel(ToolHost& host, float x, float y, ScriptHost& script) {
  host.settle_camera(script);
  const glm::ivec2 fb = host.framebuffer();
  const glm::ivec4 view = host.view_area();
  if (x < 0.0f || y < 0.0f || x >= static_cast<float>(fb.x) || y >= static_cast<float>(fb.y)) {
    char msg[128];
    std::snprintf(msg, sizeof msg, "ray-at-pixel: (%g, %g) is outside the %dx%d window", static_cast<double>(x),
                  static_cast<double>(y), fb.x, fb.y);
    return accel::make_error(msg);
  }
  if (x < static_cast<float>(view.x) || x >= static_cast<float>(view.x + view.z)) {
    char msg[160];
    std::snprintf(msg, sizeof msg,
                  "ray-at-pixel: x = %g is under a panel; the 3D view spans x = %d..%d (or: panel off)",
                  static_cast<double>(x), view.x, view.x + view.z - 1);
    return accel::make_error(msg);
  }
  // Pixel centres: "X Y" names the pixel, as a click into it does.
  host.shoot_at_pixel(x + 0.5f, y + 0.5f, shoot_from_saved_);
  return {};
}

// ---------------------------------------------------------------------------------------
// Drawing


// ---------------------------------------------------------------------------------------
// The tool's frame and its saved state

void RayDebugger::on_event(ToolEvent event, ToolHost& host) {
  if (event == ToolEvent::SceneLoaded) reset();
  if (event == ToolEvent::StructureInstalled) replay(host.session().current());
  if (event == ToolEvent::ColorsChanged) recolor();
}

void RayDebugger::mouse(const MouseFrame& m, ToolHost& host) {
  if (!m.left.click || host.camera().camera().top_down()) return;  // the blackboard's clicks are its own
  // A click: shoot through that pixel. Window coordinates -> framebuffer pixels.
  host.shoot_at_pixel(m.left.press_pos.x * m.scale.x, m.left.press_pos.y * m.scale.y, shoot_from_saved() || m.shift);
}

void RayDebugger::update(ToolHost& host, float dt) {
  advance(static_cast<double>(dt));
  // The highlights (and the numbers the panels show) of the step this frame starts at.
  refresh(host.session().scene(), host.session().current());
}

void RayDebugger::section(ToolHost&, PanelSection section) {
  if (section == PanelSection::Display) highlight_options();
}

void RayDebugger::panels(ToolHost& host) {
  const BuildPlayer& build = host.build();
  if (build.active() || build.recording()) return;  // the construction's panels take these places
  WindowLayout& layout = host.layout();
  const PanelLayout& rects = layout.rects();
  const PanelSwitches& on = layout.panels();
  const BuiltStructure* shown = host.session().shown();
  const bool board = host.session().scene().planar();
  if (on.ray && ray_panel(layout.place(rects.ray), shown, board)) {
    host.tool<CompareTool>().set_open(true);
    host.start_compare();
  }
  if (on.steps) steps_panel(layout.place(rects.steps), board);
  if (on.code) code_panel(layout.place(rects.code), shown, layout.mono());
}

void RayDebugger::late_update(ToolHost& host) { refresh(host.session().scene(), host.session().current()); }

void RayDebugger::draw(Renderer& renderer, ToolHost& host, DrawLayer layer) {
  if (layer == DrawLayer::Scene && !host.build().active()) gl_.draw(renderer);
}

void RayDebugger::save_state(std::string& out, const ToolHost& host) const {
  const StructureSession& session = host.session();
  if (!ray_.active || session.scene().planar() || session.current_request().build_call_limit) return;
  out += "ray " + accel::format_ray_line(ray_.ray) + "\n";
  if (ray_.player.step() > 0) out += "step " + std::to_string(ray_.player.step()) + "\n";
}

}  // namespace viz
