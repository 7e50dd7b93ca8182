// Procedural scenes: they need no file, so the viewer's default scene and the tests work
// on a fresh clone. Each is deterministic for a given seed (random.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "check.h"
#include "random.h"
#include "scene.h"
#include "traps.h"

namespace accel {
namespace {

// sin and cos of the scenes' shapes: in double, rounded to float. sinf and cosf differ in the
// last bit between C libraries (glibc natively, musl in the web page: the stadium's stands
// moved by an ulp), and a scene must be the same everywhere; the double results of both
// libraries round to the same float.
float sin_f(float x) { return float(std::sin(double(x))); }
float cos_f(float x) { return float(std::cos(double(x))); }

/// Accumulates positions and triangles, so each builder below reads as a list of shapes.
struct MeshBuilder {
  std::vector<Vec3> positions;
  std::vector<UVec3> triangles;

  uint32_t vertex(const Vec3& p) { positions.push_back(p); return uint32_t(positions.size() - 1); }
  void triangle(uint32_t a, uint32_t b, uint32_t c) { triangles.emplace_back(a, b, c); }
  /// Quad a,b,c,d (counter-clockwise) as two triangles.
  void quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    const uint32_t i = vertex(a), j = vertex(b), k = vertex(c), l = vertex(d);
    triangle(i, j, k);
    triangle(i, k, l);
  }
  /// Axis-aligned box with outward faces.
  void box(const Vec3& lo, const Vec3& hi) {
    const Vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                       {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    quad(p[0], p[3], p[2], p[1]);  // -z
    quad(p[4], p[5], p[6], p[7]);  // +z
    quad(p[0], p[1], p[5], p[4]);  // -y
    quad(p[3], p[7], p[6], p[2]);  // +y
    quad(p[0], p[4], p[7], p[3]);  // -x
    quad(p[1], p[2], p[6], p[5]);  // +x
  }
  /// Icosphere: an icosahedron subdivided `levels` times (20 * 4^levels triangles),
  /// vertices shared so the mesh is closed (a watertightness test case).
  void icosphere(const Vec3& center, float radius, int levels, float bump = 0.0f) {
    const float g = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<Vec3> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                           {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    for (Vec3& p : v) p = glm::normalize(p);
    std::vector<UVec3> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int l = 0; l < levels; ++l) {
      std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoint;
      auto mid = [&](uint32_t a, uint32_t b) {
        const auto key = std::minmax(a, b);
        auto [it, inserted] = midpoint.try_emplace(key, uint32_t(v.size()));
        if (inserted) v.push_back(glm::normalize(v[a] + v[b]));
        return it->second;
      };
      std::vector<UVec3> next;
      next.reserve(f.size() * 4);
      for (const UVec3& t : f) {
        const uint32_t ab = mid(t.x, t.y), bc = mid(t.y, t.z), ca = mid(t.z, t.x);
        next.insert(next.end(), {{t.x, ab, ca}, {t.y, bc, ab}, {t.z, ca, bc}, {ab, bc, ca}});
      }
      f = std::move(next);
    }
    const uint32_t base = uint32_t(positions.size());
    for (const Vec3& p : v) {
      // A deterministic bumpy surface (for the dense 'teapot' object) keeps the mesh closed.
      const float r = radius * (1.0f + bump * sin_f(7.0f * p.x) * sin_f(5.0f * p.y) * sin_f(3.0f * p.z));
      positions.push_back(center + r * p);
    }
    for (const UVec3& t : f) triangle(base + t.x, base + t.y, base + t.z);
  }
};

Scene make_sphere() {
  MeshBuilder m;
  m.icosphere(Vec3(0.0f), 1.0f, 4);
  return Scene(std::move(m.positions), std::move(m.triangles), "procedural:sphere");
}

Scene make_soup(uint32_t seed) {
  // 10k random triangles in the unit cube, each with edges up to 0.1: overlapping,
  // intersecting, of all orientations -- the classic BVH test soup.
  MeshBuilder m;
  Rng rng(seed);
  for (int i = 0; i < 10000; ++i) {
    auto point = [&rng](float lo, float hi) {
      const auto [x, y, z] = rng.uniform_xyz(lo, hi);
      return Vec3(x, y, z);
    };
    const Vec3 c = point(0.0f, 1.0f);
    const uint32_t a = m.vertex(c + point(-0.05f, 0.05f));
    const uint32_t b = m.vertex(c + point(-0.05f, 0.05f));
    const uint32_t d = m.vertex(c + point(-0.05f, 0.05f));
    m.triangle(a, b, d);
  }
  return Scene(std::move(m.positions), std::move(m.triangles), "procedural:soup");
}

Scene make_cornell() {
  // A Cornell-box-like room (open at +z) with a tall and a short block and a ceiling light,
  // all axis-aligned: rays on cell boundaries and split planes are common here.
  MeshBuilder m;
  m.quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});     // floor
  m.quad({-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1});     // ceiling
  m.quad({-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1});   // back wall
  m.quad({-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {-1, 0, 1});   // left wall
  m.quad({1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1});       // right wall
  m.quad({-0.25f, 1.98f, -0.25f}, {0.25f, 1.98f, -0.25f}, {0.25f, 1.98f, 0.25f}, {-0.25f, 1.98f, 0.25f});  // light
  m.box({-0.7f, 0.0f, -0.7f}, {-0.1f, 1.2f, -0.1f});          // tall block
  m.box({0.1f, 0.0f, 0.0f}, {0.7f, 0.6f, 0.6f});              // short block
  m.icosphere({0.4f, 0.85f, 0.3f}, 0.25f, 2);                 // a ball on the short block
  return Scene(std::move(m.positions), std::move(m.triangles), "procedural:cornell");
}

Scene make_stadium() {
  // "Teapot in a stadium" (Haines 1988): a small, dense object in the middle of a huge,
  // sparse environment. Uniform grids waste nearly every cell on it; adaptive trees don't.
  MeshBuilder m;
  m.icosphere(Vec3(0.0f, 0.5f, 0.0f), 0.5f, 5, 0.15f);   // 20480 small triangles: the 'teapot'
  const int segments = 48;
  const float r_in = 60.0f, r_out = 100.0f;
  for (int i = 0; i < segments; ++i) {  // tiered stands: a ring of large sloped quads
    const float a0 = 2.0f * std::numbers::pi_v<float> * i / segments;
    const float a1 = 2.0f * std::numbers::pi_v<float> * (i + 1) / segments;
    const Vec3 d0(cos_f(a0), 0.0f, sin_f(a0)), d1(cos_f(a1), 0.0f, sin_f(a1));
    m.quad(d0 * r_in, d0 * r_out + Vec3(0, 30, 0), d1 * r_out + Vec3(0, 30, 0), d1 * r_in);
  }
  const uint32_t centre = m.vertex(Vec3(0.0f));  // the pitch: a disc under the stands' inner edge
  for (int i = 0; i < segments; ++i) {
    const float a0 = 2.0f * std::numbers::pi_v<float> * i / segments;
    const float a1 = 2.0f * std::numbers::pi_v<float> * (i + 1) / segments;
    // Never m.triangle(centre, m.vertex(..), m.vertex(..)): the order of a call's arguments is
    // open (GCC went right to left, clang left to right). This is GCC's, as scenes were.
    const uint32_t at_a0 = m.vertex(r_in * Vec3(cos_f(a0), 0.0f, sin_f(a0)));
    const uint32_t at_a1 = m.vertex(r_in * Vec3(cos_f(a1), 0.0f, sin_f(a1)));
    m.triangle(centre, at_a1, at_a0);
  }
  return Scene(std::move(m.positions), std::move(m.triangles), "procedural:stadium");
}

Scene make_terrain() {
  // About a million triangles: a 724 x 724 heightfield of rolling hills, for measuring the
  // viewer's frame rate and the builders' speed at scale.
  constexpr int n = 724;
  MeshBuilder m;
  m.positions.reserve(size_t(n + 1) * (n + 1));
  for (int z = 0; z <= n; ++z)
    for (int x = 0; x <= n; ++x) {
      const float u = float(x) / n, v = float(z) / n;
      const float h = 0.08f * sin_f(9.0f * u) * cos_f(7.0f * v) + 0.03f * sin_f(31.0f * u + 17.0f * v);
      m.vertex(Vec3(u - 0.5f, h, v - 0.5f));
    }
  m.triangles.reserve(size_t(2) * n * n);
  for (int z = 0; z < n; ++z)
    for (int x = 0; x < n; ++x) {
      const uint32_t i = uint32_t(z * (n + 1) + x);
      m.triangle(i, i + n + 1, i + 1);
      m.triangle(i + 1, i + n + 1, i + n + 2);
    }
  return Scene(std::move(m.positions), std::move(m.triangles), "procedural:terrain");
}

// [huge] A heightfield with scattered closed objects (make_scattered_scene).

constexpr float kScatterWidth = 200.0f, kScatterDepth = 125.0f;  // the terrain's extent in x and z
constexpr uint32_t kScatterClusters = 24;
constexpr float kClusteredShare = 0.65f;  // objects placed in a cluster, the rest spread evenly
constexpr float kFloatingShare = 0.2f;    // spheres floating above the ground

/// Rolling hills with a ridge and some roughness, about +-9 over the 200 x 125 area.
float scatter_height(float x, float z) {
  return 6.0f * sin_f(0.05f * x) * cos_f(0.07f * z) + 2.5f * sin_f(0.17f * x + 0.11f * z) +
         0.6f * sin_f(0.9f * x) * sin_f(0.8f * z);
}

/// A point on the terrain's (x, z) area for one object: in one of the clusters (denser at
/// its centre) or anywhere.
struct ScatterPlacer {
  Rng& rng;
  std::array<Vec3, kScatterClusters> clusters;  // centre x, radius, centre z

