// The "Tree" window (tree_diagram.h): index [SECTION]s
//   Following     update(): what changed since the last frame, and what that rebuilds
//   Selection     select(), the 3D highlight of the selection
//   The window    panel(), the legend, the node numbers
//   The grid      the cell walk table
// The diagram's canvas (zoom, pan, follow, edges, nodes, hover, click) is
// tree_diagram_canvas.cpp's.
#include "tools/tree_diagram.h"

#include <algorithm>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "input.h"
#include "panels.h"
#include "registry.h"
#include "tools/build_player.h"
#include "tools/ray_debugger.h"
#include "tools/structure_session.h"
#include "tools/tree_diagram_colors.h"
#include "tools/tree_diagram_verbs.h"
#include "tools/ui_colors.h"
#include "tools/vars_panel.h"
#include "window_layout.h"

namespace viz {
namespace {

using tree_colors::color_u32;
using tree_colors::state_color;

// Top levels opened breadth-first besides the ray's path: enough to see the tree's shape,
// few enough that the path stays the diagram's subject. Without a ray more are opened.
constexpr size_t kBudgetWithTrace = 15;
constexpr size_t kBudgetWithoutTrace = 63;
// An isolated subtree draws at most this many nodes in 3D (breadth-first: the top levels),
// about what the node display shows of a big tree at first: more only slows the frame.
constexpr size_t kMaxIsolatedNodes = 4095;
// Column width of the node numbers beside the diagram.
constexpr float kNumbersEm = 15.0f;

const glm::vec4 kSelected3D(1.0f, 0.3f, 0.9f, 1.0f);  // as the diagram's selection ring

/// The grid's resolution from its statistics line "resolution" = "NXxNYxNZ" (0s: unknown).
void grid_resolution(const accel::BuildStats& stats, int res[3]) {
  res[0] = res[1] = res[2] = 0;
  for (const auto& [key, value] : stats.extra)
    if (key == "resolution" && std::sscanf(value.c_str(), "%dx%dx%d", &res[0], &res[1], &res[2]) != 3)
      res[0] = res[1] = res[2] = 0;
}

SahConstants sah_constants(const BuiltStructure* b) {
  // The structure's own build constants; 1 and 1 (the lecture's) where it reports none.
  SahConstants k;
  if (b && (b->stats.sah_ct > 0.0 || b->stats.sah_ci > 0.0)) k = {b->stats.sah_ct, b->stats.sah_ci};
  return k;
}

}  // namespace

// =======================================================================================
// [SECTION] Following

void TreeDiagram::follow(const BuiltPtr& built, const DebugRay& ray, const accel::BuildReplay* replay) {
  ray_ = &ray;
  if (built != built_) {
    // Another structure: its ids mean other nodes. Index it again when shown.
    built_ = built;
    structure_ = nullptr;
    shape_.reset();
    index_ = TreeIndex();
    grid_ = built_ && built_->info && built_->info->cells;
    selected_ = kNoNode;
    summary_.reset();
    trace_data_ = nullptr;
    trace_size_ = 0;
    layout_dirty_ = true;
    highlight_dirty_ = true;
    fit_pending_ = true;
  }
  if (!on_) return;
  const bool replay_mode = replay != nullptr && !grid_;
  if (replay_mode != replay_mode_) {
    replay_mode_ = replay_mode;
    selected_ = kNoNode;  // slots and node ids differ
    summary_.reset();
    layout_dirty_ = true;
    highlight_dirty_ = true;
    fit_pending_ = true;
    replay_ = nullptr;
  }
  if (replay_mode_) {
    if (replay != replay_ || replay->step() != replay_step_) {
      replay_ = replay;
      replay_step_ = replay->step();
      const accel::BuildEvent* e = replay->current();
      replay_current_ = e ? replay->slot(build_event_node(*e)) : kNoNode;
      layout_dirty_ = true;
    }
  } else {
    if (built_ && built_->structure && !grid_ && structure_ != built_->structure.get()) {
      structure_ = built_->structure.get();
      shape_ = std::make_unique<StructureTreeShape>(*structure_, built_->stats.nodes);
      index_ = TreeIndex(*shape_);  // one O(nodes) pass per structure
    }
    const std::vector<accel::TraceEvent>& events = ray.player.events();
    const accel::TraceEvent* data = ray.active && !events.empty() ? events.data() : nullptr;
    const size_t size = data ? events.size() : 0;
    if (data != trace_data_ || size != trace_size_) {
      trace_data_ = data;
      trace_size_ = size;
      states_ = TraceStates(std::span<const accel::TraceEvent>(data, size));
      if (grid_) {
        int res[3];
        grid_resolution(built_->stats, res);
        grid_rows_ = grid_walk_rows(std::span<const accel::TraceEvent>(data, size), ray.vars, res);
        grid_scrolled_ = -2;
      }
      layout_dirty_ = true;
      follow_ = true;
      fit_pending_ = true;
    }
  }
  if (layout_dirty_) rebuild_layout();
  const size_t step = ray.player.step();
  if (step != step_) {
    step_ = step;
    refresh_states();
  }
  if (highlight_dirty_) rebuild_highlight();
}

void TreeDiagram::rebuild_layout() {
  layout_dirty_ = false;
  layout_ = TreeLayout();
  TreeLayoutOptions options;
  if (selected_ != kNoNode) {
    options.focus.push_back(selected_);
    options.open.push_back(selected_);
  }
  if (replay_mode_ && replay_) {
    const ReplayTreeShape shape(*replay_);
    const TreeIndex index(shape);
    if (replay_current_ != kNoNode) options.focus.push_back(replay_current_);
    options.budget = kBudgetWithoutTrace;
    layout_ = layout_tree(shape, index, options);
    if (selected_ != kNoNode && index.subtree_nodes(selected_) > 0) {
      summary_ = summarize_subtree(shape, selected_, sah_constants(built_.get()));
      const accel::ReplayNode& n = replay_->nodes()[selected_];
      selected_view_ = accel::NodeView{};
      selected_view_.id = selected_;
      selected_view_.depth = shape.info(selected_).depth;
      selected_view_.leaf = n.leaf;
      selected_view_.prim_count = n.prim_count;
      selected_view_.box = n.box;
      selected_view_.sphere = n.sphere;
    } else {
      selected_ = kNoNode;
      summary_.reset();
    }
  } else if (shape_) {
    const std::vector<NodeId> touched =
        touched_nodes(std::span<const accel::TraceEvent>(trace_data_, trace_size_));
    options.focus.insert(options.focus.end(), touched.begin(), touched.end());
    options.budget = touched.empty() ? kBudgetWithoutTrace : kBudgetWithTrace;
    layout_ = layout_tree(*shape_, index_, options);
  }
  refresh_states();
}

void TreeDiagram::refresh_states() {
  status_.assign(layout_.items.size(), TreeNodeStatus{});
  for (size_t i = 0; i < layout_.items.size(); ++i) {
    const TreeItem& it = layout_.items[i];
    if (it.kind == TreeItem::Kind::Collapsed) continue;  // no event touches it: not reached
    status_[i] = replay_mode_ && replay_ ? replay_state(*replay_, it.node, replay_current_)
                                         : states_.at(it.node, step_);
  }
  const NodeId current = replay_mode_ ? replay_current_ : states_.current(step_);
  current_item_ = current == kNoNode ? -1 : layout_.find(current);
}

// =======================================================================================
// [SECTION] Selection

accel::Status TreeDiagram::select(NodeId node, bool isolate) {
  if (!built_ || !built_->structure) return accel::make_error("tree-select: no structure built yet");
  if (grid_)
    return accel::make_error("tree-select: the " + built_->info->label +
                             " has no tree (the Tree window shows its cell walk as a table)");
  on_ = true;
  if (replay_mode_)
    return accel::make_error(
        "tree-select: selects a node of the built structure; leave the construction mode first (B)");
  if (structure_ != built_->structure.get()) {
    structure_ = built_->structure.get();
    shape_ = std::make_unique<StructureTreeShape>(*structure_, built_->stats.nodes);
    index_ = TreeIndex(*shape_);
  }
  if (index_.subtree_nodes(node) == 0) {
    const size_t n = index_.nodes();
    return accel::make_error("tree-select: node " + std::to_string(node) + " does not exist (the " +
                             built_->info->label + " has " + std::to_string(n) + " nodes" +
                             (n ? ", 0.." + std::to_string(n - 1) : std::string()) + ")");
  }
  selected_ = node;
  isolate_ = isolate;
  summary_ = summarize_subtree(*shape_, node, sah_constants(built_.get()));
  selected_view_ = structure_->node_view(node);
  layout_dirty_ = true;
  highlight_dirty_ = true;
  center_on_selected_ = true;
  return {};
}

void TreeDiagram::rebuild_highlight() {
  highlight_dirty_ = false;
  gl_.changed();
  segments_.clear();
  lines_.clear();
  if (!on_ || selected_ == kNoNode || replay_mode_ || !structure_ || !shape_) return;
  const bool planar = built_ && built_->scene && built_->scene->planar();  // 2D: spheres are circles
  if (isolate_) {
    // Breadth-first, so a huge subtree shows its top levels; coloured by depth below it.
    const int top = selected_view_.depth;
    const float span = static_cast<float>(std::max<int>(summary_ ? summary_->max_depth : 1, 1));
    std::vector<NodeId> level{selected_}, next;
    size_t drawn = 0;
    while (!level.empty() && drawn < kMaxIsolatedNodes) {
      next.clear();
      for (NodeId n : level) {
        if (drawn++ >= kMaxIsolatedNodes) break;
        const accel::NodeView v = structure_->node_view(n);
        const glm::vec3 c = colormap(static_cast<float>(v.depth - top) / span);
        const glm::vec4 color(c, v.leaf ? 0.85f : 0.6f);
        append_node_lines(lines_, v, color, planar);
        for (NodeId k : shape_->children(n)) next.push_back(k);
      }
      level.swap(next);
    }
  }
  append_node_segments(segments_, selected_view_, kSelected3D, 3.5f, planar);
}

void TreeDiagram::draw_selection(Renderer& renderer) {
  if (on_ && !(segments_.empty() && lines_.empty())) gl_.draw(renderer);
}

// =======================================================================================
// [SECTION] The window

void TreeDiagram::panel(const PanelPlace& place) {
  if (!on_) return;
  ui::place(place);
  ImGui::SetNextWindowBgAlpha(0.92f);
  bool open = true;
  const bool shown = ImGui::Begin("Tree", &open, ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse);
  if (shown && place.dock) {
    const ImVec2 pos = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
    note_docked_bottom(*place.dock, ImGui::GetIO().DisplaySize.y, {pos.x, pos.y}, {size.x, size.y});
  }
  if (shown) {
    if (!built_) {
      ImGui::TextDisabled("no structure built yet");
    } else if (grid_) {
      grid_table();
    } else if (layout_.items.empty()) {
      ImGui::TextDisabled(replay_mode_ ? "nothing built yet at this construction step" : "the structure has no nodes");
    } else {
      const size_t total = replay_mode_ ? layout_.items.size() + layout_.collapsed_nodes : index_.nodes();
      ImGui::Checkbox("follow", &follow_);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("keep the current node in view");
      ImGui::SameLine();
      if (ImGui::SmallButton("fit")) fit_pending_ = true;
      ImGui::SameLine();
      ImGui::TextWrapped("%s%s nodes: %zu drawn, %s in collapsed subtrees", replay_mode_ ? "construction: " : "",
                         ui::with_separators(total).c_str(), layout_.items.size(),
                         ui::with_separators(layout_.collapsed_nodes).c_str());
      legend();
      const ImVec2 avail = ImGui::GetContentRegionAvail();
      const float numbers_w = std::min(kNumbersEm * ImGui::GetFontSize(), 0.4f * avail.x);
      diagram_canvas(std::max(avail.x - numbers_w - ImGui::GetStyle().ItemSpacing.x, 1.0f), std::max(avail.y, 1.0f));
      ImGui::SameLine();
      ImGui::BeginChild("##tree_numbers", ImVec2(numbers_w, avail.y), false);
      selection_numbers();
      ImGui::EndChild();
    }
  }
  ImGui::End();
  if (!open) on_ = false;
}

void TreeDiagram::legend() {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float em = ImGui::GetFontSize();
  struct Entry {
    ImVec4 color;
    const char* label;
  };
  const Entry entries[] = {
      {ui::kCurrentText, "current"},
      {ui::kVisitedText, "visited"},
      {ui::kQueueText, "stack/queue"},
      {ui::kCullMissedText, "culled: missed"},
      {ui::kCullText, "culled: beyond hit"},
      {state_color({}), "not reached"},
  };
  // Entries wrap onto a new line where the window is narrow (lecture fonts).
  const float avail = ImGui::GetContentRegionAvail().x;
  float line_w = 0.0f;
  for (size_t i = 0; i < std::size(entries); ++i) {
    const float w = 1.0f * em + ImGui::CalcTextSize(entries[i].label).x + 0.8f * em;
    if (i && line_w + w <= avail) {
      ImGui::SameLine(0.0f, 0.8f * em);
      line_w += w;
    } else {
      line_w = w;
    }
    const ImVec2 p = ImGui::GetCursorScreenPos();
    dl->AddRectFilled(ImVec2(p.x, p.y + 0.2f * em), ImVec2(p.x + 0.7f * em, p.y + 0.9f * em),
                      color_u32(entries[i].color));
    ImGui::Dummy(ImVec2(0.8f * em, em));
    ImGui::SameLine(0.0f, 0.2f * em);
    ImGui::TextUnformatted(entries[i].label);
  }
  ImGui::SameLine(0.0f, 0.8f * em);
  ui::help_marker("circle: inner node, square: leaf (its triangle count below), triangle: a subtree no step "
                  "touches, collapsed (its node count below; click to open). Yellow ring: the current node, "
                  "magenta ring: the selection. Wheel: zoom, drag: pan, click: select.");
}

void TreeDiagram::selection_numbers() {
  if (selected_ == kNoNode || !summary_) {
    ImGui::PushStyleColor(ImGuiCol_Text, ui::kDimText);
    ImGui::TextWrapped("click a node: its numbers, a 3D highlight, isolate. Wheel: zoom, drag: pan; "
                       "click a triangle: open that subtree.");
    ImGui::PopStyleColor();
    return;
  }
  const accel::NodeView& v = selected_view_;
  const SubtreeSummary& s = *summary_;
  ImGui::TextColored(ui::kSelectedText, "%s %u", replay_mode_ ? "build node (slot)" : "node", selected_);
  ImGui::Text("depth %d, %s", v.depth, v.leaf ? "leaf" : "inner");
  if (v.leaf) ImGui::Text("triangles %u", v.prim_count);
  else ImGui::Text("triangles below %s", ui::with_separators(s.prim_refs).c_str());
  if (!v.sphere.empty()) {
    ImGui::Text("centre %s", ui::format_vec(v.sphere.center).c_str());
    ImGui::Text("radius %.4g", static_cast<double>(v.sphere.radius));
  } else if (!v.box.empty()) {
    ImGui::Text("min %s", ui::format_vec(v.box.min).c_str());
    ImGui::Text("max %s", ui::format_vec(v.box.max).c_str());
  }
  ImGui::Text("subtree %s nodes", ui::with_separators(s.nodes).c_str());
  ImGui::Text("  %s leaves", ui::with_separators(s.leaves).c_str());
  const SahConstants k = sah_constants(built_.get());
  ImGui::Text("SAH cost %.4g", s.sah_cost);
  ImGui::SameLine();
  char help[256];
  std::snprintf(help, sizeof help,
                "expected cost of a ray that hits this node: a leaf costs ci x triangles, an inner node "
                "ct + sum of area(child) / area(node) x cost(child); ct = %.3g, ci = %.3g (the structure's)",
                k.ct, k.ci);
  ui::help_marker(help);
  if (!replay_mode_) {
    if (ImGui::Checkbox("isolate", &isolate_)) highlight_dirty_ = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("draw only this subtree in 3D");
    ImGui::SameLine();
  }
  if (ImGui::SmallButton("clear")) {
    selected_ = kNoNode;
    summary_.reset();
    layout_dirty_ = true;
    highlight_dirty_ = true;
  }
}

// =======================================================================================
// [SECTION] The grid

void TreeDiagram::grid_table() {
  const int current = grid_current_row(grid_rows_, step_);
  int res[3];
  grid_resolution(built_->stats, res);
  const bool board = built_->scene && built_->scene->planar();  // the blackboard: 2D texts
  if (grid_rows_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("cell walk: no debug ray yet (%s)", shoot_hint(board));
    ImGui::PopStyleColor();
    return;
  }
  if (board)
    ImGui::TextWrapped("cell walk of the 2D DDA: %zu cells entered (grid %dx%d), one row per step into a cell; "
                       "current: row %d", grid_rows_.size(), res[0], res[1], current + 1);
  else
    ImGui::TextWrapped("cell walk of the 3D-DDA: %zu cells entered (grid %dx%dx%d), one row per step into a cell; "
                       "current: row %d", grid_rows_.size(), res[0], res[1], res[2], current + 1);
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersInnerV |
                                ImGuiTableFlags_SizingFixedFit;
  if (!ImGui::BeginTable("##cell_walk", 8, flags, ImGui::GetContentRegionAvail())) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  for (const char* h : {"row", "step", "X", "Y", "Z", "stepped", "t enter", "t exit"}) ImGui::TableSetupColumn(h);
  ImGui::TableHeadersRow();
  const float row_h = ImGui::GetTextLineHeightWithSpacing();
  if (current >= 0 && current != grid_scrolled_) {
    grid_scrolled_ = current;
    const float y = static_cast<float>(current) * row_h;
    const float view_h = ImGui::GetWindowHeight() - 2.0f * row_h;
    if (y < ImGui::GetScrollY() || y > ImGui::GetScrollY() + view_h)
      ImGui::SetScrollY(std::max(0.0f, y - 0.4f * view_h));
  }
  ImGuiListClipper clipper;
  clipper.Begin(static_cast<int>(grid_rows_.size()), row_h);
  while (clipper.Step()) {
    for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
      const GridWalkRow& row = grid_rows_[static_cast<size_t>(i)];
      ImGui::TableNextRow();
      const bool is_current = i == current;
      const bool passed = i < current || current < 0;
      if (is_current) ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg1, color_u32(ui::kCurrentText, 0.3f));
      const ImVec4 color = is_current ? ui::kCurrentText
                           : passed   ? ImGui::GetStyleColorVec4(ImGuiCol_Text)
                                      : ui::kDimText;
      auto cell = [&](const char* fmt, auto... v) {
        ImGui::TableNextColumn();
        ImGui::TextColored(color, fmt, v...);
      };
      cell("%s%d", is_current ? "> " : "", i + 1);
      cell("%zu", row.step + 1);
      for (int a = 0; a < 3; ++a) {
        if (row.xyz[a] >= 0) cell("%d", row.xyz[a]);
        else cell("%s", "?");
      }
      static const char* kAxis[] = {"x", "y", "z"};
      cell("%s", row.stepped_axis >= 0 ? kAxis[row.stepped_axis] : "(entry)");
      cell("%.4g", static_cast<double>(row.t0));
      cell("%.4g", static_cast<double>(row.t1));
    }
  }
  ImGui::EndTable();
}

