#include "tools/build_player.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "panels.h"
#include "tools/build_player_verbs.h"
#include "tools/structure_session.h"
#include "tools/transport_controls.h"
#include "tools/ui_colors.h"
#include "window_layout.h"

namespace viz {
namespace {

using accel::BuildEvent;
using accel::BuildEventKind;
using ui::kCurrentText;
using ui::kDimText;
using ui::hit_text;
using ui::kQueueText;

ImVec4 event_color(const BuildEvent& e) {
  switch (e.kind) {
    case BuildEventKind::Node: return kCurrentText;
    case BuildEventKind::Leaf: return hit_text();
    case BuildEventKind::Split:
    case BuildEventKind::Subdivide:
    case BuildEventKind::Merge: return ImVec4(1.0f, 0.55f, 0.9f, 1.0f);
    case BuildEventKind::Candidates:
    case BuildEventKind::Axis: return ImVec4(0.95f, 0.75f, 1.0f, 1.0f);
    case BuildEventKind::GridInsert:
    case BuildEventKind::InsertStep: return kQueueText;
    case BuildEventKind::Unrecorded: return kDimText;
    default: return ImVec4(1.0f, 1.0f, 1.0f, 1.0f);
  }
}

/// Records the build of `request` over `scene`: accel::build_structure_recorded(), or, for a
/// failed build's replay (a build-log call limit), the same recording of a structure set up
/// with the limit (create_requested), whose stop keeps the steps up to there (`*stopped`:
/// why it stopped) where the core's would return the stop as an error.
accel::Result<accel::RecordedBuild> record_build(const accel::Scene& scene, const StructureRequest& request,
                                                 accel::BuildControl* control, std::string* stopped) {
  auto choice = accel::parse_structure(request.name, request.params);
  if (!choice) return choice.error();
  const accel::StructureInfo& info = *choice.value().info;
  const accel::ParamSet& params = choice.value().params;
  const int first_depth_limit = accel::recording_first_depth_limit(scene.triangle_count());
  if (!request.build_call_limit)
    return accel::build_structure_recorded(info, scene, params, request.kernel,
                                           accel::BuildRecorder::kDefaultBudgetBytes, control, first_depth_limit);
  accel::RecordedBuild out;
  auto steps = accel::record_within_budget(
      [&](accel::BuildRecorder& recorder) -> accel::Status {
        std::unique_ptr<accel::Structure> s = create_requested(info, scene, params, request);
        stopped->clear();
        if (auto built = s->build_recorded(scene, params, recorder, control); !built) {
          if (!stopped_at_call_limit(*s)) return built.error();
          *stopped = built.error().message;
        }
        out.structure = std::move(s);
        return {};
      },
      first_depth_limit, accel::BuildRecorder::kDefaultBudgetBytes);
  if (!steps) return steps.error();
  out.trace = std::move(steps.value().trace);
  out.attempts = std::move(steps.value().attempts);
  return out;
}

const ImU32 kAxisColors[4] = {IM_COL32(255, 90, 90, 255), IM_COL32(90, 230, 110, 255), IM_COL32(100, 150, 255, 255),
                              IM_COL32(255, 200, 60, 255)};
const char* const kAxisNames[4] = {"x", "y", "z", "PCA"};

}  // namespace

// ---------------------------------------------------------------------------------------
// Recording

void BuildPlayer::construct(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                            bool synchronous) {
  record(std::move(scene), request, {}, synchronous);
}

void BuildPlayer::construct_until(std::shared_ptr<const accel::Scene> scene, StructureRequest request, size_t calls,
                                  std::vector<std::string> note, bool synchronous) {
  request.build_call_limit = calls;
  record(std::move(scene), request, std::move(note), synchronous);
}

void BuildPlayer::record(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                         std::vector<std::string> note, bool synchronous) {
  job_.wait();
  control_ = std::make_shared<accel::BuildControl>();
  pending_scene_ = scene;
  pending_request_ = request;
  pending_note_ = std::move(note);
  error_.clear();
  auto control = control_;
  job_.start(
      [scene, request, control](const std::atomic<bool>& cancel) -> Recording {
        if (cancel) return {accel::cancelled_error(), ""};
        std::string stopped;
        accel::Result<accel::RecordedBuild> build = record_build(*scene, request, control.get(), &stopped);
        return {std::move(build), std::move(stopped)};
      },
      synchronous);
  if (synchronous) poll();
}

void BuildPlayer::poll() {
  if (!job_.ready()) return;
  Recording recording = job_.take();
  accel::Result<accel::RecordedBuild>& result = recording.build;
  const bool cancelled = control_ && control_->cancelled();
  control_.reset();
  if (!result) {
    error_ = cancelled ? "construction cancelled" : result.error().message;
    return;
  }
  scene_ = std::move(pending_scene_);
  request_ = pending_request_;
  stopped_ = std::move(recording.stopped);
  note_ = std::move(pending_note_);
  pending_note_.clear();
  trace_ = std::make_shared<const accel::BuildTrace>(std::move(result.value().trace));
  attempts_ = result.value().attempts.size();
  // The SAH constants price the tree so far; a structure without them counts 1 each.
  const accel::BuildStats stats = result.value().structure->build_stats();
  sah_ct_ = stats.sah_ct > 0.0 ? stats.sah_ct : 1.0;
  sah_ci_ = stats.sah_ci > 0.0 ? stats.sah_ci : 1.0;
  sah_prims_per_test_ = std::max(1, stats.sah_prims_per_test);
  replay_ = std::make_unique<accel::BuildReplay>(*trace_);
  code_kind_ = build_code_kind(request_.name, request_.params);
  player_.load(trace_->events.size());
  // A failed build's replay opens where it failed: on its last call's step, the node it was
  // building current (the recording's closing "done" after it); a whole build at its end.
  fault_step_ = trace_->events.size();
  if (!stopped_.empty() && fault_step_ > 1 && trace_->events.back().kind == BuildEventKind::Done) --fault_step_;
  if (request_.build_call_limit) player_.seek(fault_step_);
  active_ = true;
  dirty_ = true;
}

void BuildPlayer::cancel() {
  if (control_) control_->cancel();
  job_.cancel();
}

void BuildPlayer::wait() {
  cancel();
  job_.wait();
}

void BuildPlayer::reset() {
  wait();
  control_.reset();
  active_ = false;
  trace_.reset();
  replay_.reset();
  scene_.reset();
  attempts_ = 0;
  stopped_.clear();
  note_.clear();
  player_.clear();
  view_ = BuildView{};
  gl_.changed();
  error_.clear();
}

accel::Status BuildPlayer::need_trace() const {
  if (!trace_) {
    if (!error_.empty()) return accel::make_error("construction failed: " + error_);
    return accel::make_error("no construction recorded yet (use construct first)");
  }
  return {};
}

std::string BuildPlayer::step_line() const {
  if (!trace_) return "no construction";
  return build_step_line(*trace_, player_.step());
}

void BuildPlayer::refresh() {
  if (!replay_ || !scene_) return;
  if (!dirty_ && view_step_ == player_.step()) return;
  dirty_ = false;
  view_step_ = player_.step();
  replay_->seek(player_.step());
  view_ = build_view(*trace_, *replay_, *scene_);
  gl_.changed();
}

// ---------------------------------------------------------------------------------------
// Panels

void BuildPlayer::control_panel(const PanelPlace& where, const std::shared_ptr<const accel::Scene>& scene,
                                const StructureRequest& request) {
  const float em = ImGui::GetFontSize();
  if (!ui::begin_panel(where, "Construction")) return;
  if (recording()) {
    ImGui::TextColored(kCurrentText, "recording the build of %s ... %.1f s", pending_request_.name.c_str(),
                       recording_seconds());
    ImGui::ProgressBar(static_cast<float>(recording_fraction()), ImVec2(-5.0f * em, 0.0f), "");
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) cancel();
  } else {
    if (ImGui::Button("Construct (B)")) construct(scene, request, false);
    ImGui::SameLine();
    if (ImGui::Button("Traversal mode")) active_ = false;
  }
  if (!error_.empty()) ImGui::TextColored(ui::miss_text(), "%s", error_.c_str());
  if (!trace_) {
    ImGui::TextWrapped("Construct records every step of the current structure's build and plays it.");
    ImGui::End();
    return;
  }
  // A replay's recording is "complete" only as far as the build went: up to the fault.
  std::string coverage = trace_->coverage();
  if (!stopped_.empty() && coverage == "complete") coverage = "every step up to the fault";
  ImGui::TextDisabled("%s (%s): %s", request_.name.c_str(), build_code_label(code_kind_), coverage.c_str());
  if (attempts_ > 1) {
    ImGui::SameLine();
    ImGui::TextDisabled("(%zu attempts)", attempts_);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("the step budget ran out: re-recorded with half the depth");
  }

