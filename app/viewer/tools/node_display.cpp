#include "tools/node_display.h"

#include <algorithm>

#include <imgui.h>

#include "panels.h"
#include "tools/build_player.h"
#include "tools/ray_debugger.h"
#include "tools/node_display_verbs.h"
#include "tools/structure_session.h"
#include "tools/tree_diagram.h"
#include "window_layout.h"

namespace viz {

void NodeDisplay::install(const BuiltStructure& built) {
  geometry_ = built.geometry;
  geometry_dirty_ = true;
  // Many thousands of boxes are one unreadable blob (and slow without a GPU): open such a
  // structure with its top levels; "all depths" is one click away.
  fit_depths(depth_, geometry_);
}

void NodeDisplay::set_empty_cells(bool on, const BuiltStructure* built) {
  depth_.empty_cells = on;
  if (!built) return;
  GeometryOptions options = built->request.geometry;
  options.empty_cells = on;
  geometry_ = structure_geometry(*built->structure, options);
  geometry_dirty_ = true;
}

void NodeDisplay::show_all() {
  depth_.filter = DepthFilter::All;
  depth_.auto_limited = false;
}

void NodeDisplay::show_leaves() {
  depth_.filter = DepthFilter::Leaves;
  depth_.auto_limited = false;
}

void NodeDisplay::show_depths(int lo, int hi) {
  depth_.auto_limited = false;
  if (lo == hi) {
    depth_.filter = DepthFilter::One;
    depth_.one = lo;
  } else {
    depth_.filter = DepthFilter::Range;
    depth_.lo = lo;
    depth_.hi = hi;
  }
}

void NodeDisplay::apply_lecture_colors(bool lecture) {
  if (lecture) {
    mesh_style_.color = glm::vec4(0.82f, 0.86f, 0.94f, 1.0f);
    node_alpha_ = std::max(node_alpha_, 0.8f);
  } else {
    mesh_style_.color = glm::vec4(0.70f, 0.77f, 0.88f, 1.0f);
  }
}

bool NodeDisplay::display_section(const BuiltStructure* built) {
  bool empty_toggled = false;
  const float em = ImGui::GetFontSize();
  static const char* kMesh[] = {"solid", "translucent", "wireframe", "hidden"};
  int mesh = static_cast<int>(mesh_style_.mode);
  ImGui::SetNextItemWidth(10.0f * em);
  if (ImGui::Combo("mesh", &mesh, kMesh, 4)) mesh_style_.mode = static_cast<MeshStyle::Mode>(mesh);
  ImGui::Checkbox("nodes", &show_nodes_);
  ImGui::SameLine();
  ImGui::Checkbox("x-ray", &xray_);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("nodes behind the mesh drawn faintly");
  if (!geometry_.planes.empty()) {
    ImGui::SameLine();
    ImGui::Checkbox("split planes", &show_planes_);
  }
  static const char* kFilter[] = {"all depths", "leaves only", "one depth", "depth range"};
  int filter = static_cast<int>(depth_.filter);
  ImGui::SetNextItemWidth(10.0f * em);
  if (ImGui::Combo("show", &filter, kFilter, 4)) {
    depth_.filter = static_cast<DepthFilter>(filter);
    depth_.auto_limited = false;
  }
  const int max_depth = std::max(geometry_.max_depth, 0);
  if (depth_.filter == DepthFilter::One) {
    ImGui::SetNextItemWidth(10.0f * em);
    ImGui::SliderInt("depth", &depth_.one, 0, max_depth, "%d", ImGuiSliderFlags_AlwaysClamp);
  } else if (depth_.filter == DepthFilter::Range) {
    ImGui::SetNextItemWidth(10.0f * em);
    if (ImGui::DragIntRange2("depths", &depth_.lo, &depth_.hi, 0.1f, 0, max_depth, "from %d", "to %d",
                             ImGuiSliderFlags_AlwaysClamp)) {
      depth_.hi = std::max(depth_.hi, depth_.lo);
      depth_.auto_limited = false;
    }
  }
  ImGui::TextDisabled("%s of %s nodes drawn", ui::with_separators(drawn_nodes_).c_str(),
                      ui::with_separators(geometry_.boxes.size() + geometry_.spheres.size()).c_str());
  if (filtered_nodes_ > drawn_nodes_) {
    ImGui::TextDisabled("(level-of-detail limit: the %s shallowest of the %s chosen)",
                        ui::with_separators(drawn_nodes_).c_str(), ui::with_separators(filtered_nodes_).c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("At most %s boxes are drawn: the coarse levels whole, then an even share of the next.\n"
                        "Choose fewer depths to see deeper ones.", ui::with_separators(kMaxDrawnNodes).c_str());
  }
  if (depth_.auto_limited && depth_.filter == DepthFilter::Range) {
    ImGui::TextDisabled("(a large structure: first shown to depth %d)", depth_.hi);
    ImGui::SameLine();
    if (ImGui::SmallButton("all depths")) show_all();
  }
  static const char* kColor[] = {"auto", "depth", "triangles"};
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::Combo("colour by", &coloring_, kColor, 3);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("auto: triangle count for a grid (all cells at depth 0), else depth");
  ImGui::SetNextItemWidth(10.0f * em);
  ImGui::SliderFloat("opacity", &node_alpha_, 0.05f, 1.0f, "%.2f");
  ImGui::Checkbox("hide empty leaves", &depth_.hide_empty_leaves);
  if (built && built->info->cells) {
    bool empty = depth_.empty_cells;
    if (ImGui::Checkbox("empty cells", &empty)) {
      set_empty_cells(empty, built);
      empty_toggled = true;
    }
    if (geometry_.empty_cells_too_many) ImGui::TextDisabled("(too many cells to draw the empty ones)");
  }
  // The colour scale of the nodes.
  const bool by_count = coloring_ == 2 || (coloring_ == 0 && geometry_.uniform_depth);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float bar_w = 12.0f * em, bar_h = 0.7f * em;
  for (int i = 0; i < 32; ++i) {
    const float t0 = static_cast<float>(i) / 32.0f, t1 = static_cast<float>(i + 1) / 32.0f;
    const glm::vec3 c = colormap(by_count ? 0.15f + 0.85f * t0 : 0.12f + 0.86f * t0);
    dl->AddRectFilled(ImVec2(p.x + t0 * bar_w, p.y), ImVec2(p.x + t1 * bar_w, p.y + bar_h),
                      ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.0f)));
  }
  ImGui::Dummy(ImVec2(bar_w, bar_h));
  if (by_count)
    ImGui::TextDisabled("triangles per cell: 1 .. %u (log)", geometry_.max_prims);
  else
    ImGui::TextDisabled("depth: 0 (root) .. %d", geometry_.max_depth);
  return empty_toggled;
}

