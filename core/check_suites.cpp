#include "check_suites.h"

#include <cmath>
#include <tuple>

#include "random.h"
#include "ray_gen.h"

namespace accel {
namespace {

Scene transformed(const Scene& s, float scale, Vec3 offset, const std::string& name) {
  std::vector<Vec3> p = s.positions();
  for (Vec3& v : p) v = v * scale + offset;
  return Scene(std::move(p), s.triangles(), name);
}

/// Rays from outside towards every vertex and every edge of a mesh (through shared edges and
/// vertices of a closed mesh: the watertightness cases).
std::vector<Ray> rays_at_vertices_and_edges(const Scene& s, uint64_t seed, size_t limit) {
  Rng rng(seed);
  std::vector<Ray> rays;
  const Vec3 c = s.bounds().center();
  const float r = glm::length(s.bounds().extent());
  for (uint32_t t = 0; t < s.triangle_count() && rays.size() < limit; ++t) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = s.vertex(t, k), b = s.vertex(t, (k + 1) % 3);
      const Vec3 dir_out = glm::normalize(Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)) + 1e-3f);
      for (const Vec3& target : {a, 0.5f * (a + b), a + 0.25f * (b - a)}) {
        Ray ray;
        ray.org = c + r * dir_out;
        ray.dir = target - ray.org;
        rays.push_back(ray);
      }
    }
  }
  return rays;
}

/// Axis-parallel rays on a lattice of planes x, y, z = k / 8 of the scene box: rays in cell
/// boundary and split planes, origins on the box faces and inside.
std::vector<Ray> axis_rays(const Aabb& box, int n) {
  std::vector<Ray> rays;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sgn : {1, -1}) {
      for (int i = 0; i <= n; ++i) {
        for (int j = 0; j <= n; ++j) {
          const int u = (axis + 1) % 3, v = (axis + 2) % 3;
          for (int start : {0, 1}) {  // from outside the box, and from its face
            Ray r;
            r.org[u] = box.min[u] + (box.max[u] - box.min[u]) * float(i) / float(n);
            r.org[v] = box.min[v] + (box.max[v] - box.min[v]) * float(j) / float(n);
            const float face = sgn > 0 ? box.min[axis] : box.max[axis];
            const float extent = std::max(box.max[axis] - box.min[axis], 1.0f);
            r.org[axis] = start == 0 ? face - float(sgn) * extent : face;
            r.dir = Vec3(0.0f);
            r.dir[axis] = float(sgn);
            rays.push_back(r);
            Ray z = r;  // the same with a -0.0 / +0.0 in the other components
            z.dir[u] = -0.0f;
            rays.push_back(z);
          }
        }
      }
    }
  }
  return rays;
}

/// A cube of small random triangles, pinned to exactly [0, 1]^3, crossed by diagonal rays
/// whose x and y (or y and z, or z and x) coordinates stay equal: in any grid of equal
/// cells per axis over the cube the DDA's tMax of those two axes tie at every step, so a
/// walk that breaks such a tie wrongly leaves the ray's path (the lecture's 3D-DDA).
HardCase cube_diagonals() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  Rng rng(11);
  for (uint32_t i = 0; i < 600; ++i) {
    const Vec3 c(rng.uniform(0.05f, 0.95f), rng.uniform(0.05f, 0.95f), rng.uniform(0.05f, 0.95f));
    const uint32_t base = uint32_t(p.size());
    for (int k = 0; k < 3; ++k)
      p.push_back(c + Vec3(rng.uniform(-0.05f, 0.05f), rng.uniform(-0.05f, 0.05f), rng.uniform(-0.05f, 0.05f)));
    t.emplace_back(base, base + 1, base + 2);
  }
  for (const Vec3 corner : {Vec3(0.0f), Vec3(1.0f)}) {  // tiny triangles at two corners pin the box
    const uint32_t base = uint32_t(p.size());
    const Vec3 in = corner.x == 0.0f ? Vec3(0.01f) : Vec3(-0.01f);
    p.push_back(corner);
    p.push_back(corner + Vec3(in.x, 0.0f, 0.0f));
    p.push_back(corner + Vec3(0.0f, in.y, in.z));
    t.emplace_back(base, base + 1, base + 2);
  }
  Scene cube(std::move(p), std::move(t), "cube_diagonals");
  std::vector<Ray> rays;
  for (int i = 0; i < 400; ++i) {
    const float a = rng.uniform(-0.5f, 0.6f), c = rng.uniform(0.0f, 1.0f), slope = rng.uniform(-0.6f, 0.6f);
    const float s = i % 2 ? 1.0f : -1.0f;
    for (int pair = 0; pair < 3; ++pair) {  // the two equal axes: (x, y), (y, z), (z, x)
      Ray r;
      const int u = pair, v = (pair + 1) % 3, w = (pair + 2) % 3;
      r.org[u] = s > 0 ? a - 0.6f : 1.6f - a;
      r.org[v] = r.org[u];
      r.org[w] = c;
      r.dir[u] = s;
      r.dir[v] = s;
      r.dir[w] = slope;
      rays.push_back(r);
    }
  }
  return {"cube_diagonals", std::move(cube), std::move(rays)};
}

