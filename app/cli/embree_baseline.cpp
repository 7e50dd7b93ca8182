#include "embree_baseline.h"

#include <atomic>
#include <chrono>

#include <embree3/rtcore.h>

namespace cli {

bool embree_available() { return true; }

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::atomic<ssize_t> bytes{0};
};

namespace {
// Embree reports its allocations through this callback: that is its memory figure.
bool memory_monitor(void* user, ssize_t bytes, bool) {
  static_cast<std::atomic<ssize_t>*>(user)->fetch_add(bytes);
  return true;
}
}  // namespace

EmbreeScene::EmbreeScene(const accel::Scene& scene, const std::string& quality, int threads)
    : impl_(std::make_unique<Impl>()) {
  // Without "threads=N" Embree builds on every core whatever --threads says.
  const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : std::string();
  impl_->device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  rtcSetDeviceMemoryMonitorFunction(impl_->device, memory_monitor, &impl_->bytes);
  const auto start = std::chrono::steady_clock::now();
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, quality == "high" ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
  if (quality == "robust") rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  if (scene.triangle_count() > 0) {
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, quality == "high" ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
    // Embree may read 16 bytes from the last vertex: pad the buffer by one element.
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), scene.vertex_count() + 1));
    for (size_t i = 0; i < scene.vertex_count(); ++i) {
      v[3 * i] = scene.positions()[i].x;
      v[3 * i + 1] = scene.positions()[i].y;
      v[3 * i + 2] = scene.positions()[i].z;
    }
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), scene.triangle_count()));
    for (size_t i = 0; i < scene.triangle_count(); ++i)
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = scene.triangles()[i][k];
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  build_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

EmbreeScene::~EmbreeScene() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

size_t EmbreeScene::memory_bytes() const { return size_t(std::max<ssize_t>(0, impl_->bytes.load())); }

accel::Hit EmbreeScene::intersect(const accel::Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = ray.org.x;
  rh.ray.org_y = ray.org.y;
  rh.ray.org_z = ray.org.z;
  rh.ray.dir_x = ray.dir.x;
  rh.ray.dir_y = ray.dir.y;
  rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.mask = ~0u;
  rh.ray.flags = 0;
  rh.ray.time = 0.0f;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  return {int32_t(rh.hit.primID), rh.ray.tfar, rh.hit.u, rh.hit.v};
}

}  // namespace cli
