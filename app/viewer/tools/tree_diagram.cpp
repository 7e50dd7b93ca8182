// The "Tree" window (tree_diagram.h): index [SECTION]s
//   Following     update(): what changed since the last frame, and what that rebuilds
//   Selection     select(), the 3D highlight of the selection
//   The window    panel(), the legend, the node numbers
//   The diagram   the canvas: zoom, pan, follow, edges, nodes, hover, click
//   The grid      the cell walk table
#include "tools/tree_diagram.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include <GLFW/glfw3.h>
#include <imgui.h>

#include "input.h"
#include "panels.h"
#include "registry.h"
#include "tools/build_player.h"
#include "tools/ray_debugger.h"
#include "tools/structure_session.h"
#include "tools/tree_diagram_verbs.h"
#include "tools/ui_colors.h"
#include "tools/vars_panel.h"
#include "window_layout.h"

namespace viz {
namespace {

// Top levels opened breadth-first besides the ray's path: enough to see the tree's shape,
// few enough that the path stays the diagram's subject. Without a ray more are opened.
constexpr size_t kBudgetWithTrace = 15;
constexpr size_t kBudgetWithoutTrace = 63;
// An isolated subtree draws at most this many nodes in 3D (breadth-first: the top levels),
// about what the node display shows of a big tree at first: more only slows the frame.
constexpr size_t kMaxIsolatedNodes = 4095;
// Spacing of the diagram in font sizes at zoom 1 (so lecture mode scales with its font).
constexpr float kSlotEm = 1.7f;
constexpr float kRowEm = 2.4f;
constexpr float kNodeEm = 0.45f;  // half size of a node's glyph
constexpr float kMinZoom = 0.05f, kMaxZoom = 6.0f;
constexpr float kMinRowScale = 0.45f;  // rows at most this much closer than the zoom's spacing
// Column width of the node numbers beside the diagram.
constexpr float kNumbersEm = 15.0f;

const glm::vec4 kSelected3D(1.0f, 0.3f, 0.9f, 1.0f);  // as the diagram's selection ring

ImU32 color_u32(const ImVec4& c, float alpha_scale = 1.0f) {
  return ImGui::GetColorU32(ImVec4(c.x, c.y, c.z, c.w * alpha_scale));
}

ImVec4 state_color(const TreeNodeStatus& s) {
  switch (s.state) {
    case TreeNodeState::Current: return ui::kCurrentText;
    case TreeNodeState::Visited: return ui::kVisitedText;
    case TreeNodeState::OnStack: return ui::kQueueText;
    case TreeNodeState::Culled:
      return s.reason == accel::CullReason::MissedBounds ? ui::kCullMissedText : ui::kCullText;
    case TreeNodeState::NotReached: break;
  }
  return ImVec4(0.42f, 0.45f, 0.52f, 1.0f);
}

const char* state_name(TreeNodeState s) {
  switch (s) {
    case TreeNodeState::Current: return "current";
    case TreeNodeState::Visited: return "visited";
    case TreeNodeState::OnStack: return "on the stack / queue";
    case TreeNodeState::Culled: return "culled";
    case TreeNodeState::NotReached: break;
  }
  return "not reached";
}

/// 1234567 -> "1.2M": the collapsed glyphs' labels must stay short.
std::string short_count(size_t n) {
  char buf[32];
  if (n < 10000) std::snprintf(buf, sizeof buf, "%zu", n);
  else if (n < 1000000) std::snprintf(buf, sizeof buf, "%.0fk", static_cast<double>(n) / 1e3);
  else std::snprintf(buf, sizeof buf, "%.1fM", static_cast<double>(n) / 1e6);
  return buf;
}

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
// [SECTION] The diagram

void TreeDiagram::diagram_canvas(float width, float height) {
  const float em = ImGui::GetFontSize();
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 p1(p0.x + width, p0.y + height);
  ImGui::InvisibleButton("##tree_canvas", ImVec2(width, height));
  const bool hovered = ImGui::IsItemHovered();
  const bool active = ImGui::IsItemActive();
  const bool released = ImGui::IsItemDeactivated();
  ImGuiIO& io = ImGui::GetIO();
  const float margin = 1.2f * em;

  // Fit: the whole layout when it is small; else a readable zoom around the current node.
  // Again when the canvas changes size (the layout is applied, lecture fonts) while following.
  if (follow_ && (width != canvas_size_.x || height != canvas_size_.y)) fit_pending_ = true;
  canvas_size_ = {width, height};
  if (fit_pending_) {
    fit_pending_ = false;
    const float cols = std::max(layout_.columns - 1.0f, 1.0f), rows = std::max(layout_.rows - 1.0f, 1.0f);
    const float fit_x = (width - 2.0f * margin) / (cols * kSlotEm * em);
    const float fit_y = (height - 2.5f * margin) / (rows * kRowEm * em);  // room for the leaves' counts
    // Width and depth are fitted apart (rows squeezed down to kMinRowScale first): a deep,
    // narrow path would otherwise shrink to dots.
    zoom_ = std::clamp(std::min({fit_x, 1.0f, fit_y / kMinRowScale}), 0.35f, kMaxZoom);
    row_scale_ = std::clamp(fit_y / zoom_, kMinRowScale, 1.0f);
    const float content_w = cols * kSlotEm * em * zoom_;
    pan_ = {std::max((width - 2.0f * margin - content_w) * 0.5f, 0.0f), 0.0f};
    followed_item_ = -1;  // re-centre on the current node if it is out of view
  }
  const float sx = kSlotEm * em * zoom_, sy = kRowEm * em * zoom_ * row_scale_;
  const float r = std::max(std::min(kNodeEm * em * std::min(zoom_, 1.5f), 0.3f * sy), 2.0f);
  auto screen = [&](const TreeItem& it) {
    return ImVec2(p0.x + pan_.x + margin + it.x * sx, p0.y + pan_.y + margin + static_cast<float>(it.depth) * sy);
  };
  // An item out of view is brought to the middle, per axis; one in view stays where it is,
  // and the view never leaves room above the root (the path reads from the top).
  auto bring_into_view = [&](int item) {
    const ImVec2 c = screen(layout_.items[static_cast<size_t>(item)]);
    if (c.x < p0.x + margin || c.x > p1.x - margin) pan_.x += (p0.x + 0.5f * width) - c.x;
    if (c.y < p0.y + 0.5f * margin || c.y > p1.y - 0.5f * margin)
      pan_.y = std::min(pan_.y + (p0.y + 0.6f * height) - c.y, 0.0f);
  };
  if (center_on_selected_) {
    center_on_selected_ = false;
    if (const int i = layout_.find(selected_); i >= 0) bring_into_view(i);
  }
  if (follow_ && current_item_ >= 0 && current_item_ != followed_item_) {
    followed_item_ = current_item_;
    bring_into_view(current_item_);
  }

  // Zoom about the mouse; drag pans (and stops following).
  if (hovered && io.MouseWheel != 0.0f) {
    const float old = zoom_;
    zoom_ = std::clamp(zoom_ * std::pow(1.2f, io.MouseWheel), kMinZoom, kMaxZoom);
    const float f = zoom_ / old;
    const ImVec2 m = io.MousePos;
    pan_.x = (m.x - p0.x - margin) - (m.x - p0.x - margin - pan_.x) * f;
    pan_.y = (m.y - p0.y - margin) - (m.y - p0.y - margin - pan_.y) * f;
  }
  if (active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 2.0f)) {
    pan_.x += io.MouseDelta.x;
    pan_.y += io.MouseDelta.y;
    follow_ = false;
  }

  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(p0, p1, true);
  dl->AddRectFilled(p0, p1, ImGui::GetColorU32(ImVec4(0.0f, 0.0f, 0.0f, 0.35f)));
  auto visible_x = [&](float x) { return x >= p0.x - sx && x <= p1.x + sx; };
  auto visible = [&](const ImVec2& c) { return visible_x(c.x) && c.y >= p0.y - sy && c.y <= p1.y + sy; };

