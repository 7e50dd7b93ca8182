#pragma once
// Scene: exactly what ray casting needs (positions, triangles, their bounds) and nothing
// more: no materials, normals, textures or scene graph.
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vec_math.h"
#include "result.h"

namespace accel {

/// A triangle soup. Triangles are numbered 0,1,2,... in file order (docs/hits.md); degenerate
/// (zero-area) triangles keep their number but are never hit and never enter a structure.
class Scene {
 public:
  Scene() = default;
  /// Takes positions and triangle indices (validated by the caller: indices in range,
  /// coordinates finite) and computes the cached per-triangle data.
  Scene(std::vector<Vec3> positions, std::vector<UVec3> triangles, std::string name = {});

  size_t triangle_count() const { return triangles_.size(); }
  size_t vertex_count() const { return positions_.size(); }
  const std::vector<Vec3>& positions() const { return positions_; }
  const std::vector<UVec3>& triangles() const { return triangles_; }
  /// Vertex k (0..2) of triangle `prim`.
  const Vec3& vertex(uint32_t prim, int k) const { return positions_[triangles_[prim][k]]; }
  const Aabb& triangle_bounds(uint32_t prim) const { return tri_bounds_[prim]; }
  const Vec3& centroid(uint32_t prim) const { return centroids_[prim]; }
  bool degenerate(uint32_t prim) const { return degenerate_[prim] != 0; }
  /// Indices of all non-degenerate triangles, ascending: what structures are built over.
  const std::vector<uint32_t>& valid_prims() const { return valid_prims_; }
  size_t degenerate_count() const { return triangles_.size() - valid_prims_.size(); }
  /// Bounds of all vertices referenced by a triangle.
  const Aabb& bounds() const { return bounds_; }
  /// Largest absolute coordinate (the M of docs/hits.md's ulp allowance).
  float max_abs_coordinate() const;
  const std::string& name() const { return name_; }
  /// A 2D scene (blackboard mode, docs/hits.md "2D scenes"): every vertex lies in the plane
  /// z = 0 and rays are 2D rays in it, tested by the 2D hit rule (planar_geometry.h).
  bool planar() const { return planar_; }
  /// Marks the scene 2D. Error when a vertex has z != 0 (naming it).
  Status mark_planar();

  /// Replaces the vertex positions (same count; the triangles stay) and recomputes what
  /// derives from them: triangle bounds, centroids, degenerate flags, valid_prims(), bounds().
  /// A triangle may change between degenerate and valid; structures built over the old
  /// positions are then stale: Structure::refit() them (it fails when valid_prims() changed)
  /// or rebuild. Errors, leaving the scene unchanged: a count other than vertex_count(), a
  /// NaN or infinite coordinate (named by vertex index), a 2D scene's vertex off z = 0.
  Status move_vertices(std::span<const Vec3> positions);

 private:
  /// Computes tri_bounds_, centroids_, degenerate_, valid_prims_ and bounds_ from the
  /// positions (the constructor's and move_vertices()'s shared step).
  void compute_triangle_data();

  std::vector<Vec3> positions_;
  std::vector<UVec3> triangles_;
  std::vector<Aabb> tri_bounds_;
  std::vector<Vec3> centroids_;
  std::vector<uint8_t> degenerate_;
  std::vector<uint32_t> valid_prims_;
  Aabb bounds_;
  std::string name_;
  bool planar_ = false;
};

/// Loads a Wavefront OBJ (docs/hits.md: polygons fan-triangulated in place, materials,
/// normals and uvs ignored). Rejects, with "FILE:LINE: what" messages: unreadable or
/// non-text (e.g. UTF-16) files, malformed numbers, NaN/inf coordinates, out-of-range or
/// zero face indices, faces with fewer than 3 vertices, and files with no triangles.
/// A missing .mtl is not an error.
Result<Scene> load_obj(const std::string& path);

/// True for the formats load_mesh() reads, by extension (case-insensitive): .ply, .stl,
/// .gltf, .glb.
bool is_mesh_format(const std::string& path);
/// Loads a PLY, STL or glTF 2.0 / GLB file through Assimp, triangles only (docs/hits.md):
/// meshes in the order the file's node tree reaches them (depth first, children in file
/// order) with their node transforms applied, each mesh's faces in file order, polygons
/// fan-triangulated in place as for OBJ; points and lines are skipped. Rejects, with "FILE:
/// what" messages: missing, empty or unreadable files, Assimp's parse errors, a PLY header
/// claiming more elements than the file holds, non-finite coordinates, out-of-range
/// indices, and files with no triangles.
Result<Scene> load_mesh(const std::string& path);

/// Names accepted by make_procedural_scene(), e.g. "sphere", "soup", "cornell", "stadium";
/// the large ones ("terrain", ~1M triangles; "huge", 10M) only with include_large.
std::vector<std::string> procedural_scene_names(bool include_large = false);
/// One-line description of a procedural scene, for help texts and the viewer's presets.
std::string procedural_scene_description(std::string_view name);
/// Builds a procedural scene by name; `seed` varies the random ones. Unknown name -> Error.
Result<Scene> make_procedural_scene(std::string_view name, uint32_t seed = 1);
/// The parts of a scattered scene (make_scattered_scene): a heightfield of rolling hills over a
/// fixed 200 x 125 area, and closed objects on and above it. The defaults are
/// "procedural:huge", 10,000,000 triangles; the tests scale them down.
struct ScatteredSceneSize {
  uint32_t terrain_x = 2000, terrain_z = 1250;  ///< heightfield cells along x and z (>= 1), 2 triangles each
  uint32_t boxes = 20000;                       ///< yawed boxes (12 triangles, 8 shared vertices)
  /// Icospheres per subdivision level 1..4 (80, 320, 1280, 5120 triangles each).
  std::array<uint32_t, 4> spheres = {2700, 5000, 1500, 200};

  /// Triangles of the scene this size makes.
  size_t triangle_count() const;
  /// Vertices of the scene this size makes (every mesh shares its vertices).
  size_t vertex_count() const;
};

/// A heightfield terrain (triangles first, row by row) followed by scattered closed objects
/// (boxes, then icospheres from level 1 to 4), most of them in clusters of varying radius, the
/// rest spread evenly, a fifth of the spheres floating: dense and sparse regions, objects of
/// sizes from 0.1 to 8 over a 200-wide terrain. Deterministic for a given size and seed
/// (random.h); no degenerate triangles.
Scene make_scattered_scene(const ScatteredSceneSize& size, uint32_t seed = 1, std::string name = "procedural:huge");

/// Loads "procedural:NAME" via make_procedural_scene, .ply/.stl/.gltf/.glb via load_mesh,
/// a .scene2d file via load_scene2d (scene2d.h: a 2D scene), anything else via load_obj.
Result<Scene> load_scene(const std::string& spec);

/// The first thing load_scene does with a spec that names a file: fetch_missing_input
/// (input_files.h), so that in the page a file next to it is there. For a caller that loads
/// on another thread or fibre: it calls this first, where the page can wait for a download.
Status fetch_scene_file(const std::string& spec);

}  // namespace accel
