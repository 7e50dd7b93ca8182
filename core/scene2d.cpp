#include "scene2d.h"

#include <cmath>
#include <cstdio>
#include <string_view>
#include <vector>

#include "rays_io.h"

namespace accel {

Result<Scene> parse_scene2d(const std::string& text, const std::string& source_name) {
  std::vector<Vec3> positions;
  std::vector<UVec3> triangles;
  TokenLines lines(text, source_name);
  auto fail = [&](const std::string& what) { return lines.error(what); };
  while (lines.next()) {
    const std::vector<std::string_view>& tok = lines.tokens();
    if (tok[0] == "seg")
      return fail("'seg': 2D scenes hold triangles only (a segment has no area: docs/hits.md, 2D scenes)");
    if (tok[0] != "tri") return fail("unknown command '" + printable(tok[0]) + "' (expected tri x1 y1 x2 y2 x3 y3)");
    if (tok.size() != 7)
      return fail("tri needs 6 numbers (x1 y1 x2 y2 x3 y3), got " + std::to_string(tok.size() - 1));
    float v[6];
    for (size_t k = 0; k < 6; ++k) {
      if (!parse_ray_number(tok[k + 1], &v[k]))
        return fail("malformed number '" + printable(tok[k + 1]) + "' (number " + std::to_string(k + 1) + ")");
      if (!std::isfinite(v[k]))
        return fail("coordinates must be finite (number " + std::to_string(k + 1) + " is '" + printable(tok[k + 1]) +
                    "')");
    }
    const uint32_t first = uint32_t(positions.size());
    for (int k = 0; k < 3; ++k) positions.emplace_back(v[2 * k], v[2 * k + 1], 0.0f);
    triangles.push_back(UVec3(first, first + 1, first + 2));
  }
  Scene scene(std::move(positions), std::move(triangles), source_name);
  const Status planar = scene.mark_planar();
  ACCEL_CHECK(planar.ok());  // every vertex was made with z = 0
  return scene;
}

Result<Scene> load_scene2d(const std::string& path) {
  auto text = read_text_file(path, "2D scene");
  if (!text) return text.error();
  return parse_scene2d(text.value(), path);
}

namespace {

Scene planar_scene(std::vector<Vec3> positions, std::vector<UVec3> triangles, const std::string& name) {
  Scene out(std::move(positions), std::move(triangles), name);
  const Status planar = out.mark_planar();
  ACCEL_CHECK(planar.ok());  // every vertex of a 2D scene's edit has z = 0
  return out;
}

}  // namespace

Scene scene2d_with_triangle(const Scene& scene, const std::array<float, 6>& xy) {
  std::vector<Vec3> positions = scene.positions();
  std::vector<UVec3> triangles = scene.triangles();
  const uint32_t first = uint32_t(positions.size());
  for (int k = 0; k < 3; ++k) positions.emplace_back(xy[size_t(2 * k)], xy[size_t(2 * k + 1)], 0.0f);
  triangles.push_back(UVec3(first, first + 1, first + 2));
  return planar_scene(std::move(positions), std::move(triangles), scene.name());
}

Scene scene2d_with_vertex_moved(const Scene& scene, uint32_t vertex, float x, float y) {
  std::vector<Vec3> positions = scene.positions();
  ACCEL_CHECK(vertex < positions.size());
  positions[vertex] = Vec3(x, y, 0.0f);
  return planar_scene(std::move(positions), scene.triangles(), scene.name());
}

Scene scene2d_without_triangle(const Scene& scene, uint32_t prim) {
  std::vector<UVec3> triangles = scene.triangles();
  ACCEL_CHECK(prim < triangles.size());
  triangles.erase(triangles.begin() + ptrdiff_t(prim));
  return planar_scene(scene.positions(), std::move(triangles), scene.name());
}

std::string format_scene2d(const Scene& scene) {
  std::string out = "# accelviz 2D scene: tri x1 y1 x2 y2 x3 y3 (docs/hits.md, 2D scene files)\n";
  char buf[160];
  for (size_t prim = 0; prim < scene.triangle_count(); ++prim) {
    const Vec3 &a = scene.vertex(uint32_t(prim), 0), &b = scene.vertex(uint32_t(prim), 1),
               &c = scene.vertex(uint32_t(prim), 2);
    std::snprintf(buf, sizeof buf, "tri %.9g %.9g %.9g %.9g %.9g %.9g\n", double(a.x), double(a.y), double(b.x),
                  double(b.y), double(c.x), double(c.y));
    out += buf;
  }
  return out;
}

Status save_scene2d(const std::string& path, const Scene& scene) {
  return write_file_atomic(path, format_scene2d(scene));
}

}  // namespace accel