void NodeDisplay::sync_instances() {
  if (boxes_gl_ && (geometry_dirty_ || !(node_filter(depth_) == uploaded_filter_))) upload();
}

void NodeDisplay::upload() {
  // Only the nodes the filter shows go to the GPU: re-done when the filter changes, never
  // per frame. (The vertex shader filters too, but then every instance still costs.)
  const NodeFilter f = node_filter(depth_);
  auto boxes = filter_nodes(geometry_.boxes, f);
  auto spheres = filter_nodes(geometry_.spheres, f);
  filtered_nodes_ = boxes.size() + spheres.size();
  boxes = limit_drawn_nodes(std::move(boxes), kMaxDrawnNodes);
  spheres = limit_drawn_nodes(std::move(spheres), kMaxDrawnNodes - boxes.size());
  NodeFilter planes_filter = f;
  planes_filter.leaves_only = false;  // split planes belong to inner nodes
  planes_filter.hide_empty = false;
  boxes_gl_->upload(boxes);
  // A 2D scene's sphere-tree nodes are circles in the plane: the one-circle unit shape.
  const NodeStyle::Shape round = geometry_.planar ? NodeStyle::Shape::Circle : NodeStyle::Shape::Sphere;
  if (spheres_gl_->shape() != round) spheres_gl_.emplace(round);
  spheres_gl_->upload(spheres);
  planes_gl_->upload(f.leaves_only ? std::vector<NodeInstance>{} : filter_nodes(geometry_.planes, planes_filter));
  drawn_nodes_ = boxes.size() + spheres.size();
  uploaded_filter_ = f;
  geometry_dirty_ = false;
}

