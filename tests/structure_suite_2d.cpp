// The suite's 2D part (issue #32; docs/hits.md, "2D scenes"): every structure x option, built
// over 2D scenes by the same builders as in 3D, answers every 2D ray exactly like the 2D
// brute force (reference_closest() over a planar scene): on random triangles and on a
// triangulated lattice whose rays run along cell and split lines, along edges and through
// shared vertices, and from inside triangles. Recording changes no answer.
#include "structure_suite.h"

#include "accuracy.h"
#include "batch.h"
#include "random.h"
#include "registry.h"
#include "trace.h"

namespace accel::testing {
namespace {

Ray ray2d(Vec3 o, Vec3 d) {
  Ray r;
  r.org = Vec3(o.x, o.y, 0.0f);
  r.dir = Vec3(d.x, d.y, 0.0f);
  return r;
}

Scene planar_scene(std::vector<Vec3> p, std::vector<UVec3> t, const char* name) {
  Scene scene(std::move(p), std::move(t), name);
  EXPECT_TRUE(scene.mark_planar());
  return scene;
}

/// 200 random triangles of sizes 1 to 15 in [0, 100]^2, overlapping.
Scene random_triangles() {
  Rng rng(32);
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (uint32_t i = 0; i < 200; ++i) {
    const float cx = rng.uniform(0.0f, 100.0f), cy = rng.uniform(0.0f, 100.0f), size = rng.uniform(1.0f, 15.0f);
    for (int k = 0; k < 3; ++k) {
      const float dx = rng.uniform(-size, size), dy = rng.uniform(-size, size);
      p.emplace_back(cx + dx, cy + dy, 0.0f);
    }
    t.emplace_back(3 * i, 3 * i + 1, 3 * i + 2);
  }
  return planar_scene(std::move(p), std::move(t), "2d:random");
}

/// A 10 x 10 lattice of unit squares on integer coordinates, every other square cut into two
/// triangles along one diagonal (shared edges and vertices everywhere), the rest empty.
Scene lattice() {
  std::vector<Vec3> p;
  std::vector<UVec3> t;
  for (int y = 0; y <= 10; ++y)
    for (int x = 0; x <= 10; ++x) p.emplace_back(float(x), float(y), 0.0f);
  auto id = [](int x, int y) { return uint32_t(y * 11 + x); };
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      if ((x + y) % 3 == 2) continue;
      t.emplace_back(id(x, y), id(x + 1, y), id(x + 1, y + 1));
      t.emplace_back(id(x, y), id(x + 1, y + 1), id(x, y + 1));
    }
  return planar_scene(std::move(p), std::move(t), "2d:lattice");
}

/// Random rays from around the scene's box; axis-parallel rays along every integer line
/// (the lattice's edges, the structures' cell and split lines) both ways; rays from vertex
/// to vertex (through shared vertices, along edges and diagonals); rays from inside.
std::vector<Ray> rays_for(const Scene& scene, uint32_t seed) {
  Rng rng(seed);
  const Aabb b = scene.bounds();
  const Vec3 lo = b.min - Vec3(10.0f), hi = b.max + Vec3(10.0f);
  std::vector<Ray> rays;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 o(rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), 0.0f);
    const Vec3 target(rng.uniform(b.min.x, b.max.x), rng.uniform(b.min.y, b.max.y), 0.0f);
    if (target != o) rays.push_back(ray2d(o, target - o));
  }
  for (int k = int(std::floor(b.min.x)) - 1; k <= int(std::ceil(b.max.x)) + 1; ++k) {
    const float c = float(k);
    rays.push_back(ray2d({c, lo.y, 0}, {0, 1, 0}));
    rays.push_back(ray2d({c, hi.y, 0}, {0, -1, 0}));
    rays.push_back(ray2d({lo.x, c, 0}, {1, 0, 0}));
    rays.push_back(ray2d({hi.x, c, 0}, {-1, 0, 0}));
  }
  const size_t prims = scene.triangle_count();
  for (int i = 0; i < 600 && prims > 0; ++i) {
    const uint32_t a = uint32_t(rng.next_u64() % prims), c = uint32_t(rng.next_u64() % prims);
    const Vec3 from = scene.vertex(a, int(rng.next_u64() % 3)), to = scene.vertex(c, int(rng.next_u64() % 3));
    if (from == to) continue;
    rays.push_back(ray2d(from, to - from));                         // starts on a vertex
    rays.push_back(ray2d(from - (to - from), 2.0f * (to - from)));  // passes through both
    const Vec3 centroid = scene.centroid(a);
    rays.push_back(ray2d(centroid, to - centroid));                 // starts inside
  }
  return rays;
}

TEST_P(StructureVsReference, SameHitsAsThe2dBruteForce) {
  const SuiteCase& c = GetParam();
  for (const Scene& scene : {random_triangles(), lattice()}) {
    SCOPED_TRACE(scene.name());
    auto built = build_structure(c.structure, scene, c.params);
    ASSERT_TRUE(built) << built.error().message;
    const Structure& s = *built.value();
    EXPECT_EQ(s.kernel(), Kernel::Planar);
    const std::vector<Ray> rays = rays_for(scene, 5);
    const std::vector<Hit> hits = trace_all(s, rays);
    size_t wrong = 0, hit = 0;
    std::string first;
    for (size_t i = 0; i < rays.size(); ++i) {
      if (i % 7 == 0) {  // recording changes nothing
        TraceRecorder rec;
        const Hit traced = s.intersect_traced(rays[i], rec);
        ASSERT_EQ(traced.prim, hits[i].prim) << "ray " << i;
        ASSERT_EQ(traced.t, hits[i].t) << "ray " << i;
      }
      const ReferenceHit ref = reference_closest(scene, rays[i]);
      hit += ref.prim >= 0;
      const HitVerdict verdict = judge_hit(scene, rays[i], hits[i], ref);
      if (verdict == HitVerdict::Correct) continue;
      if (wrong++ == 0)
        first = "ray " + std::to_string(i) + " (" + std::to_string(rays[i].org.x) + ", " +
                std::to_string(rays[i].org.y) + ") + t (" + std::to_string(rays[i].dir.x) + ", " +
                std::to_string(rays[i].dir.y) + "): " + verdict_name(verdict) + ", got " +
                std::to_string(hits[i].prim) + " at " + std::to_string(hits[i].t) + ", reference " +
                std::to_string(ref.prim) + " at " + std::to_string(ref.t);
    }
    EXPECT_EQ(wrong, 0u) << "of " << rays.size() << " rays; first: " << first;
    EXPECT_GT(hit, rays.size() / 2);  // most rays meet a triangle: the comparison has teeth
  }
}

}  // namespace
}  // namespace accel::testing