  explicit ScatterPlacer(Rng& r) : rng(r) {
    for (Vec3& c : clusters) {
      c.x = rng.uniform(-0.4f, 0.4f) * kScatterWidth;
      c.y = rng.uniform(3.0f, 12.0f);
      c.z = rng.uniform(-0.4f, 0.4f) * kScatterDepth;
    }
  }
  std::pair<float, float> place() {
    if (rng.uniform() < kClusteredShare) {
      const Vec3& c = clusters[std::min<size_t>(size_t(rng.uniform() * kScatterClusters), kScatterClusters - 1)];
      const float a = 2.0f * std::numbers::pi_v<float> * rng.uniform(), u = rng.uniform();
      const float r = c.y * u * u;
      return {std::clamp(c.x + r * cos_f(a), -0.5f * kScatterWidth, 0.5f * kScatterWidth),
              std::clamp(c.z + r * sin_f(a), -0.5f * kScatterDepth, 0.5f * kScatterDepth)};
    }
    return {rng.uniform(-0.5f, 0.5f) * kScatterWidth, rng.uniform(-0.5f, 0.5f) * kScatterDepth};
  }
};

constexpr uint32_t icosphere_vertices(int level) { return 10u * (1u << (2 * level)) + 2u; }
constexpr uint32_t icosphere_triangles(int level) { return 20u * (1u << (2 * level)); }

}  // namespace

