#include "ray_gen.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "planar_geometry.h"
#include "random.h"
#include "rays_io.h"

namespace accel {

PinholeCamera default_camera(const Aabb& bounds) {
  PinholeCamera cam;
  if (bounds.empty()) return cam;
  const Vec3 c = bounds.center();
  const float radius = std::max(0.5f * glm::length(bounds.extent()), 1e-6f);
  const float dist = radius / std::sin(glm::radians(cam.fovy_deg) * 0.5f);
  cam.target = c;
  cam.eye = c + dist * glm::normalize(Vec3(0.55f, 0.45f, 1.0f));
  return cam;
}

Ray camera_ray(const PinholeCamera& cam, float px, float py, int width, int height) {
  const Vec3 forward = glm::normalize(cam.target - cam.eye);
  const Vec3 right = glm::normalize(glm::cross(forward, cam.up));
  const Vec3 up = glm::cross(right, forward);
  const float tan_half = std::tan(glm::radians(cam.fovy_deg) * 0.5f);
  const float aspect = float(width) / float(height);
  const float sx = (2.0f * px / float(width) - 1.0f) * tan_half * aspect;
  const float sy = (1.0f - 2.0f * py / float(height)) * tan_half;
  Ray r;
  r.org = cam.eye;
  r.dir = glm::normalize(forward + sx * right + sy * up);
  return r;
}

std::vector<Ray> primary_rays(const PinholeCamera& cam, int width, int height) {
  std::vector<Ray> rays;
  rays.reserve(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) rays.push_back(camera_ray(cam, float(x) + 0.5f, float(y) + 0.5f, width, height));
  return rays;
}

std::vector<Ray> random_rays(const Aabb& bounds, size_t n, uint64_t seed, bool planar) {
  std::vector<Ray> rays;
  rays.reserve(n);
  Rng rng(seed);
  const Vec3 c = bounds.empty() ? Vec3(0.0f) : bounds.center();
  // At least 2^-16 of the centre's magnitude: a tiny scene far from the origin would
  // otherwise round every origin and target onto the centre, a zero direction each time,
  // and the loop below would never end (fuzz_obj found one). No real scene is that thin.
  const float far = std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)}) * 0x1p-16f;
  const Vec3 e = bounds.empty() ? Vec3(1.0f) : glm::max(bounds.extent(), Vec3(std::max(1e-6f, far)));
  while (rays.size() < n) {
    const auto [ox, oy, oz] = rng.uniform_xyz(-0.5f, 0.5f);
    Vec3 o = c + 1.5f * e * Vec3(ox, oy, oz);
    const auto [px, py, pz] = rng.uniform_xyz(-0.5f, 0.5f);
    Vec3 p = c + e * Vec3(px, py, pz);
    if (planar) o.z = p.z = 0.0f;  // the same draws, in the plane z = 0
    const Vec3 d = p - o;
    if (d == Vec3(0.0f)) continue;
    Ray r;
    r.org = o;
    r.dir = d;
    rays.push_back(r);
  }
  return rays;
}

namespace {
bool parse_positive(std::string_view s, uint64_t* out) {
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), *out);
  return !s.empty() && ec == std::errc() && ptr == s.data() + s.size();
}
}  // namespace

Result<std::vector<Ray>> make_rays(const std::string& spec, const Scene& scene) {
  std::vector<std::string_view> parts;
  {
    std::string_view s(spec);
    size_t start = 0, pos;
    while ((pos = s.find(':', start)) != std::string_view::npos) {
      parts.push_back(s.substr(start, pos - start));
      start = pos + 1;
    }
    parts.push_back(s.substr(start));
  }
  if (parts[0] == "primary") {
    uint64_t w, h;
    if (parts.size() != 3 || !parse_positive(parts[1], &w) || !parse_positive(parts[2], &h) || w == 0 || h == 0 ||
        w > 16384 || h > 16384)
      return make_error("rays '" + spec + "': expected primary:W:H with W, H in [1, 16384]");
    if (scene.planar())
      return make_error("rays '" + spec + "': a 2D scene has no camera; use random:N:SEED or a file of 2D rays");
    return primary_rays(default_camera(scene.bounds()), int(w), int(h));
  }
  if (parts[0] == "random") {
    uint64_t n, seed;
    if (parts.size() != 3 || !parse_positive(parts[1], &n) || !parse_positive(parts[2], &seed) || n == 0 ||
        n > 100'000'000)
      return make_error("rays '" + spec + "': expected random:N:SEED with N in [1, 1e8]");
    return random_rays(scene.bounds(), n, seed, scene.planar());
  }
  auto rays = read_rays(spec);
  if (!rays || !scene.planar()) return rays;
  // docs/hits.md, 2D scenes: a 3D ray would leave the plane the triangles lie in.
  for (size_t i = 0; i < rays.value().size(); ++i)
    if (!is_planar_ray(rays.value()[i]))
      return make_error(spec + ": ray " + std::to_string(i) +
                        " (0-based) is not a 2D ray, which a 2D scene needs: oz = dz = 0, dx and dy not both 0");
  return rays;
}

}  // namespace accel
