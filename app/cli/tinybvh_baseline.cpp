// tinybvh's implementation and the bench's calls into it. This one translation unit is
// compiled with -mavx2 -mfma (app/cli/CMakeLists.txt): BVH8_CPU needs AVX2, and tinybvh's
// implementation (TINYBVH_IMPLEMENTATION) must be defined in exactly one unit, so BVH4_CPU
// shares the flags. bench.cpp calls in only when tinybvh_cpu_supported().
#include "tinybvh_baseline.h"

#include <chrono>
#include <cmath>
#include <vector>

#define TINYBVH_IMPLEMENTATION
#include <tiny_bvh.h>  // from ACCEL_TINYBVH_DIR, a SYSTEM include: its own warnings are not ours

namespace cli {

bool tinybvh_available() { return true; }

struct TinyBvhScene::Impl {
  std::vector<tinybvh::bvhvec4> vertices;  // 3 per triangle; the BVH keeps pointing here
  std::unique_ptr<tinybvh::BVH8_CPU> bvh8;
  std::unique_ptr<tinybvh::BVH4_CPU> bvh4;
};

TinyBvhScene::TinyBvhScene(const float* triangles, size_t triangle_count, TinyBvhLayout layout)
    : impl_(std::make_unique<Impl>()) {
  impl_->vertices.resize(3 * triangle_count);
  for (size_t i = 0; i < 3 * triangle_count; ++i)
    impl_->vertices[i] = tinybvh::bvhvec4(triangles[3 * i], triangles[3 * i + 1], triangles[3 * i + 2], 0.0f);
  if (triangle_count == 0) return;  // tinybvh does not build over nothing: every ray misses
  const auto* v = impl_->vertices.data();
  const auto n = uint32_t(triangle_count);
  const auto start = std::chrono::steady_clock::now();
  switch (layout) {
    case TinyBvhLayout::Bvh8:
      impl_->bvh8 = std::make_unique<tinybvh::BVH8_CPU>();
      impl_->bvh8->Build(v, n);
      break;
    case TinyBvhLayout::Bvh8Hq:
      impl_->bvh8 = std::make_unique<tinybvh::BVH8_CPU>();
      impl_->bvh8->BuildHQ(v, n);
      break;
    case TinyBvhLayout::Bvh4:
      impl_->bvh4 = std::make_unique<tinybvh::BVH4_CPU>();
      impl_->bvh4->Build(v, n);
      break;
  }
  build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

TinyBvhScene::~TinyBvhScene() = default;

size_t TinyBvhScene::memory_bytes() const {
  // Both layouts count usedBlocks in 64-byte cache lines (BVH8_CPU/BVH4_CPU::ConvertFrom).
  if (impl_->bvh8) return size_t(impl_->bvh8->usedBlocks) * 64;
  if (impl_->bvh4) return size_t(impl_->bvh4->usedBlocks) * 64;
  return 0;
}

TinyBvhHit TinyBvhScene::intersect(const float org[3], const float dir[3], float tmax) const {
  if (!impl_->bvh8 && !impl_->bvh4) return {};
  tinybvh::Ray ray;  // not the (origin, direction) constructor: it normalises the direction
  ray.O = tinybvh::bvhvec3(org[0], org[1], org[2]);
  ray.D = tinybvh::bvhvec3(dir[0], dir[1], dir[2]);
  ray.rD = tinybvh::tinybvh_rcp(ray.D);
  const float t_start = std::isinf(tmax) ? BVH_FAR : tmax;
  ray.hit.t = t_start;
  ray.hit.u = ray.hit.v = 0.0f;
  ray.hit.prim = 0;
  if (impl_->bvh8)
    impl_->bvh8->Intersect(ray);
  else
    impl_->bvh4->Intersect(ray);
  if (!(ray.hit.t < t_start)) return {};
  return {int32_t(ray.hit.prim), ray.hit.t, ray.hit.u, ray.hit.v};
}

}  // namespace cli