  // Edges first, brighter where the ray went.
  const float edge_w = std::max(1.0f, 0.08f * em * std::min(zoom_, 1.5f));
  for (size_t i = 0; i < layout_.items.size(); ++i) {
    const TreeItem& it = layout_.items[i];
    if (it.parent < 0) continue;
    const ImVec2 a = screen(layout_.items[static_cast<size_t>(it.parent)]), b = screen(it);
    if ((a.x < p0.x - sx && b.x < p0.x - sx) || (a.x > p1.x + sx && b.x > p1.x + sx) || b.y < p0.y - sy ||
        a.y > p1.y + sy)
      continue;
    const bool reached = status_[i].state != TreeNodeState::NotReached;
    dl->AddLine(ImVec2(a.x, a.y + r), ImVec2(b.x, b.y - r),
                color_u32(reached ? ui::kVisitedText : state_color({}), reached ? 0.8f : 0.45f), edge_w);
  }

  // Nodes, the hovered one found on the way.
  hovered_ = -1;
  // Counts in a smaller font, shown once the slots are wide enough for a digit or two.
  const float label_size = 0.8f * em;
  const bool labels = sx >= 0.8f * em;
  ImFont* font = ImGui::GetFont();
  const ImU32 outline = ImGui::GetColorU32(ImVec4(0.0f, 0.0f, 0.0f, 0.9f));
  for (size_t i = 0; i < layout_.items.size(); ++i) {
    const TreeItem& it = layout_.items[i];
    const ImVec2 c = screen(it);
    if (!visible(c)) continue;
    const TreeNodeStatus& st = status_[i];
    const ImU32 fill = color_u32(state_color(st));
    if (it.kind == TreeItem::Kind::Collapsed) {
      // A triangle standing for a whole subtree, labelled with its node count.
      dl->AddTriangleFilled(ImVec2(c.x, c.y - r), ImVec2(c.x - 1.2f * r, c.y + 1.3f * r),
                            ImVec2(c.x + 1.2f * r, c.y + 1.3f * r), color_u32(state_color({}), 0.8f));
      if (labels) {
        const std::string text = short_count(it.subtree_nodes);
        const ImVec2 ts = font->CalcTextSizeA(label_size, FLT_MAX, 0.0f, text.c_str());
        dl->AddText(font, label_size, ImVec2(c.x - 0.5f * ts.x, c.y + 1.4f * r), color_u32(ui::kDimText), text.c_str());
      }
    } else if (it.leaf) {
      dl->AddRectFilled(ImVec2(c.x - r, c.y - r), ImVec2(c.x + r, c.y + r), fill);
      dl->AddRect(ImVec2(c.x - r, c.y - r), ImVec2(c.x + r, c.y + r), outline);
      if (labels) {
        const std::string text = std::to_string(it.prims);
        const ImVec2 ts = font->CalcTextSizeA(label_size, FLT_MAX, 0.0f, text.c_str());
        dl->AddText(font, label_size, ImVec2(c.x - 0.5f * ts.x, c.y + 1.1f * r), ImGui::GetColorU32(ImGuiCol_Text),
                    text.c_str());
      }
    } else {
      dl->AddCircleFilled(c, r, fill, 20);
      dl->AddCircle(c, r, outline, 20);
      if (it.children.empty() && labels) {  // a touched node whose subtree stays closed
        char text[40];  // (not "+" + std::string: GCC 12 warns falsely on that, -Wrestrict)
        std::snprintf(text, sizeof text, "+%s", short_count(it.subtree_nodes - 1).c_str());
        const ImVec2 ts = font->CalcTextSizeA(label_size, FLT_MAX, 0.0f, text);
        dl->AddText(font, label_size, ImVec2(c.x - 0.5f * ts.x, c.y + 1.1f * r), color_u32(ui::kDimText), text);
      }
    }
    if (st.state == TreeNodeState::Current)
      dl->AddCircle(c, 1.9f * r, color_u32(ui::kCurrentText), 24, std::max(2.0f, 0.12f * em));
    if (it.node == selected_ && it.kind == TreeItem::Kind::Node)
      dl->AddCircle(c, 2.3f * r, color_u32(ui::kSelectedText), 24, std::max(2.0f, 0.15f * em));
    if (hovered) {
      const float dx = io.MousePos.x - c.x, dy = io.MousePos.y - c.y;
      const float pick = std::max(1.4f * r, 0.5f * em);
      if (dx * dx + dy * dy <= pick * pick) hovered_ = static_cast<int>(i);
    }
  }
  dl->PopClipRect();