size_t ScatteredSceneSize::triangle_count() const {
  size_t n = size_t(2) * terrain_x * terrain_z + size_t(12) * boxes;
  for (int l = 0; l < 4; ++l) n += size_t(spheres[size_t(l)]) * icosphere_triangles(l + 1);
  return n;
}

size_t ScatteredSceneSize::vertex_count() const {
  size_t n = size_t(terrain_x + 1) * (terrain_z + 1) + size_t(8) * boxes;
  for (int l = 0; l < 4; ++l) n += size_t(spheres[size_t(l)]) * icosphere_vertices(l + 1);
  return n;
}

Scene make_scattered_scene(const ScatteredSceneSize& size, uint32_t seed, std::string name) {
  MeshBuilder m;
  m.positions.reserve(size.vertex_count());
  m.triangles.reserve(size.triangle_count());
  ACCEL_CHECK(size.terrain_x > 0 && size.terrain_z > 0);
  const uint32_t nx = size.terrain_x, nz = size.terrain_z;
  for (uint32_t z = 0; z <= nz; ++z)
    for (uint32_t x = 0; x <= nx; ++x) {
      const float px = (float(x) / float(nx) - 0.5f) * kScatterWidth, pz = (float(z) / float(nz) - 0.5f) * kScatterDepth;
      m.vertex(Vec3(px, scatter_height(px, pz), pz));
    }
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t x = 0; x < nx; ++x) {
      const uint32_t i = z * (nx + 1) + x;
      m.triangle(i, i + nx + 1, i + 1);
      m.triangle(i + 1, i + nx + 1, i + nx + 2);
    }

  Rng rng(seed);
  ScatterPlacer placer(rng);
  // Boxes stand on the ground (sunk a little into its slope), yawed, up to 6 tall.
  constexpr std::array<UVec3, 12> kBoxFaces = {{{0, 3, 2}, {0, 2, 1}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                                {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}}};
  for (uint32_t b = 0; b < size.boxes; ++b) {
    const auto [x, z] = placer.place();
    const float hw = rng.uniform(0.1f, 1.0f), hd = rng.uniform(0.1f, 1.0f), h = rng.uniform(0.3f, 6.0f);
    const float yaw = 2.0f * std::numbers::pi_v<float> * rng.uniform(), c = cos_f(yaw), sn = sin_f(yaw);
    const float y0 = scatter_height(x, z) - 0.3f;
    const uint32_t base = uint32_t(m.positions.size());
    for (int k = 0; k < 8; ++k) {  // box()'s corners: x high at 1,2,5,6, y at 2,3,6,7, z at 4..7
      const float lx = (k == 1 || k == 2 || k == 5 || k == 6) ? hw : -hw;
      const float ly = (k == 2 || k == 3 || k == 6 || k == 7) ? h : 0.0f;
      const float lz = k >= 4 ? hd : -hd;
      m.vertex(Vec3(x + c * lx - sn * lz, y0 + ly, z + sn * lx + c * lz));
    }
    for (const UVec3& f : kBoxFaces) m.triangle(base + f.x, base + f.y, base + f.z);
  }
  // Icospheres: one unit template per level, scaled (flattened or stretched in y), resting
  // half sunk on the ground or floating up to 25 above it.
  constexpr std::array<std::pair<float, float>, 4> kRadius = {{{0.08f, 0.25f}, {0.2f, 0.6f}, {0.5f, 1.5f}, {1.5f, 4.0f}}};
  for (int level = 1; level <= 4; ++level) {
    MeshBuilder unit;
    unit.icosphere(Vec3(0.0f), 1.0f, level);
    for (uint32_t i = 0; i < size.spheres[size_t(level - 1)]; ++i) {
      const auto [x, z] = placer.place();
      const float r = rng.uniform(kRadius[size_t(level - 1)].first, kRadius[size_t(level - 1)].second);
      const float squash = rng.uniform(0.6f, 1.3f);
      const float lift = rng.uniform() < kFloatingShare ? rng.uniform(2.0f, 25.0f) : 0.0f;
      const Vec3 centre(x, scatter_height(x, z) + 0.5f * r * squash + lift, z);
      const uint32_t base = uint32_t(m.positions.size());
      for (const Vec3& p : unit.positions) m.vertex(centre + r * Vec3(p.x, squash * p.y, p.z));
      for (const UVec3& t : unit.triangles) m.triangle(base + t.x, base + t.y, base + t.z);
    }
  }
  return Scene(std::move(m.positions), std::move(m.triangles), std::move(name));
}

