#pragma once
// What the viewer draws of a structure and of a trace step, as plain vertex and instance
// lists (no GL): the renderer uploads them as they are. Built from the Structure interface
// only (for_each_node / node_view / NodeView), never from a concrete structure, so a new
// structure shows up without viewer changes. GL-free, hence unit-tested without a window.
//
//   structure_geometry()   all nodes -> instances: one instanced draw per shape
//   append_box_segments()  12 thick edges of a box (highlights)
//   sphere_outline() ...   a sphere-tree node's outline: three great circles in 3D, in 2D
//                          (the blackboard) the one circle where it cuts the plane z = 0
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "color_scheme.h"

#include "structure.h"

namespace viz {

/// One end of a thin line, or one corner of a filled triangle.
struct ColorVertex {
  glm::vec3 position{0.0f};
  glm::vec4 color{1.0f};
};
static_assert(sizeof(ColorVertex) == 28, "ColorVertex is uploaded as 7 tightly packed floats");

/// A thick line segment, drawn as a screen-space quad `width` pixels wide.
struct Segment {
  glm::vec3 a{0.0f};
  glm::vec3 b{0.0f};
  glm::vec4 color{1.0f};
  float width = 2.0f;
};
static_assert(sizeof(Segment) == 44, "Segment is uploaded as 11 tightly packed floats");

/// One node drawn by instancing a unit shape. Box: the unit cube's edges scaled to
/// [lo, hi]. Sphere: three unit great circles scaled by hi.x around lo; in 2D one unit
/// circle in the plane z = 0, scaled by hi.x around lo (z = 0). Split plane: the
/// unit square spanning [lo, hi] across the two axes other than `axis` (lo[axis] = hi[axis]).
struct NodeInstance {
  glm::vec3 lo{0.0f};
  glm::vec3 hi{0.0f};
  float depth = 0.0f;
  float leaf = 0.0f;    ///< 1 for a leaf / grid cell
  float prims = 0.0f;   ///< NodeView::prim_count
  float axis = 0.0f;    ///< split planes only
};
static_assert(sizeof(NodeInstance) == 40, "NodeInstance is uploaded as 10 tightly packed floats");

/// Which nodes structure_geometry() lists.
struct GeometryOptions {
  /// Grid cells without triangles too (for_each_node skips them): every id below
  /// BuildStats::nodes through node_view(), but only up to max_empty_cells ids.
  bool empty_cells = false;
  size_t max_empty_cells = size_t(1) << 21;
  /// A 2D scene (Scene::planar(), the blackboard): a sphere-tree node is listed as its circle
  /// in the plane z = 0 (sphere_in_plane()), drawn with the one-circle unit shape.
  bool planar = false;
};

/// Every node of a structure as instances, plus what the colour scales need.
struct StructureGeometry {
  std::vector<NodeInstance> boxes;    ///< nodes / cells with a box (all but sphere-tree nodes)
  std::vector<NodeInstance> spheres;  ///< sphere-tree nodes: lo = centre, hi.x = radius (2D: the circle in z = 0)
  std::vector<NodeInstance> planes;   ///< kd-tree inner nodes: the split plane inside the node box
  int max_depth = 0;
  uint32_t max_prims = 0;             ///< largest prim_count of a leaf / cell
  size_t nodes = 0;                   ///< nodes listed
  bool uniform_depth = true;          ///< every node at depth 0 (a grid): colour by count instead
  bool empty_cells_listed = false;    ///< GeometryOptions::empty_cells took effect
  bool empty_cells_too_many = false;  ///< asked for but more than max_empty_cells
  bool planar = false;                ///< GeometryOptions::planar: spheres are circles in z = 0
};

/// Lists the nodes of `s` (GL-free; runs on the build thread).
StructureGeometry structure_geometry(const accel::Structure& s, const GeometryOptions& options);

/// Which nodes are drawn: the "show one depth, a depth range, or leaves only" filter.
struct NodeFilter {
  int depth_min = 0;
  int depth_max = 1 << 20;  ///< inclusive
  bool leaves_only = false;
  bool hide_empty = false;  ///< leaves / cells without triangles
  bool operator==(const NodeFilter&) const = default;
  bool accepts(const NodeInstance& n) const {
    const int d = static_cast<int>(n.depth);
    const bool leaf = n.leaf > 0.5f;
    return d >= depth_min && d <= depth_max && (!leaves_only || leaf) && !(hide_empty && leaf && n.prims < 0.5f);
  }
};

/// The instances `filter` accepts. The viewer re-uploads these only when the filter
/// changes, so a filtered view also costs the GPU less (never per frame).
std::vector<NodeInstance> filter_nodes(const std::vector<NodeInstance>& nodes, const NodeFilter& filter);

/// The level-of-detail limit on what is drawn: at most `max_nodes` of `nodes`, the
/// shallowest levels whole (in a tree each parent covers its children, so the coarse levels
/// summarise what is dropped) and an evenly spaced share of the first level that does not
/// fit (a grid's cells, all at depth 0, thin out evenly). Order is kept. A 10M-triangle
/// scene's BVH has millions of boxes, which no projector shows readably or draws fast.
std::vector<NodeInstance> limit_drawn_nodes(std::vector<NodeInstance> nodes, size_t max_nodes);

/// The deepest depth d such that the nodes of depth <= d number at most `budget` (boxes and
/// spheres counted); -1 when even the root level is over budget. For a readable (and fast)
/// first view of structures with millions of nodes.
int depth_for_budget(const StructureGeometry& g, size_t budget);

/// The split plane of a kd-tree inner node as an instance, or false when the view has none.
bool split_plane_instance(const accel::NodeView& v, NodeInstance* out);

/// Appends the 12 edges of `box` as thick segments; nothing for an empty box.
void append_box_segments(std::vector<Segment>& out, const accel::Aabb& box, const glm::vec4& color, float width);
/// Appends the 12 edges of `box` as thin line vertex pairs; nothing for an empty box.
void append_box_edges(std::vector<ColorVertex>& lines, const accel::Aabb& box, const glm::vec4& color);
/// Where a sphere cuts the plane z = 0, the plane of a 2D scene: the circle's centre (z = 0)
/// and radius sqrt(r^2 - z^2) (r itself for a centre in the plane, as the sphere tree's are
/// over a 2D scene); false when the sphere misses the plane.
bool sphere_in_plane(const glm::vec3& center, float radius, glm::vec3* circle_center, float* circle_radius);
/// A sphere-tree node's outline as a line list (vertex pairs), `segments` per circle: the
/// sphere's three great circles (XY, YZ, ZX) in 3D; over a 2D scene (`planar`) the one circle
/// where it cuts the plane z = 0 (sphere_in_plane(); nothing when it misses). Every outline
/// the viewer draws of a sphere (nodes, highlights, tree selection, construction) is this one.
std::vector<glm::vec3> sphere_outline(const glm::vec3& center, float radius, bool planar, int segments = 32);
/// Appends sphere_outline() as thick segments.
void append_sphere_segments(std::vector<Segment>& out, const glm::vec3& center, float radius, const glm::vec4& color,
                            float width, bool planar, int segments = 48);
/// Appends sphere_outline() as thin line vertex pairs.
void append_sphere_lines(std::vector<ColorVertex>& lines, const glm::vec3& center, float radius,
                         const glm::vec4& color, bool planar);
/// Appends a node's outline, thick: its sphere's (2D: its circle) when it has one, else its box.
void append_node_segments(std::vector<Segment>& out, const accel::NodeView& v, const glm::vec4& color, float width,
                          bool planar);
/// The same as thin line vertex pairs.
void append_node_lines(std::vector<ColorVertex>& lines, const accel::NodeView& v, const glm::vec4& color,
                       bool planar);

/// Unit shapes instanced by the renderer: the cube's 12 edges (24 vertices in [0,1]^3),
/// three unit circles (line list), one unit circle in the plane z = 0 (line list: a 2D
/// sphere-tree node), and the unit square (two triangles, z = 0).
std::vector<glm::vec3> unit_cube_edges();
std::vector<glm::vec3> unit_sphere_circles(int segments = 48);
std::vector<glm::vec3> unit_circle(int segments = 48);
std::vector<glm::vec3> unit_square_triangles();



}  // namespace viz
