// Built instead of embree_baseline.cpp when libembree-dev is absent: the bench then leaves
// the Embree rows and ratio column empty.
#include "embree_baseline.h"

namespace cli {

bool embree_available() { return false; }

struct EmbreeScene::Impl {};

EmbreeScene::EmbreeScene(const accel::Scene&, const std::string&, int) {}
EmbreeScene::~EmbreeScene() = default;
size_t EmbreeScene::memory_bytes() const { return 0; }
accel::Hit EmbreeScene::intersect(const accel::Ray&) const { return {}; }

}  // namespace cli
