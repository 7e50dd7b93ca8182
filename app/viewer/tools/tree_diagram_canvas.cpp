// The "Tree" window's canvas (tree_diagram.h): the node-link diagram, drawn with ImDrawList.
// The steps of diagram_canvas(), in order:
//   fit_canvas()      the zoom and pan that show the layout (when it changed)
//   keep_in_view()    the selection and the current node brought into view
//   zoom_and_pan()    the wheel zooms about the mouse, a drag pans
//   draw_edges()      edges, brighter where the ray went
//   draw_nodes()      glyphs, their counts, the current and selected rings; the hovered node
//   node_tooltip()    the hovered node's numbers
//   click_node()      a click selects, or opens a collapsed subtree
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <string>

#include <imgui.h>

#include "panels.h"
#include "tools/tree_diagram.h"
#include "tools/tree_diagram_colors.h"
#include "tools/ui_colors.h"

namespace viz {
namespace {

using tree_colors::color_u32;
using tree_colors::state_color;

// Spacing of the diagram in font sizes at zoom 1 (so lecture mode scales with its font).
constexpr float kSlotEm = 1.7f;
constexpr float kRowEm = 2.4f;
constexpr float kNodeEm = 0.45f;  // half size of a node's glyph
constexpr float kMinZoom = 0.05f, kMaxZoom = 6.0f;
constexpr float kMinRowScale = 0.45f;  // rows at most this much closer than the zoom's spacing

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

/// Counts under the glyphs in a smaller font, shown once the slots are wide enough for a
/// digit or two.
struct GlyphLabels {
  bool shown;
  float size;
  ImFont* font = ImGui::GetFont();
};

/// The glyph of item `it` centred at `c`, half size `r`: a triangle for a collapsed subtree
/// (its node count below), a square for a leaf (its triangle count), a circle for an inner
/// node (the nodes below it when its subtree stays closed).
void node_glyph(ImDrawList* dl, const TreeItem& it, const TreeNodeStatus& st, ImVec2 c, float r,
                const GlyphLabels& labels) {
  const ImU32 fill = color_u32(state_color(st));
  const ImU32 outline = ImGui::GetColorU32(ImVec4(0.0f, 0.0f, 0.0f, 0.9f));
  ImFont* font = labels.font;
  if (it.kind == TreeItem::Kind::Collapsed) {
    dl->AddTriangleFilled(ImVec2(c.x, c.y - r), ImVec2(c.x - 1.2f * r, c.y + 1.3f * r),
                          ImVec2(c.x + 1.2f * r, c.y + 1.3f * r), color_u32(state_color({}), 0.8f));
    if (labels.shown) {
      const std::string text = short_count(it.subtree_nodes);
      const ImVec2 ts = font->CalcTextSizeA(labels.size, FLT_MAX, 0.0f, text.c_str());
      dl->AddText(font, labels.size, ImVec2(c.x - 0.5f * ts.x, c.y + 1.4f * r), color_u32(ui::kDimText), text.c_str());
    }
  } else if (it.leaf) {
    dl->AddRectFilled(ImVec2(c.x - r, c.y - r), ImVec2(c.x + r, c.y + r), fill);
    dl->AddRect(ImVec2(c.x - r, c.y - r), ImVec2(c.x + r, c.y + r), outline);
    if (labels.shown) {
      const std::string text = std::to_string(it.prims);
      const ImVec2 ts = font->CalcTextSizeA(labels.size, FLT_MAX, 0.0f, text.c_str());
      dl->AddText(font, labels.size, ImVec2(c.x - 0.5f * ts.x, c.y + 1.1f * r), ImGui::GetColorU32(ImGuiCol_Text),
                  text.c_str());
    }
  } else {
    dl->AddCircleFilled(c, r, fill, 20);
    dl->AddCircle(c, r, outline, 20);
    if (it.children.empty() && labels.shown) {  // a touched node whose subtree stays closed
      char text[40];  // (not "+" + std::string: GCC 12 warns falsely on that, -Wrestrict)
      std::snprintf(text, sizeof text, "+%s", short_count(it.subtree_nodes - 1).c_str());
      const ImVec2 ts = font->CalcTextSizeA(labels.size, FLT_MAX, 0.0f, text);
      dl->AddText(font, labels.size, ImVec2(c.x - 0.5f * ts.x, c.y + 1.1f * r), color_u32(ui::kDimText), text);
    }
  }
}

}  // namespace

/// The canvas this frame: its rectangle [p0, p1], the margin inside it, and the scale the
/// frame draws at (sx, sy: a slot's width and a row's height; r: a node's half size).
struct TreeDiagram::Canvas {
  float em;
  ImVec2 p0, p1;
  float width, height;
  float margin;
  float sx, sy, r;
  ImDrawList* dl;

