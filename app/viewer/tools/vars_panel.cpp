#include "tools/vars_panel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "input.h"
#include "panels.h"
#include "tool_host.h"
#include "tools/build_player.h"
#include "tools/false_claims.h"
#include "tools/ray_debugger.h"
#include "tools/structure_session.h"
#include "tools/trap_tool.h"
#include "tools/tree_diagram.h"
#include "tools/traversal_numbers.h"
#include "tools/ui_colors.h"
#include "window_layout.h"

namespace viz {
namespace {

using ui::kCullText;
using ui::kCurrentText;
using ui::kDimText;
using ui::kFalseClaimText;
using ui::hit_text;
using ui::kQueueText;

constexpr const char* kAxisUpper[3] = {"X", "Y", "Z"};
const ImVec4 kWhite(1.0f, 1.0f, 1.0f, 1.0f);
const ImVec4 kNaiveText(1.0f, 0.35f, 0.85f, 1.0f);  // the naive traversal's (wrong) answer

std::string num(float v) { return ui::fmt("%.5g", static_cast<double>(v)); }

void cell(int column, const std::string& text, const ImVec4& color = kWhite) {
  ImGui::TableSetColumnIndex(column);
  ImGui::TextColored(color, "%s", text.c_str());
}

/// A name/value row; `mono` for the value.
void value_row(const char* name, const std::string& value, ImFont* mono, const ImVec4& color = kWhite) {
  ImGui::TableNextRow();
  ImGui::TableSetColumnIndex(0);
  ImGui::TextColored(kDimText, "%s", name);
  ImGui::TableSetColumnIndex(1);
  if (mono) ImGui::PushFont(mono);
  ImGui::TextColored(color, "%s", value.c_str());
  if (mono) ImGui::PopFont();
}

/// A student's false claims (tools/false_claims.h), each in the warning colour.
void false_claims(std::span<const accel::FalseClaim* const> claims) {
  ImGui::PushStyleColor(ImGuiCol_Text, kFalseClaimText);
  for (const accel::FalseClaim* c : claims) ImGui::TextWrapped("%s", false_claim_text(*c).c_str());
  ImGui::PopStyleColor();
}

constexpr ImGuiTableFlags kTable = ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_BordersInnerH |
                                   ImGuiTableFlags_RowBg;

void grid_vars(const accel::GridDdaVars& v, float closest, ImFont* mono) {
  if (mono) ImGui::PushFont(mono);
  const int dims = v.dims == 2 ? 2 : 3;  // the blackboard's 2D DDA: X and Y
  if (ImGui::BeginTable("dda", dims + 1, kTable)) {
    ImGui::TableNextRow();
    for (int a = 0; a < dims; ++a) cell(a + 1, std::string(kAxisUpper[a]) + "=" + std::to_string(v.cell[a]));
    cell(0, "cell", kDimText);
    auto row = [&](const char* name, auto value_of) {
      ImGui::TableNextRow();
      cell(0, name, kDimText);
      for (int a = 0; a < dims; ++a) cell(a + 1, value_of(a), a == v.next_axis ? kCurrentText : kWhite);
    };
    row("step", [&](int a) { return std::to_string(v.step[a]); });
    row("tMax", [&](int a) { return num(v.t_max[a]); });
    row("tDelta", [&](int a) { return num(v.t_delta[a]); });
    ImGui::EndTable();
  }
  if (mono) ImGui::PopFont();
  const int n = (v.next_axis % 3 + 3) % 3;
  const float exit_t = v.t_max[n];
  ImGui::PushStyleColor(ImGuiCol_Text, kCurrentText);
  ImGui::TextWrapped("next: %s += step%s (tMax%s = %s is the smallest)", kAxisUpper[n], kAxisUpper[n], kAxisUpper[n],
                     num(exit_t).c_str());
  ImGui::PopStyleColor();
  // The lecture's rule: the walk may stop only at a hit inside the current cell.
  if (std::isfinite(closest)) {
    const bool inside = closest <= exit_t;
    ImGui::PushStyleColor(ImGuiCol_Text, inside ? hit_text() : kCullText);
    ImGui::TextWrapped("closest_hit %s %s tMax%s %s: %s", num(closest).c_str(), inside ? "<=" : ">", kAxisUpper[n],
                       num(exit_t).c_str(), inside ? "inside this cell, stop" : "beyond this cell, walk on");
    ImGui::PopStyleColor();
  }
}

void kd_split_vars(const accel::KdSplitVars& v, ImFont* mono, std::span<const accel::FalseClaim* const> claims) {
  if (ImGui::BeginTable("kd", 2, kTable)) {
    value_row("t_min", num(v.t_min), mono);
    value_row("t_split", num(v.t_split), mono, kCurrentText);
    value_row("t_max", num(v.t_max), mono);
    value_row("split axis", kAxisUpper[(v.axis % 3 + 3) % 3], mono);
    value_row("near child", std::to_string(v.near_child), mono);
    value_row("far child", std::to_string(v.far_child), mono);
    ImGui::EndTable();
  }
  struct Case {
    accel::KdCase kase;
    const char* text;
  };
  const Case cases[3] = {
      {accel::KdCase::Both, "(a) t_min <= t_split <= t_max: near on [t_min, t_split], far on [t_split, t_max]"},
      {accel::KdCase::NearOnly, "(b) t_split > t_max: near child only"},
      {accel::KdCase::FarOnly, "(c) t_split < t_min: far child only"},
  };
  // The case the log took is marked as taken; a false one is said so below it.
  for (const Case& c : cases) {
    const bool on = c.kase == v.kase;
    ImGui::PushStyleColor(ImGuiCol_Text, on ? (claims.empty() ? kCurrentText : kFalseClaimText) : kDimText);
    ImGui::TextWrapped("%s %s", on ? ">" : " ", c.text);
    ImGui::PopStyleColor();
  }
  false_claims(claims);
}

void kd_exit_vars(const accel::KdExitVars& v, ImFont* mono, std::span<const accel::FalseClaim* const> claims) {
  ImGui::PushStyleColor(ImGuiCol_Text, kQueueText);
  ImGui::TextWrapped("pop the far child %u: early exit if t_hit < t_split", v.far_child);
  ImGui::PopStyleColor();
  if (ImGui::BeginTable("kdexit", 2, kTable)) {
    value_row("t_hit", num(v.t_hit), mono);
    value_row("t_split", num(v.t_split), mono);
    ImGui::EndTable();
  }
  // A false early exit is never narrated as the lecture's (true) one: the truth instead.
  if (!claims.empty()) {
    false_claims(claims);
    return;
  }
  ImGui::PushStyleColor(ImGuiCol_Text, v.exits ? hit_text() : kCullText);
  if (v.exits)
    ImGui::TextWrapped("%s < %s: the hit lies before the far child: return it", num(v.t_hit).c_str(),
                       num(v.t_split).c_str());
  else
    ImGui::TextWrapped("%s >= %s: a nearer hit may wait in the far child: go on", num(v.t_hit).c_str(),
                       num(v.t_split).c_str());
  ImGui::PopStyleColor();
}

const char* fate_text(accel::OctreeOrderVars::Fate f) {
  switch (f) {
    case accel::OctreeOrderVars::Fate::Pushed: return "pushed";
    case accel::OctreeOrderVars::Fate::Missed: return "missed";
    case accel::OctreeOrderVars::Fate::BeyondClosestHit: return "beyond closest hit";
    case accel::OctreeOrderVars::Fate::Empty: return "empty";
  }
  return "";
}

void octree_vars(const accel::OctreeOrderVars& v, ImFont* mono, std::span<const accel::FalseClaim* const> claims) {
  ImGui::PushStyleColor(ImGuiCol_Text, kDimText);
  ImGui::TextWrapped("child order: octant i ^ mask, mask = %u (axes the ray travels down)", v.mask);
  ImGui::PopStyleColor();
  if (mono) ImGui::PushFont(mono);
  if (ImGui::BeginTable("oct", 6, kTable)) {
    for (const char* h : {"#", "octant", "node", "t_enter", "t_exit", "fate"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (int i = 0; i < v.count && i < 8; ++i) {
      const accel::OctreeOrderVars::Child& c = v.children[i];
      const ImVec4 color = c.fate == accel::OctreeOrderVars::Fate::Pushed ? kQueueText
                           : c.fate == accel::OctreeOrderVars::Fate::Empty ? kDimText
                                                                            : kCullText;
      ImGui::TableNextRow();
      cell(0, std::to_string(i + 1), kDimText);
      cell(1, std::to_string(c.octant), color);
      cell(2, c.node == accel::kNoNode ? "-" : std::to_string(c.node), color);
      const bool timed = c.fate != accel::OctreeOrderVars::Fate::Empty && c.fate != accel::OctreeOrderVars::Fate::Missed;
      cell(3, timed ? num(c.t_enter) : "", color);
      cell(4, timed ? num(c.t_exit) : "", color);
      cell(5, fate_text(c.fate), color);
    }
    ImGui::EndTable();
  }
  if (mono) ImGui::PopFont();
  false_claims(claims);
}

void pending_table(const accel::TraceHighlight& h, TraversalKind kind, ImFont* mono) {
  const bool queue = kind == TraversalKind::HierarchyPqueue;
  const std::vector<accel::PendingNode> pending = pending_in_pop_order(h, kind);
  ImGui::TextColored(kQueueText, "%s (%zu)", queue ? "priority queue, nearest first" : "stack, top first",
                     pending.size());
  if (pending.empty()) return;
  if (mono) ImGui::PushFont(mono);
  constexpr size_t kShown = 12;
  if (ImGui::BeginTable("pending", 3, kTable)) {
    for (const char* name : {"node", "key (entry t)", "vs closest_hit"}) ImGui::TableSetupColumn(name);
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < pending.size() && i < kShown; ++i) {
      const accel::PendingNode& p = pending[i];
      // The key decides at the pop: a node entered beyond the closest hit is skipped.
      const bool skip = p.key > h.closest_t;
      ImGui::TableNextRow();
      cell(0, std::to_string(p.node), i == 0 ? kCurrentText : kWhite);
      cell(1, num(p.key));
      cell(2, skip ? "> closest: skip" : "<= closest: visit", skip ? kCullText : hit_text());
    }
    ImGui::EndTable();
  }
  if (pending.size() > kShown) ImGui::TextColored(kDimText, "... %zu more", pending.size() - kShown);
  if (mono) ImGui::PopFont();
}

/// The t-axis strip's place in its window: the rows (title, visited intervals, keys, axis),
/// the axis's ends, t to x, and the colours.
struct StripCanvas {
  explicit StripCanvas(const TStrip& s)
      : em(ImGui::GetFontSize()),
        dl(ImGui::GetWindowDrawList()),
        p0(ImGui::GetCursorScreenPos()),
        avail(ImGui::GetContentRegionAvail()),
        x0(p0.x + 4.4f * em),  // the row names on the left
        x1(p0.x + avail.x - 0.5f * em),
        t_lo(s.t_lo),
        span(std::max(s.t_hi - s.t_lo, 1e-30f)),
        y_title(p0.y),
        y_int(p0.y + 1.15f * em),
        y_keys(y_int + 1.15f * em),
        y_axis(y_keys + 1.15f * em) {}

  float x_of(float t) const {
    const float u = std::clamp((t - t_lo) / span, -0.01f, 1.01f);
    return x0 + u * (x1 - x0);
  }

  float em;
  ImDrawList* dl;
  ImVec2 p0, avail;
  float x0, x1;  // the axis's ends: t_lo and t_hi
  float t_lo, span;
  float y_title, y_int, y_keys, y_axis;  // the rows' tops
  ImU32 dim = ImGui::GetColorU32(kDimText), white = ImGui::GetColorU32(kWhite);
  ImU32 current = ImGui::GetColorU32(kCurrentText), queue = ImGui::GetColorU32(kQueueText);
  ImU32 hit = ImGui::GetColorU32(ImVec4(1.0f, 0.78f, 0.05f, 1.0f));
};

/// "t in [lo, hi]", with tmin when the strip starts after it.
std::string strip_title(const TStrip& s, float tmin) {
  char title[160];
  if (s.t_lo > tmin)
    std::snprintf(title, sizeof title, "t in [%s, %s] (tmin %s)", num(s.t_lo).c_str(), num(s.t_hi).c_str(),
                  num(tmin).c_str());
  else
    std::snprintf(title, sizeof title, "t in [%s, %s]", num(s.t_lo).c_str(), num(s.t_hi).c_str());
  return title;
}

/// The visited intervals: earlier ones faint (overlaps add up), the current one bright.
void strip_intervals(const StripCanvas& c, const TStrip& s) {
  const float em = c.em;
  const float bar_h = 0.55f * em, bar_y = c.y_int + 0.25f * em;
  for (const TStrip::Interval& iv : s.intervals) {
    if (iv.current || !(iv.t1 >= iv.t0)) continue;
    c.dl->AddRectFilled(ImVec2(c.x_of(iv.t0), bar_y),
                        ImVec2(std::max(c.x_of(iv.t1), c.x_of(iv.t0) + 1.0f), bar_y + bar_h),
                        ImGui::GetColorU32(ImVec4(0.85f, 0.88f, 0.95f, 0.22f)));
  }
  for (const TStrip::Interval& iv : s.intervals) {
    if (!iv.current || !(iv.t1 >= iv.t0)) continue;
    const float a = c.x_of(iv.t0), b = std::max(c.x_of(iv.t1), a + 2.0f);
    c.dl->AddRectFilled(ImVec2(a, bar_y - 0.1f * em), ImVec2(b, bar_y + bar_h + 0.1f * em), c.current);
  }
}

/// Push keys (pending bright, taken faint) and the kd-tree's split distances.
void strip_keys_and_splits(const StripCanvas& c, const TStrip& s) {
  const float em = c.em;
  const float tick_y = c.y_keys + 0.15f * em, tick_h = 0.8f * em;
  for (const TStrip::Key& k : s.keys) {
    if (!std::isfinite(k.t)) continue;
    const float x = c.x_of(k.t);
    const ImU32 color = k.pending ? c.queue : ImGui::GetColorU32(ImVec4(kQueueText.x, kQueueText.y, kQueueText.z, 0.3f));
    c.dl->AddTriangleFilled(ImVec2(x, tick_y + tick_h), ImVec2(x - 0.3f * em, tick_y + 0.3f * em),
                            ImVec2(x + 0.3f * em, tick_y + 0.3f * em), color);
  }
  for (const TStrip::Split& sp : s.splits) {
    if (!std::isfinite(sp.t) || sp.t < s.t_lo - c.span || sp.t > s.t_hi + c.span) continue;
    const float x = c.x_of(sp.t);
    c.dl->AddLine(ImVec2(x, tick_y), ImVec2(x, tick_y + tick_h), sp.current ? c.current : c.dim,
                  sp.current ? 0.2f * em : 0.08f * em);
  }
}

/// The axis with ticks at tmin and tmax.
void strip_axis(const StripCanvas& c, const TStrip& s) {
  const float em = c.em;
  c.dl->AddLine(ImVec2(c.x0, c.y_axis), ImVec2(c.x1, c.y_axis), c.white, 0.08f * em);
  c.dl->AddText(ImVec2(c.x0, c.y_axis + 0.1f * em), c.dim, num(s.t_lo).c_str());
  const std::string hi = num(s.t_hi);
  c.dl->AddText(ImVec2(c.x1 - ImGui::CalcTextSize(hi.c_str()).x, c.y_axis + 0.1f * em), c.dim, hi.c_str());
}

/// The current event's own distance, the closest hit so far (labelled right of `title`),
/// and the naive answer where it differs from the true one.
void strip_markers(const StripCanvas& c, const TStrip& s, const std::string& title, const DebugRay& ray,
                   const accel::NaiveAnswer* naive) {
  const float em = c.em;
  const float top = c.y_int, bottom = c.y_axis;
  if (std::isfinite(s.event_t)) {
    const float x = c.x_of(s.event_t);
    c.dl->AddLine(ImVec2(x, top), ImVec2(x, bottom), c.white, 0.06f * em);
  }
  if (std::isfinite(s.closest)) {
    const float x = c.x_of(s.closest);
    c.dl->AddLine(ImVec2(x, top - 0.2f * em), ImVec2(x, bottom + 0.2f * em), c.hit, 0.22f * em);
    // Labelled on the title row, right of the title so the two never overlap.
    const float title_end = c.p0.x + ImGui::CalcTextSize(title.c_str()).x + em;
    std::string label = "closest_hit " + num(s.closest);
    if (title_end + ImGui::CalcTextSize(label.c_str()).x > c.x1) label = "hit " + num(s.closest);  // a narrow view
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    c.dl->AddText(ImVec2(std::max(std::min(x - 0.5f * w, c.x1 - w), title_end), c.y_title), c.hit, label.c_str());
  }
  if (naive && naive->hit && (!ray.hit.valid() || naive->prim != ray.hit.prim)) {
    const float x = c.x_of(naive->t);
    const ImU32 color = ImGui::GetColorU32(kNaiveText);
    for (float y = top; y < bottom; y += 0.5f * em)
      c.dl->AddLine(ImVec2(x, y), ImVec2(x, y + 0.3f * em), color, 0.18f * em);
    // On the keys row, beside the marker (the axis row holds the tmin and tmax labels).
    const std::string label = "naive " + num(naive->t);
    const float w = ImGui::CalcTextSize(label.c_str()).x;
    c.dl->AddText(ImVec2(x + 0.3f * em + w <= c.x1 ? x + 0.3f * em : x - 0.3f * em - w, c.y_keys), color,
                  label.c_str());
  }
}

}  // namespace

void VarsPanel::panel(const PanelPlace& where, const DebugRay& ray, const accel::TraceHighlight& h, TraversalKind kind,
                      bool board, ImFont* mono, const std::function<void()>& top_block) {
  if (!ui::begin_panel(where, "Variables")) return;
  if (top_block) top_block();
  const auto& events = ray.player.events();
  if (!ray.active || events.empty() || !h.valid) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("the traversal's variables at the current step: %s", shoot_hint(board));
    ImGui::PopStyleColor();
    ImGui::End();
    return;
  }
  ImGui::TextDisabled("%s, step %zu of %zu", traversal_label(kind), h.step + 1, events.size());
  // A student's false claims: those of the variables shown (recorded at an earlier step of
  // this node, e.g. the early exit's pop before its cull) beside them; the current step's
  // others (a cull) here first.
  const std::optional<size_t> vars_event = shown_vars_event(events, ray.vars, h.step);
  const std::vector<const accel::FalseClaim*> vars_claims =
      vars_event ? claims_at(ray.audit, *vars_event) : std::vector<const accel::FalseClaim*>{};
  if (!vars_event || *vars_event != h.step) false_claims(claims_at(ray.audit, h.step));
  const accel::StepVars* v = accel::vars_at(events, ray.vars, h.step);
  if (v) {
    if (const auto* g = std::get_if<accel::GridDdaVars>(v)) {
      grid_vars(*g, h.closest_t, mono);
      false_claims(vars_claims);
    } else if (const auto* k = std::get_if<accel::KdSplitVars>(v)) {
      kd_split_vars(*k, mono, vars_claims);
    } else if (const auto* x = std::get_if<accel::KdExitVars>(v)) {
      kd_exit_vars(*x, mono, vars_claims);
    } else if (const auto* o = std::get_if<accel::OctreeOrderVars>(v)) {
      octree_vars(*o, mono, vars_claims);
    }
  } else if (kind == TraversalKind::Grid || kind == TraversalKind::Grid2d || kind == TraversalKind::KdTree ||
             kind == TraversalKind::Octree) {
    ImGui::TextDisabled(h.node == accel::kNoNode ? "before the first node" : "a leaf: testing its triangles");
  }
  ImGui::Separator();
  if (std::isfinite(h.closest_t))
    ImGui::TextColored(hit_text(), "closest_hit = %s (triangle %d)", num(h.closest_t).c_str(), h.closest_prim);
  else
    ImGui::TextColored(kDimText, "closest_hit = inf (nothing hit yet)");
  if (keeps_pending(kind)) pending_table(h, kind, mono);
  ImGui::End();
}

void VarsPanel::strip(const WindowRect& rect, const DebugRay& ray, const accel::TraceHighlight& h,
                      const accel::NaiveAnswer* naive) {
  const auto& events = ray.player.events();
  if (!ray.active || events.empty() || !h.valid || rect.size.x < 1.0f || rect.size.y < 1.0f) return;
  float t_lo = 0.0f, t_hi = 1.0f;
  t_strip_range(events, ray.ray.tmin, t_lo, t_hi);
  if (naive && naive->hit) t_hi = std::max(t_hi, naive->t);
  const TStrip s = t_strip_at(events, ray.vars, h, t_lo, t_hi);

  ImGui::SetNextWindowPos(ImVec2(rect.pos.x, rect.pos.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(rect.size.x, rect.size.y), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.82f);
  if (!ImGui::Begin("##t-strip", nullptr,
                    ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                        ImGuiWindowFlags_NoFocusOnAppearing | ImGuiWindowFlags_NoNav |
                        ImGuiWindowFlags_NoBringToFrontOnFocus)) {
    ImGui::End();
    return;
  }
  const StripCanvas canvas(s);
  const std::string title = strip_title(s, ray.ray.tmin);
  canvas.dl->AddText(ImVec2(canvas.p0.x, canvas.y_title), canvas.white, title.c_str());
  canvas.dl->AddText(ImVec2(canvas.p0.x, canvas.y_int), canvas.dim, "visited");
  canvas.dl->AddText(ImVec2(canvas.p0.x, canvas.y_keys), canvas.dim, "keys");
  strip_intervals(canvas, s);
  strip_keys_and_splits(canvas, s);
  strip_axis(canvas, s);
  strip_markers(canvas, s, title, ray, naive);
  ImGui::Dummy(canvas.avail);
  ImGui::End();
}

// ---------------------------------------------------------------------------------------
// Keys

std::vector<KeyBinding> VarsPanel::keys(ToolHost&) {
  return {{GLFW_KEY_V, "V", "the Variables panel and the t-axis strip, together", [this](const KeyPress&) {
             shown_ = !(shown_ && strip_shown_);
             strip_shown_ = shown_;
             return true;
           }}};
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void VarsPanel::on_event(ToolEvent event, ToolHost&) {
  if (event != ToolEvent::PlaylistReset) return;
  shown_ = true;
  strip_shown_ = true;
}

void VarsPanel::update(ToolHost& host, float) {
  const BuildPlayer& build = host.build();
  host.layout().set_vars_column(shown_ && !build.active() && !build.recording());
}

void VarsPanel::panels(ToolHost& host) {
  const BuildPlayer& build = host.build();
  if (build.active()) return;
  WindowLayout& layout = host.layout();
  const PanelLayout& rects = layout.rects();
  RayDebugger& ray = host.ray();
  TrapTool& trap = host.tool<TrapTool>();
  if (shown_ && !build.recording()) {
    WindowRect rect = rects.vars;
    const float em = ImGui::GetFontSize();
    if (layout.lecture() && host.tool<TreeDiagram>().on())
      rect.size.y = std::max(rects.tree.pos.y - rect.pos.y - rects.main.pos.y, 6.0f * em);
    const BuiltStructure* shown = host.session().shown();
    panel(layout.place(rect), ray.ray(), ray.step_highlight(), shown ? shown->kind : TraversalKind::Unknown,
          host.session().scene().planar(), layout.mono(), [&] { trap.block(ray.ray(), ray.player()); });
  }
  if (!strip_shown_) return;
  // The t-axis strip along the bottom of the 3D view, between the docked panels (known
  // now: every docked panel of this frame has been drawn).
  const DockEdges& dock = layout.dock();
  const ImGuiIO& io = ImGui::GetIO();
  const float em = ImGui::GetFontSize(), pad = 0.4f * em;
  const float left = dock.left > 0.0f ? dock.left + pad : pad;
  const float right = (dock.right < io.DisplaySize.x ? dock.right : io.DisplaySize.x) - pad;
  const float h = strip_height(em);
  if (right - left < 12.0f * em) return;  // no room beside the panels
  // Above the tree diagram when it is docked along the bottom.
  const float bottom = dock.bottom > 0.0f ? dock.bottom : io.DisplaySize.y;
  strip({{left, bottom - h - pad}, {right - left, h}}, ray.ray(), ray.step_highlight(),
        trap.misleads() || trap.marked_step() ? &trap.naive() : nullptr);
}

bool VarsPanel::set_panel(const std::string& name, bool on) {
  if (name == "vars") shown_ = on;
  else if (name == "strip") strip_shown_ = on;
  else return false;
  return true;
}

}  // namespace viz