  if (hovered_ >= 0) {
    const TreeItem& it = layout_.items[static_cast<size_t>(hovered_)];
    const TreeNodeStatus& st = status_[static_cast<size_t>(hovered_)];
    ImGui::BeginTooltip();
    if (it.kind == TreeItem::Kind::Collapsed) {
      ImGui::Text("subtree of node %u: %s nodes", it.node, ui::with_separators(it.subtree_nodes).c_str());
      ImGui::TextDisabled("no step of the ray touches it; click to open");
    } else {
      ImGui::Text("node %u (depth %d), %s", it.node, it.depth, it.leaf ? "leaf" : "inner");
      if (it.leaf) ImGui::Text("%u triangles", it.prims);
      else ImGui::Text("subtree: %s nodes", ui::with_separators(it.subtree_nodes).c_str());
      ImGui::TextColored(state_color(st), "%s", state_name(st.state));
      if (st.state == TreeNodeState::Culled)
        ImGui::TextColored(state_color(st), "reason: %s (step %zu)", accel::cull_reason_name(st.reason), st.step + 1);
      else if (st.state != TreeNodeState::NotReached && !replay_mode_)
        ImGui::TextDisabled("since step %zu", st.step + 1);
    }
    ImGui::EndTooltip();
  }
  // A click (not a drag) selects the node under the mouse; a collapsed glyph opens.
  if (released && io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < 9.0f && hovered_ >= 0) {
    const NodeId node = layout_.items[static_cast<size_t>(hovered_)].node;
    if (replay_mode_) {
      selected_ = node;
      layout_dirty_ = true;
    } else {
      (void)select(node, isolate_);  // a node of the layout always exists
    }
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