  /// Where item `it` is, panned by `pan` (the pan of the moment: bringing a node into view
  /// and the wheel move it after the frame's scale is set).
  ImVec2 at(glm::vec2 pan, const TreeItem& it) const {
    return ImVec2(p0.x + pan.x + margin + it.x * sx, p0.y + pan.y + margin + static_cast<float>(it.depth) * sy);
  }
  bool visible_x(float x) const { return x >= p0.x - sx && x <= p1.x + sx; }
  bool visible(const ImVec2& c) const { return visible_x(c.x) && c.y >= p0.y - sy && c.y <= p1.y + sy; }
};

void TreeDiagram::diagram_canvas(float width, float height) {
  const float em = ImGui::GetFontSize();
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##tree_canvas", ImVec2(width, height));
  const bool hovered = ImGui::IsItemHovered();
  const bool active = ImGui::IsItemActive();
  const bool released = ImGui::IsItemDeactivated();
  const float margin = 1.2f * em;
  fit_canvas(width, height, margin, em);
  const float sx = kSlotEm * em * zoom_, sy = kRowEm * em * zoom_ * row_scale_;
  const float r = std::max(std::min(kNodeEm * em * std::min(zoom_, 1.5f), 0.3f * sy), 2.0f);
  const ImVec2 p1(p0.x + width, p0.y + height);
  const Canvas canvas{em, p0, p1, width, height, margin, sx, sy, r, ImGui::GetWindowDrawList()};
  keep_in_view(canvas);
  zoom_and_pan(canvas, hovered, active);

  canvas.dl->PushClipRect(canvas.p0, canvas.p1, true);
  canvas.dl->AddRectFilled(canvas.p0, canvas.p1, ImGui::GetColorU32(ImVec4(0.0f, 0.0f, 0.0f, 0.35f)));
  draw_edges(canvas);
  draw_nodes(canvas, hovered);
  canvas.dl->PopClipRect();
  node_tooltip();
  // A click (not a drag) selects the node under the mouse; a collapsed glyph opens.
  if (released && ImGui::GetIO().MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < 9.0f && hovered_ >= 0) click_node();
}

void TreeDiagram::fit_canvas(float width, float height, float margin, float em) {
  // Fit: the whole layout when it is small; else a readable zoom around the current node.
  // Again when the canvas changes size (the layout is applied, lecture fonts) while following.
  if (follow_ && (width != canvas_size_.x || height != canvas_size_.y)) fit_pending_ = true;
  canvas_size_ = {width, height};
  if (!fit_pending_) return;
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

void TreeDiagram::bring_into_view(const Canvas& canvas, int item) {
  // Per axis; the view never leaves room above the root (the path reads from the top).
  const ImVec2 c = canvas.at(pan_, layout_.items[static_cast<size_t>(item)]);
  const ImVec2 p0 = canvas.p0, p1 = canvas.p1;
  if (c.x < p0.x + canvas.margin || c.x > p1.x - canvas.margin) pan_.x += (p0.x + 0.5f * canvas.width) - c.x;
  if (c.y < p0.y + 0.5f * canvas.margin || c.y > p1.y - 0.5f * canvas.margin)
    pan_.y = std::min(pan_.y + (p0.y + 0.6f * canvas.height) - c.y, 0.0f);
}

void TreeDiagram::keep_in_view(const Canvas& canvas) {
  if (center_on_selected_) {
    center_on_selected_ = false;
    if (const int i = layout_.find(selected_); i >= 0) bring_into_view(canvas, i);
  }
  if (follow_ && current_item_ >= 0 && current_item_ != followed_item_) {
    followed_item_ = current_item_;
    bring_into_view(canvas, current_item_);
  }
}

void TreeDiagram::zoom_and_pan(const Canvas& canvas, bool hovered, bool active) {
  const ImGuiIO& io = ImGui::GetIO();
  if (hovered && io.MouseWheel != 0.0f) {
    const float old = zoom_;
    zoom_ = std::clamp(zoom_ * std::pow(1.2f, io.MouseWheel), kMinZoom, kMaxZoom);
    const float f = zoom_ / old;
    const ImVec2 m = io.MousePos;
    pan_.x = (m.x - canvas.p0.x - canvas.margin) - (m.x - canvas.p0.x - canvas.margin - pan_.x) * f;
    pan_.y = (m.y - canvas.p0.y - canvas.margin) - (m.y - canvas.p0.y - canvas.margin - pan_.y) * f;
  }
  if (active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 2.0f)) {
    pan_.x += io.MouseDelta.x;
    pan_.y += io.MouseDelta.y;
    follow_ = false;
  }
}

void TreeDiagram::draw_edges(const Canvas& canvas) const {
  const ImVec2 p0 = canvas.p0, p1 = canvas.p1;
  const float sx = canvas.sx, sy = canvas.sy;
  // At this frame's zoom (the wheel's included), while the nodes keep the frame's scale.
  const float edge_w = std::max(1.0f, 0.08f * canvas.em * std::min(zoom_, 1.5f));
  for (size_t i = 0; i < layout_.items.size(); ++i) {
    const TreeItem& it = layout_.items[i];
    if (it.parent < 0) continue;
    const ImVec2 a = canvas.at(pan_, layout_.items[static_cast<size_t>(it.parent)]), b = canvas.at(pan_, it);
    if ((a.x < p0.x - sx && b.x < p0.x - sx) || (a.x > p1.x + sx && b.x > p1.x + sx) || b.y < p0.y - sy ||
        a.y > p1.y + sy)
      continue;
    const bool reached = status_[i].state != TreeNodeState::NotReached;
    canvas.dl->AddLine(ImVec2(a.x, a.y + canvas.r), ImVec2(b.x, b.y - canvas.r),
                       color_u32(reached ? ui::kVisitedText : state_color({}), reached ? 0.8f : 0.45f), edge_w);
  }
}

void TreeDiagram::draw_nodes(const Canvas& canvas, bool hovered) {
  const float em = canvas.em, r = canvas.r;
  const ImGuiIO& io = ImGui::GetIO();
  hovered_ = -1;  // found on the way
  const GlyphLabels labels{canvas.sx >= 0.8f * em, 0.8f * em};
  for (size_t i = 0; i < layout_.items.size(); ++i) {
    const TreeItem& it = layout_.items[i];
    const ImVec2 c = canvas.at(pan_, it);
    if (!canvas.visible(c)) continue;
    const TreeNodeStatus& st = status_[i];
    node_glyph(canvas.dl, it, st, c, r, labels);
    if (st.state == TreeNodeState::Current)
      canvas.dl->AddCircle(c, 1.9f * r, color_u32(ui::kCurrentText), 24, std::max(2.0f, 0.12f * em));
    if (it.node == selected_ && it.kind == TreeItem::Kind::Node)
      canvas.dl->AddCircle(c, 2.3f * r, color_u32(ui::kSelectedText), 24, std::max(2.0f, 0.15f * em));
    if (hovered) {
      const float dx = io.MousePos.x - c.x, dy = io.MousePos.y - c.y;
      const float pick = std::max(1.4f * r, 0.5f * em);
      if (dx * dx + dy * dy <= pick * pick) hovered_ = static_cast<int>(i);
    }
  }
}

void TreeDiagram::node_tooltip() const {
  if (hovered_ < 0) return;
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

void TreeDiagram::click_node() {
  const NodeId node = layout_.items[static_cast<size_t>(hovered_)].node;
  if (replay_mode_) {
    selected_ = node;
    layout_dirty_ = true;
  } else {
    (void)select(node, isolate_);  // a node of the layout always exists
  }
}

}  // namespace viz