/// Flat scene: a 20x20 grid of quads in z = 0 (zero-thickness box), shared edges.
HardCase flat_scene() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (int y = 0; y <= 20; ++y)
    for (int x = 0; x <= 20; ++x) p.emplace_back(float(x) / 20.0f, float(y) / 20.0f, 0.0f);
  for (uint32_t y = 0; y < 20; ++y)
    for (uint32_t x = 0; x < 20; ++x) {
      const uint32_t i = y * 21 + x;
      t.emplace_back(i, i + 1, i + 22);
      t.emplace_back(i, i + 22, i + 21);
    }
  Scene flat(std::move(p), std::move(t), "flat");
  std::vector<Ray> rays;
  for (int y = 0; y <= 40; ++y)
    for (int x = 0; x <= 40; ++x) {  // straight down through vertices, edges and diagonals
      Ray r;
      r.org = Vec3(float(x) / 40.0f, float(y) / 40.0f, 1.0f);
      r.dir = Vec3(0, 0, -1);
      rays.push_back(r);
      r.dir = Vec3(0.001f * float(x - 20), 0.0f, -1.0f);
      rays.push_back(r);
      Ray in_plane;  // inside the plane: never a hit
      in_plane.org = Vec3(-1.0f, float(y) / 40.0f, 0.0f);
      in_plane.dir = Vec3(1, 0, 0);
      rays.push_back(in_plane);
    }
  return {"flat_scene", std::move(flat), std::move(rays)};
}

/// Slivers, zero-area and duplicate triangles.
HardCase slivers_zero_area_duplicates() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  Rng rng(5);
  for (uint32_t i = 0; i < 2000; ++i) {
    const Vec3 a(rng.uniform(), rng.uniform(), rng.uniform());
    const Vec3 d = glm::normalize(Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)) + 1e-3f);
    const Vec3 side = glm::normalize(glm::cross(d, Vec3(0.3f, 0.5f, 0.7f)));
    const uint32_t base = uint32_t(p.size());
    p.push_back(a);
    p.push_back(a + 0.3f * d);
    p.push_back(a + 0.15f * d + 1e-5f * side);  // a sliver 30000x longer than wide
    t.emplace_back(base, base + 1, base + 2);
    if (i % 10 == 0) t.emplace_back(base, base + 1, base + 1);  // zero area
    if (i % 7 == 0) t.emplace_back(base, base + 1, base + 2);   // duplicate
  }
  Scene slivers(std::move(p), std::move(t), "slivers");
  auto rays = random_rays(slivers.bounds(), 20000, 6);
  return {"slivers_zero_area_duplicates", std::move(slivers), std::move(rays)};
}

/// Thousands of coplanar, overlapping triangles: every hit is a tie.
HardCase coplanar_overlapping() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  Rng rng(8);
  for (uint32_t i = 0; i < 3000; ++i) {
    const Vec3 c(rng.uniform(), rng.uniform(), 0.25f);
    p.push_back(c + Vec3(-0.3f, -0.3f, 0.0f));
    p.push_back(c + Vec3(0.3f, -0.2f, 0.0f));
    p.push_back(c + Vec3(0.0f, 0.3f, 0.0f));
    t.emplace_back(3 * i, 3 * i + 1, 3 * i + 2);
  }
  Scene coplanar(std::move(p), std::move(t), "coplanar_overlapping");
  auto rays = random_rays(coplanar.bounds(), 10000, 9);
  return {"coplanar_overlapping", std::move(coplanar), std::move(rays)};
}