namespace {

struct ProceduralEntry {
  const char* name;
  const char* description;
  bool large;  ///< too big for the brute-force-checked test suites
};
constexpr std::array<ProceduralEntry, 6> kProcedural = {{
    {"stadium", "teapot in a stadium: a dense 20k-triangle object in a huge sparse room", false},
    {"sphere", "icosphere, 5120 triangles, closed mesh with shared vertices", false},
    {"soup", "10k random triangles in the unit cube (seeded)", false},
    {"cornell", "Cornell-box-like room with two blocks and a ball, mostly axis-aligned", false},
    {"terrain", "heightfield of rolling hills, 1,048,352 triangles (for frame-rate and build-time tests)", true},
    {"huge", "10,000,000 triangles: a 5M-triangle heightfield and 29,400 closed boxes and icospheres (5M) in "
             "clusters and scattered (the huge-scene bench)", true},
}};

}  // namespace

std::vector<std::string> procedural_scene_names(bool include_large) {
  std::vector<std::string> names;
  for (const auto& e : kProcedural)
    if (include_large || !e.large) names.emplace_back(e.name);
  return names;
}

namespace {
/// "trap_pq" -> "pq": the traps' scenes (traps.h), known by name but not listed in
/// procedural_scene_names(), whose scenes the suites iterate; empty for other names.
std::string_view trap_of(std::string_view name) {
  constexpr std::string_view prefix = "trap_";
  return name.starts_with(prefix) ? name.substr(prefix.size()) : std::string_view{};
}
}  // namespace

std::string procedural_scene_description(std::string_view name) {
  for (const auto& e : kProcedural)
    if (name == e.name) return e.description;
  if (!trap_of(name).empty())
    if (auto demo = trap_demo(trap_of(name))) return "trap demonstration: " + demo.value().title;
  return {};
}

Result<Scene> make_procedural_scene(std::string_view name, uint32_t seed) {
  if (name == "sphere") return make_sphere();
  if (name == "soup") return make_soup(seed);
  if (name == "cornell") return make_cornell();
  if (name == "stadium") return make_stadium();
  if (name == "terrain") return make_terrain();
  if (name == "huge") return make_scattered_scene(ScatteredSceneSize{}, seed);
  if (!trap_of(name).empty() && trap_demo(trap_of(name))) return make_trap_scene(trap_of(name));
  std::string valid;
  for (const auto& e : kProcedural) valid += std::string(valid.empty() ? "" : ", ") + e.name;
  for (const std::string& trap : trap_names()) valid += ", trap_" + trap;
  return make_error("unknown procedural scene '" + std::string(name) + "' (valid: " + valid + ")");
}

}  // namespace accel