void NodeDisplay::draw_nodes(Renderer& renderer, const BuiltStructure* current, bool dimmed) {
  if (!boxes_gl_ || !current || !show_nodes_) return;
  NodeStyle style;
  const bool by_count = coloring_ == 2 || (coloring_ == 0 && geometry_.uniform_depth);
  style.coloring = by_count ? NodeStyle::Coloring::Prims : NodeStyle::Coloring::Depth;
  style.max_depth = static_cast<float>(std::max(geometry_.max_depth, 1));
  style.max_prims = static_cast<float>(std::max<uint32_t>(geometry_.max_prims, 1));
  style.alpha = node_alpha_;
  // While a trace is shown the structure steps back so the highlights stand out.
  if (dimmed) style.alpha *= 0.6f;
  // The instances on the GPU are already filtered (upload_geometry); the shader's filter
  // stays open.
  // X-ray draws every node twice; beyond ~100k nodes that second pass is not worth it.
  constexpr size_t kMaxXrayNodes = 100000;
  const bool occluding = mesh_style_.mode == MeshStyle::Mode::Solid || mesh_style_.mode == MeshStyle::Mode::Translucent;
  style.hidden_alpha = xray_ && occluding && drawn_nodes_ <= kMaxXrayNodes ? 0.3f : 0.0f;
  renderer.draw_nodes(*boxes_gl_, style);
  renderer.draw_nodes(*spheres_gl_, style);
  if (show_planes_) {
    // Split planes: translucent, a fifth of the lines' opacity, so stacked planes stay readable.
    NodeStyle planes = style;
    planes.alpha = 0.2f * node_alpha_;
    planes.hidden_alpha = 0.0f;
    planes.depth_bias = 0.0f;
    renderer.draw_nodes(*planes_gl_, planes);
  }
}

void NodeDisplay::init_gl() {
  boxes_gl_.emplace(NodeStyle::Shape::Box);
  spheres_gl_.emplace(NodeStyle::Shape::Sphere);
  planes_gl_.emplace(NodeStyle::Shape::Plane);
  geometry_dirty_ = true;
}

void NodeDisplay::release_gl() {
  planes_gl_.reset();
  spheres_gl_.reset();
  boxes_gl_.reset();
}

// ---------------------------------------------------------------------------------------
// Script verbs (tools/node_display_verbs.h)

void NodeDisplay::add_verbs(VerbTable& table, ToolHost& host) {
  ToolVerbs<NodeDisplay> verbs(table, *this, host);
  node_display_verbs(verbs);
}

// ---------------------------------------------------------------------------------------
// The tool's frame

void NodeDisplay::on_event(ToolEvent event, ToolHost& host) {
  if (event == ToolEvent::StructureInstalled) {
    static const BuiltStructure kNothing;  // a failed build's replay: no structure to draw
    const BuiltStructure* shown = host.session().shown();
    install(shown ? *shown : kNothing);
  }
  if (event == ToolEvent::PlaylistReset) {
    show_all();
    set_visible(true);
    set_opacity(0.55f);
    set_mesh_mode(MeshStyle::Mode::Solid);
  }
}

void NodeDisplay::update(ToolHost& host, float) {
  const bool lecture = host.layout().lecture();
  if (lecture == lecture_applied_) return;
  lecture_applied_ = lecture;
  apply_lecture_colors(lecture);
}

void NodeDisplay::section(ToolHost& host, PanelSection section) {
  if (section != PanelSection::Display) return;
  StructureSession& session = host.session();
  if (display_section(session.shown())) session.set_empty_cells(empty_cells());
}

void NodeDisplay::draw(Renderer& renderer, ToolHost& host, DrawLayer layer) {
  if (layer == DrawLayer::Under) renderer.draw_mesh(mesh_style_);
  // The construction draws its partly built structure instead; while the tree isolates a
  // subtree it draws that subtree instead of all the nodes.
  if (layer != DrawLayer::Scene || host.build().active() || host.tool<TreeDiagram>().isolating()) return;
  const DebugRay& ray = host.ray().ray();
  draw_nodes(renderer, host.session().current(), ray.active && !ray.player.empty());
}

}  // namespace viz