  replay_lines();

  transport_controls(player_, {0, "nothing recorded"});

  const BuildEvent* e = replay_ ? replay_->current() : nullptr;
  if (e) {
    ImGui::PushStyleColor(ImGuiCol_Text, event_color(*e));
    ImGui::TextWrapped("%s", accel::describe_build_event(*trace_, *e).c_str());
    ImGui::PopStyleColor();
  } else {
    ImGui::TextDisabled("nothing built yet");
  }
  if (replay_ && ImGui::BeginTable("bcounters", 5, ImGuiTableFlags_SizingStretchSame | ImGuiTableFlags_BordersInnerH)) {
    for (const char* h : {"so far", "nodes", "leaves", "references", "SAH cost"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextDisabled("step %zu", player_.step());
    const size_t values[3] = {replay_->live_nodes(), replay_->leaves(), replay_->references()};
    for (int i = 0; i < 3; ++i) {
      ImGui::TableSetColumnIndex(i + 1);
      ImGui::Text("%zu", values[i]);
    }
    // The tree as it stands, open nodes priced as leaves (a grid has no tree: "-").
    ImGui::TableSetColumnIndex(4);
    const double cost = replay_->sah_cost(sah_ct_, sah_ci_, sah_prims_per_test_);
    if (std::isnan(cost))
      ImGui::TextDisabled("-");
    else
      ImGui::Text("%.4g", cost);
    ImGui::EndTable();
  }
  if (view_.nodes_capped) ImGui::TextDisabled("drawing the %zu shallowest nodes", view_.nodes_drawn);
  ImGui::Checkbox("SAH cost plot", &sah_plot_);
  if (sah_plot_) cost_plot_widget();
  ImGui::End();
}

void BuildPlayer::replay_lines() {
  const size_t calls = request_.build_call_limit;
  if (!calls) return;
  if (stopped_.empty()) {
    ImGui::TextDisabled("construct-until %zu: the build made fewer build-log calls; played whole", calls);
    return;
  }
  // What the viewer knows is where it stopped the build; what failed there, the check's
  // comments say (its state file's), when the replay came from one.
  std::string line = player_.step() >= fault_step_ ? "the build failed here in the check"
                                                   : "the build failed in the check after its last step";
  line += note_.empty() ? ": " + stopped_ : " (after " + std::to_string(calls) + " build-log calls): " + note_[0];
  ui::error_text(line, ImGui::GetContentRegionAvail().x);
  for (size_t i = 1; i < note_.size(); ++i) {
    ImGui::PushStyleColor(ImGuiCol_Text, kDimText);
    ImGui::TextWrapped("%s", note_[i].c_str());
    ImGui::PopStyleColor();
  }
}

void BuildPlayer::cost_plot_widget() {
  const CostPlot plot = trace_ ? cost_plot(*trace_, player_.step()) : CostPlot{};
  const float em = ImGui::GetFontSize();
  if (plot.curves.empty()) {
    ImGui::TextDisabled("C(B): no candidate planes at this step");
    return;
  }
  ImGui::Text("C(B) of node %u against the plane position", plot.node);
  const ImVec2 size(ImGui::GetContentRegionAvail().x, 6.0f * em);
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 p1(p0.x + size.x, p0.y + size.y);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(p0, p1, IM_COL32(20, 22, 28, 255));
  dl->AddRect(p0, p1, IM_COL32(120, 120, 130, 255));
  const float pad = 0.4f * em;
  const float lo = plot.min_cost, hi = plot.max_cost > plot.min_cost ? plot.max_cost : plot.min_cost + 1.0f;
  auto y_of = [&](float c) { return p1.y - pad - (c - lo) / (hi - lo) * (size.y - 2.0f * pad); };
  // Each axis on its own position range, stretched over the plot's width.
  for (size_t i = 0; i < plot.curves.size(); ++i) {
    const CostCurve& c = plot.curves[i];
    const auto [mn, mx] = std::minmax_element(c.pos.begin(), c.pos.end());
    const float a = *mn, b = *mx > *mn ? *mx : *mn + 1.0f;
    auto x_of = [&](float x) { return p0.x + pad + (x - a) / (b - a) * (size.x - 2.0f * pad); };
    const ImU32 col = kAxisColors[std::clamp(c.axis, 0, 3)];
    for (size_t k = 0; k + 1 < c.pos.size(); ++k)
      if (std::isfinite(c.cost[k]) && std::isfinite(c.cost[k + 1]))
        dl->AddLine(ImVec2(x_of(c.pos[k]), y_of(c.cost[k])), ImVec2(x_of(c.pos[k + 1]), y_of(c.cost[k + 1])), col, 2.0f);
    if (c.pos.size() == 1) dl->AddCircleFilled(ImVec2(x_of(c.pos[0]), y_of(c.cost[0])), 3.0f, col);
    const ImVec2 m(x_of(c.pos[c.best]), y_of(c.cost[c.best]));
    const bool overall = static_cast<int>(i) == plot.best_curve;
    dl->AddCircle(m, overall ? 6.0f : 4.0f, overall ? IM_COL32(255, 255, 255, 255) : col, 12, 2.0f);
  }
  if (plot.has_leaf_cost && std::isfinite(plot.leaf_cost)) {
    const float y = y_of(plot.leaf_cost);
    for (float x = p0.x + pad; x < p1.x - pad; x += 8.0f)
      dl->AddLine(ImVec2(x, y), ImVec2(std::min(x + 4.0f, p1.x - pad), y), IM_COL32(230, 230, 230, 220), 1.5f);
    dl->AddText(ImVec2(p0.x + pad, y - em), IM_COL32(230, 230, 230, 220), "leaf cost");
  }
  ImGui::Dummy(size);
  // Legend: the axes evaluated and their minima.
  for (size_t i = 0; i < plot.curves.size(); ++i) {
    const CostCurve& c = plot.curves[i];
    if (i) ImGui::SameLine();
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::ColorConvertU32ToFloat4(kAxisColors[std::clamp(c.axis, 0, 3)]));
    ImGui::Text("%s: min %.4g at %.4g%s", kAxisNames[std::clamp(c.axis, 0, 3)], static_cast<double>(c.cost[c.best]),
                static_cast<double>(c.pos[c.best]), static_cast<int>(i) == plot.best_curve ? " (best)" : "");
    ImGui::PopStyleColor();
  }
  if (plot.has_leaf_cost) ImGui::TextDisabled("leaf cost %.4g (dashed)", static_cast<double>(plot.leaf_cost));
}

void BuildPlayer::steps_panel(const PanelPlace& where) {
  if (!ui::begin_panel(where, "Construction steps")) return;
  if (!trace_ || trace_->events.empty()) {
    ImGui::TextDisabled("nothing recorded yet: Construct (B)");
    ImGui::End();
    return;
  }
  // Step K has applied events 0..K-1: the current row is the last one applied.
  const auto& events = trace_->events;
  const size_t applied = player_.step();
  const std::optional<size_t> current = applied ? std::optional<size_t>(applied - 1) : std::nullopt;
  const auto clicked = step_list(events.size(), current, applied, steps_, [&](size_t i) {
    return StepRow{events[i].depth, accel::describe_build_event(*trace_, events[i]), event_color(events[i])};
  });
  if (clicked) {
    player_.pause();
    player_.seek(*clicked + 1);
    steps_.scrolled = *clicked + 1;
  }
  ImGui::End();
}

void BuildPlayer::code_panel(const PanelPlace& where, ImFont* mono) {
  if (!ui::begin_panel(where, "Construction code")) return;
  const PseudoCode& code = build_pseudo_code(code_kind_);
  const int line = build_code_line(code_kind_, replay_ ? replay_->current() : nullptr);
  ImGui::TextDisabled("%s", code.title.c_str());
  ui::code_listing("bcode", code.lines, line, mono, code_scrolled_);
  ImGui::End();
}

// ---------------------------------------------------------------------------------------
// Keys and script verbs (the verbs registered in tools/build_player_verbs.h)

std::vector<KeyBinding> BuildPlayer::keys(ToolHost& host) {
  std::vector<KeyBinding> rows = {
      {GLFW_KEY_B, "B", "construction mode: record the current structure's build (again: back to the traversal)",
       [this, &host](const KeyPress&) {
         // A failed build's replay has no structure, but its construction plays again.
         const StructureSession& session = host.session();
         if (active())
           set_active(false);
         else if ((session.current() || session.current_request().build_call_limit) && !recording())
           host.construct();
         return true;
       }},
  };
  // PgUp / PgDn: the playlist's rows come first and leave them here without a playlist or
  // with shift.
  const std::vector<KeyBinding> transport =
      transport_keys(player_, {"construction", GLFW_KEY_P, "P", GLFW_KEY_COMMA, GLFW_KEY_PERIOD, ", / .",
                               GLFW_KEY_PAGE_UP, GLFW_KEY_PAGE_DOWN, "PgUp / PgDn", GLFW_KEY_MINUS, GLFW_KEY_EQUAL,
                               "- / =", " (with a playlist loaded: shift + PgUp / PgDn)"});
  rows.insert(rows.end(), transport.begin(), transport.end());
  return rows;
}

void BuildPlayer::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<BuildPlayer> verbs(table, *this, host);
  build_player_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// Drawing

void BuildPlayer::draw(Renderer& renderer, ToolHost&, DrawLayer layer) {
  if (layer == DrawLayer::Scene && active_) gl_.draw(renderer);
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void BuildPlayer::on_event(ToolEvent event, ToolHost&) {
  if (event == ToolEvent::SceneLoaded || event == ToolEvent::SceneEdited || event == ToolEvent::StructureInstalled)
    reset();  // recorded on another structure
  if (event == ToolEvent::PlaylistReset) set_active(false);
}

void BuildPlayer::update(ToolHost&, float dt) {
  poll();
  advance(static_cast<double>(dt));
}

void BuildPlayer::section(ToolHost& host, PanelSection section) {
  if (section != PanelSection::Structure) return;
  ImGui::BeginDisabled(!host.session().current() || recording());
  if (ImGui::Button("Construct (B)")) host.construct();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("record the build and watch it step by step");
  ImGui::SameLine();
  bool mode = active();
  if (ImGui::Checkbox("construction mode", &mode)) set_active(mode);
}

void BuildPlayer::panels(ToolHost& host) {
  if (!active() && !recording()) return;  // the traversal's panels are shown instead
  WindowLayout& layout = host.layout();
  const PanelSwitches& on = layout.panels();
  // The construction panel also holds the SAH cost plot: it takes a third of the code
  // panel's height (in lecture mode's large fonts the plot was cut off).
  WindowRect control = layout.rects().ray, code = layout.rects().code;
  const float moved = std::round(code.size.y / 3.0f);
  control.size.y += moved;
  code.pos.y += moved;
  code.size.y -= moved;
  const StructureSession& session = host.session();
  if (on.ray) control_panel(layout.place(control), session.scene_ptr(), session.current_request());
  if (on.steps) steps_panel(layout.place(layout.rects().steps));
  if (on.code) code_panel(layout.place(code), layout.mono());
}

}  // namespace viz
