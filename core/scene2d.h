#pragma once
// 2D scene files (blackboard mode, issue #32; docs/hits.md "2D scene files"): one triangle
// per line, `tri x1 y1 x2 y2 x3 y3`, '#' comments and blank lines skipped. A scene read
// from one lies in the plane z = 0, its triangles numbered in file order, and is marked
// planar (Scene::planar()).
#include <array>
#include <string>

#include "result.h"
#include "scene.h"

namespace accel {

/// The file extension of 2D scene files, ".scene2d": what load_scene() reads as one.
inline constexpr const char* kScene2dExtension = ".scene2d";

/// Reads a 2D scene from `text`; errors name `source_name` and the line ("SOURCE:LINE:
/// what"): an unknown command (`seg` among them: 2D scenes hold triangles only), a count
/// other than 6 numbers, a malformed or non-finite number. An empty scene is valid (the
/// blackboard starts empty). The name of the scene is `source_name`.
Result<Scene> parse_scene2d(const std::string& text, const std::string& source_name);
/// Reads the 2D scene file at `path` (errors name it).
Result<Scene> load_scene2d(const std::string& path);

/// `scene` (a 2D one, or empty) with the triangle (x1, y1), (x2, y2), (x3, y3) appended as
/// its last: the blackboard's edit. The result is planar and named as `scene`.
Scene scene2d_with_triangle(const Scene& scene, const std::array<float, 6>& xy);
/// `scene` (2D) with vertex `vertex` moved to (x, y): the blackboard's drag of a corner.
Scene scene2d_with_vertex_moved(const Scene& scene, uint32_t vertex, float x, float y);
/// `scene` (2D) without triangle `prim` (its vertices stay, unused); later triangles move
/// down one number, as in the file saved afterwards.
Scene scene2d_without_triangle(const Scene& scene, uint32_t prim);

/// The text of `scene` (a planar one) as a 2D scene file: a comment line, then one `tri`
/// line per triangle in order, coordinates with %.9g (read back to the same floats).
std::string format_scene2d(const Scene& scene);
/// Writes format_scene2d(scene) to `path` atomically (never half written; errors name it).
Status save_scene2d(const std::string& path, const Scene& scene);

}  // namespace accel
