// Built instead of tinybvh_baseline.cpp when CMake finds no tiny_bvh.h (ACCEL_TINYBVH_DIR):
// the bench then has no tinybvh rows.
#include "tinybvh_baseline.h"

namespace cli {

bool tinybvh_available() { return false; }

struct TinyBvhScene::Impl {};

TinyBvhScene::TinyBvhScene(const float*, size_t, TinyBvhLayout) {}
TinyBvhScene::~TinyBvhScene() = default;
size_t TinyBvhScene::memory_bytes() const { return 0; }
TinyBvhHit TinyBvhScene::intersect(const float*, const float*, float) const { return {}; }

}  // namespace cli