/// Hits exactly at tmin / tmax: the floor of cornell (y = 0) seen straight down from y = 3,
/// t = 3 exactly; one ulp beyond either bound must miss.
HardCase hits_at_tmin_tmax() {
  std::vector<Ray> rays;
  for (int i = 0; i < 50; ++i) {
    Ray r;
    r.org = Vec3(-0.9f + 0.036f * float(i), 3.0f, 0.9f);
    r.dir = Vec3(0, -1, 0);
    for (auto [lo, hi] : {std::pair{0.0f, 3.0f}, std::pair{3.0f, kInf}, std::pair{0.0f, std::nextafter(3.0f, 0.0f)},
                          std::pair{std::nextafter(3.0f, 4.0f), kInf}, std::pair{3.0f, 3.0f}}) {
      r.tmin = lo;
      r.tmax = hi;
      rays.push_back(r);
    }
  }
  Scene floor_only({{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}, {{0, 1, 2}, {0, 2, 3}}, "floor");
  return {"hits_at_tmin_tmax", std::move(floor_only), std::move(rays)};
}

}  // namespace

std::vector<HardCase> hard_cases() {
  std::vector<HardCase> cases;
  const Scene sphere = make_procedural_scene("sphere").value();
  cases.push_back({"closed_mesh_edges_vertices", sphere, rays_at_vertices_and_edges(sphere, 1, 20000)});
  const Scene cornell = make_procedural_scene("cornell").value();
  cases.push_back({"axis_parallel_on_planes", cornell, axis_rays(cornell.bounds(), 16)});
  {
    auto rays = random_rays(cornell.bounds(), 5000, 2);
    for (Ray& r : rays) r.org = cornell.bounds().center() + 0.9f * (r.org - cornell.bounds().center()) / 1.5f;
    cases.push_back({"origins_inside_scene", cornell, rays});
  }
  for (auto [scale, offset, name] :
       {std::tuple{1.0f, Vec3(1e5f, -1e5f, 1e5f), "offset_1e5"}, std::tuple{1e-3f, Vec3(0.0f), "scale_1e-3"},
        std::tuple{1e3f, Vec3(0.0f), "scale_1e3"}}) {
    const Scene s = transformed(sphere, scale, offset, name);
    auto rays = rays_at_vertices_and_edges(s, 3, 6000);
    auto more = random_rays(s.bounds(), 4000, 4);
    rays.insert(rays.end(), more.begin(), more.end());
    cases.push_back({name, s, rays});
  }
  cases.push_back(flat_scene());
  cases.push_back(slivers_zero_area_duplicates());
  cases.push_back({"teapot_in_stadium", make_procedural_scene("stadium").value(),
                   random_rays(Aabb{Vec3(-1.0f), Vec3(1.0f)}, 10000, 7)});
  cases.push_back(coplanar_overlapping());
  cases.push_back(hits_at_tmin_tmax());
  cases.push_back(cube_diagonals());
  return cases;
}

std::vector<std::string> edge_scene_names() { return {"one_triangle", "coplanar", "identical"}; }

Scene edge_scene(const std::string& name) {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  if (name == "one_triangle") {
    p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    t = {{0, 1, 2}};
  } else if (name == "coplanar") {
    // 2000 random triangles in the plane z = 0.5: a flat scene box, split planes in it.
    Rng rng(4);
    for (uint32_t i = 0; i < 2000; ++i) {
      const Vec3 c(rng.uniform(), rng.uniform(), 0.5f);
      for (int k = 0; k < 3; ++k) p.push_back(c + Vec3(rng.uniform(-0.05f, 0.05f), rng.uniform(-0.05f, 0.05f), 0.0f));
      t.emplace_back(3 * i, 3 * i + 1, 3 * i + 2);
    }
  } else if (name == "identical") {
    p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
    for (int i = 0; i < 500; ++i) t.emplace_back(0, 1, 2);
  }
  return Scene(std::move(p), std::move(t), name);
}

}  // namespace accel
