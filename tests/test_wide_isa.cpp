// The 8-wide BVH's kernels per instruction set (structures/wide_bvh_isa.h): every kernel
// this CPU runs takes the SSE2 kernel's box decisions bit for bit, and the traversals they
// drive visit the same nodes in the same order, so the fast path (AVX2 / AVX-512 on this
// machine) is the query the viewer animates (SSE2, recorded).
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <vector>

#include "isa.h"
#include "random.h"
#include "registry.h"
#include "scene.h"
#include "structures/wide_bvh_isa.h"
#include "trace.h"

namespace accel {
namespace {

std::vector<Isa> vector_isas() {
  std::vector<Isa> isas;
  for (Isa isa : {Isa::Avx2, Isa::Avx512})
    if (cpu_runs(isa)) isas.push_back(isa);
  return isas;
}

/// A coordinate that is often one of a few shared values, so rays start on box faces and
/// slabs are flat or touch.
float tricky(Rng& rng, const float* shared, int n) {
  const float pick = rng.uniform();
  if (pick < 0.3f) return shared[int(rng.uniform() * float(n)) % n];
  return rng.uniform(-2.0f, 2.0f);
}

TEST(WideIsa, NamesRoundTripAndTheBaselineAlwaysRuns) {
  for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) EXPECT_EQ(parse_isa(isa_name(isa)), isa);
  EXPECT_FALSE(parse_isa("neon"));
  EXPECT_TRUE(cpu_runs(Isa::Sse2));
  EXPECT_TRUE(cpu_runs(active_isa()));
}

TEST(WideIsa, BoxDecisionsAreTheSse2KernelsBitForBit) {
  const std::vector<Isa> isas = vector_isas();
  if (isas.empty()) GTEST_SKIP() << "this CPU runs neither AVX2 nor AVX-512";
  Rng rng(2026);
  const float shared[] = {0.0f, -0.0f, 1.0f, -1.0f, 0.5f};
  int hits = 0, lanes = 0;
  for (int iter = 0; iter < 40000; ++iter) {
    WideNode8 node;
    for (int s = 0; s < 8; ++s) {
      const float kind = rng.uniform();
      for (int axis = 0; axis < 3; ++axis) {
        float lo = tricky(rng, shared, 5), hi = tricky(rng, shared, 5);
        if (lo > hi) std::swap(lo, hi);
        if (kind < 0.1f) lo = hi;  // flat box
        if (kind > 0.9f) {         // unused slot: the empty box every ray misses
          lo = kInf;
          hi = -kInf;
        }
        node.bounds[axis][s] = lo;
        node.bounds[3 + axis][s] = hi;
      }
      node.ref[s] = 0;
    }
    Ray ray;
    for (int axis = 0; axis < 3; ++axis) {
      ray.org[axis] = tricky(rng, shared, 5);
      const float d = rng.uniform();
      ray.dir[axis] = d < 0.1f ? 0.0f : d < 0.2f ? -0.0f : rng.uniform(-1.0f, 1.0f);
    }
    if (ray.dir == Vec3(0.0f)) ray.dir.x = 1.0f;
    const float tmin = rng.uniform() < 0.5f ? 0.0f : rng.uniform(0.0f, 1.0f);
    const float tmax = rng.uniform() < 0.5f ? kInf : rng.uniform(tmin, 4.0f);
    const BoxTester box_ray(ray);
    float base0[8], base1[8];
    const int base = wide8_children_mask(Isa::Sse2, node, box_ray, tmin, tmax, base0, base1);
    // The SSE2 kernel is the binary tree's slab test, slot by slot.
    for (int s = 0; s < 8; ++s) {
      Aabb box;
      box.min = Vec3(node.bounds[0][s], node.bounds[1][s], node.bounds[2][s]);
      box.max = Vec3(node.bounds[3][s], node.bounds[4][s], node.bounds[5][s]);
      float t0, t1;
      ASSERT_EQ(bool((base >> s) & 1), box_ray.intersect(box, tmin, tmax, &t0, &t1)) << "iter " << iter;
      ++lanes;
    }
    hits += std::popcount(unsigned(base));
    for (Isa isa : isas) {
      float t0[8], t1[8];
      const int mask = wide8_children_mask(isa, node, box_ray, tmin, tmax, t0, t1);
      ASSERT_EQ(mask, base) << isa_name(isa) << " iter " << iter;
      ASSERT_EQ(std::memcmp(t0, base0, sizeof t0), 0) << isa_name(isa) << " iter " << iter;
      ASSERT_EQ(std::memcmp(t1, base1, sizeof t1), 0) << isa_name(isa) << " iter " << iter;
    }
  }
  // Both outcomes are well represented.
  EXPECT_GT(hits, lanes / 20);
  EXPECT_LT(hits, lanes * 9 / 10);
}

bool same_events(const std::vector<TraceEvent>& a, const std::vector<TraceEvent>& b, std::string* why) {
  if (a.size() != b.size()) {
    *why = "step counts " + std::to_string(a.size()) + " and " + std::to_string(b.size());
    return false;
  }
  for (size_t i = 0; i < a.size(); ++i) {
    const TraceEvent &x = a[i], &y = b[i];
    if (x.kind != y.kind || x.reason != y.reason || x.hit != y.hit || x.depth != y.depth || x.node != y.node ||
        x.prim != y.prim || std::bit_cast<uint32_t>(x.t0) != std::bit_cast<uint32_t>(y.t0) ||
        std::bit_cast<uint32_t>(x.t1) != std::bit_cast<uint32_t>(y.t1)) {
      *why = "step " + std::to_string(i) + ": " + describe_event(x) + " / " + describe_event(y);
      return false;
    }
  }
  return true;
}

TEST(WideIsa, EveryKernelVisitsTheSameNodesInTheSameOrder) {
  const std::vector<Isa> isas = vector_isas();
  for (const char* scene_name : {"soup", "cornell", "stadium"}) {
    const Scene scene = make_procedural_scene(scene_name).value();
    for (const char* order : {"ordered", "dfs", "pqueue"}) {
      auto built = build_structure("bvh", scene, {"width=8", std::string("traversal=") + order});
      ASSERT_TRUE(built);
      const auto* bvh = dynamic_cast<const WideBvh8*>(built.value().get());
      ASSERT_NE(bvh, nullptr);
      Rng rng(17);
      const Aabb box = scene.bounds();
      for (int i = 0; i < 1500; ++i) {
        Ray r;
        r.org = box.center() + box.extent() * Vec3(rng.uniform(-0.7f, 0.7f), rng.uniform(-0.7f, 0.7f),
                                                   rng.uniform(-0.7f, 0.7f));
        r.dir = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        if (i % 7 == 0) r.dir[i % 3] = 0.0f;  // axis-parallel planes: NaN-prone slabs
        // The viewer's recording (SSE2 kernels, TraceRecorder inline) ...
        TraceRecorder viewer;
        const Hit shown = built.value()->intersect_traced(r, viewer);
        // ... equals each kernel's steps, and the fast path's answer.
        const Hit fast = built.value()->intersect(r);
        ASSERT_EQ(fast.prim, shown.prim) << scene_name << " " << order << " ray " << i;
        ASSERT_EQ(std::bit_cast<uint32_t>(fast.t), std::bit_cast<uint32_t>(shown.t));
        for (Isa isa : {Isa::Sse2, Isa::Avx2, Isa::Avx512}) {
          if (!cpu_runs(isa)) continue;
          TraceRecorder steps;
          RecordingListener listener(steps);
          const Hit h = wide8_traverse_observed(isa, *bvh, r, listener);
          ASSERT_EQ(h.prim, shown.prim) << isa_name(isa);
          std::string why;
          ASSERT_TRUE(same_events(viewer.events(), steps.events(), &why))
              << scene_name << " " << order << " ray " << i << " " << isa_name(isa) << ": " << why;
        }
      }
    }
  }
  if (isas.empty()) GTEST_SKIP() << "only the SSE2 kernel runs here: compared with itself";
}

TEST(WideIsa, BatchesAnswerAsOneRayAtATime) {
  const std::vector<Isa> isas = vector_isas();
  if (isas.empty()) GTEST_SKIP() << "this CPU runs neither AVX2 nor AVX-512";
  const Scene scene = make_procedural_scene("stadium").value();
  auto built = build_structure("bvh", scene, {"width=8"});
  ASSERT_TRUE(built);
  const auto& bvh = dynamic_cast<const WideBvh8&>(*built.value());
  Rng rng(5);
  const Aabb box = scene.bounds();
  std::vector<Ray> rays(1000);
  for (size_t i = 0; i < rays.size(); ++i) {
    rays[i].org = box.center() + box.extent() * Vec3(rng.uniform(-0.7f, 0.7f), rng.uniform(-0.7f, 0.7f),
                                                     rng.uniform(-0.7f, 0.7f));
    rays[i].dir = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    if (i % 7 == 0) rays[i].dir[i % 3] = 0.0f;
    if (i % 5 == 0) rays[i].tmin = rng.uniform(0.0f, 0.5f);
  }
  for (Isa isa : isas) {
    std::vector<Hit> batch(rays.size());
    // Uneven batches, one of a single ray and one empty among them.
    const auto batch_of = isa == Isa::Avx2 ? wide8_fast_batch_avx2 : wide8_fast_batch_avx512;
    const auto one_of = isa == Isa::Avx2 ? wide8_fast_avx2 : wide8_fast_avx512;
    for (size_t i = 0, n = 0; i < rays.size(); i += n, n = (n * 7 + 3) % 97)
      batch_of(bvh, rays.data() + i, std::min(n, rays.size() - i), batch.data() + i);
    int hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      const Hit one = one_of(bvh, rays[i]);
      ASSERT_EQ(batch[i].prim, one.prim) << isa_name(isa) << " ray " << i;
      ASSERT_EQ(std::bit_cast<uint32_t>(batch[i].t), std::bit_cast<uint32_t>(one.t)) << isa_name(isa) << " ray " << i;
      ASSERT_EQ(std::bit_cast<uint32_t>(batch[i].u), std::bit_cast<uint32_t>(one.u));
      ASSERT_EQ(std::bit_cast<uint32_t>(batch[i].v), std::bit_cast<uint32_t>(one.v));
      hits += one.valid();
    }
    EXPECT_GT(hits, 100);
  }
}

TEST(WideIsa, EightWideTreesRunTheBestKernelOnStackOrders) {
  const Scene scene = make_procedural_scene("cornell").value();
  auto ordered = build_structure("bvh", scene, {"width=8"});
  auto queue = build_structure("bvh", scene, {"width=8", "traversal=pqueue"});
  auto four = build_structure("bvh", scene, {"width=4"});
  ASSERT_TRUE(ordered && queue && four);
  EXPECT_EQ(dynamic_cast<const WideBvh8&>(*ordered.value()).fast_isa(), active_isa());
  EXPECT_EQ(dynamic_cast<const WideBvh8&>(*queue.value()).fast_isa(), Isa::Sse2);
  EXPECT_EQ(dynamic_cast<const WideBvh&>(*four.value()).fast_isa(), Isa::Sse2);
  bool reported = false;
  for (const auto& [key, value] : ordered.value()->build_stats().extra)
    if (key == "kernel isa") reported = value == isa_name(active_isa());
  EXPECT_TRUE(reported);
}

}  // namespace
}  // namespace accel