// ---------------------------------------------------------------------------------------
// Keys and script verbs (the verbs registered in tools/tree_diagram_verbs.h)

std::vector<KeyBinding> TreeDiagram::keys(ToolHost& host) {
  return {{GLFW_KEY_T, "T", "the tree diagram", [this, &host](const KeyPress&) {
             toggle();
             host.relayout();  // the bottom dock appears or goes
             return true;
           }}};
}

void TreeDiagram::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<TreeDiagram> verbs(table, *this, host);
  tree_diagram_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void TreeDiagram::on_event(ToolEvent event, ToolHost&) {
  if (event == ToolEvent::PlaylistReset) set_on(false);
}

void TreeDiagram::update(ToolHost& host, float) {
  const BuildPlayer& build = host.build();
  follow(host.session().current_ptr(), host.ray().ray(), build.active() ? build.replay() : nullptr);
}

void TreeDiagram::panels(ToolHost& host) {
  if (!on_) return;
  WindowLayout& layout = host.layout();
  const PanelLayout& rects = layout.rects();
  WindowRect rect = rects.tree;  // docks along the bottom; the whole width when the left column is empty
  // In lecture mode the controls are collapsed: the tree takes the whole width and the
  // Variables panel the column above it (its larger font needs the room more).
  if ((!layout.panels().main && !host.tool<VarsPanel>().shown()) || layout.lecture()) {
    rect.size.x += rect.pos.x - rects.main.pos.x;
    rect.pos.x = rects.main.pos.x;
  }
  panel(layout.place(rect));
}

void TreeDiagram::draw(Renderer& renderer, ToolHost& host, DrawLayer layer) {
  if (layer == DrawLayer::Scene && !host.build().active()) draw_selection(renderer);
}

}  // namespace viz
