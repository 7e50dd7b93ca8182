// The assignment kit's functions (student/accelviz_student.h) over the core's own tests, so
// a student structure answers by exactly the rule the built-in ones do.
#include <new>
#include <type_traits>

#include "accelviz_student.h"
#include "student/kit_access.h"

namespace accelviz {
namespace {

/// What Ray::kit_prepared holds: the core's per-ray constants of the triangle and slab tests.
struct Prepared {
  accel::TriangleTester triangle;
  accel::BoxTester box;
};
static_assert(sizeof(Prepared) <= sizeof(Ray::kit_prepared), "Ray::kit_prepared must hold the testers");
static_assert(alignof(Prepared) <= 16 && std::is_trivially_copyable_v<Prepared> &&
                  std::is_trivially_destructible_v<Prepared>,
              "the testers are plain bytes, copied with the ray");

const Prepared& prepared(const Ray& ray) { return *std::launder(reinterpret_cast<const Prepared*>(ray.kit_prepared)); }

accel::Vec3 to_core(Vec3 v) { return {v.x, v.y, v.z}; }

}  // namespace

Ray make_ray(Vec3 origin, Vec3 direction, float tmin, float tmax) {
  accel::Ray r;
  r.org = to_core(origin);
  r.dir = to_core(direction);
  r.tmin = tmin;
  r.tmax = tmax;
  return KitAccess::make_ray(r, accel::Kernel::Watertight);
}

Ray KitAccess::make_ray(const accel::Ray& r, accel::Kernel kernel) {
  Ray ray;
  ray.origin = {r.org.x, r.org.y, r.org.z};
  ray.direction = {r.dir.x, r.dir.y, r.dir.z};
  ray.tmin = r.tmin;
  ray.tmax = r.tmax;
  const accel::BoxTester box(r);
  ray.inv_direction = {box.inv_dir.x, box.inv_dir.y, box.inv_dir.z};
  new (ray.kit_prepared) Prepared{accel::TriangleTester(r, kernel), box};
  return ray;
}

void KitAccess::fill_scene(Scene& out, std::vector<Triangle> triangles, std::vector<unsigned char> degenerate,
                           const Box& bounds, bool planar) {
  out.boxes_.resize(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i) out.boxes_[i] = triangles[i].box();
  out.triangles_ = std::move(triangles);
  degenerate.resize(out.triangles_.size(), 0);
  out.degenerate_ = std::move(degenerate);
  out.bounds_ = bounds;
  out.planar_ = planar;
}

accel::Kernel KitAccess::kernel(const Ray& ray) { return prepared(ray).triangle.kernel(); }

Box KitAccess::to_box(const accel::Aabb& b) { return Box{{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}; }
accel::Aabb KitAccess::to_aabb(const Box& b) {
  accel::Aabb a;
  if (!b.empty()) a = accel::Aabb{to_core(b.lo), to_core(b.hi)};
  return a;
}

bool intersect_triangle(const Ray& ray, const Scene& scene, uint32_t prim, float t_max, Hit& hit) {
  if (prim >= scene.size() || scene.is_degenerate(prim)) return false;
  const Triangle& t = scene.triangle(prim);
  accel::TriangleHit th{kInfinity, 0.0f, 0.0f};
  if (!prepared(ray).triangle.intersect(to_core(t.v0), to_core(t.v1), to_core(t.v2), t_max, &th)) return false;
  hit = Hit{int32_t(prim), th.t, th.u, th.v};
  return true;
}

bool intersect_box(const Ray& ray, const Box& box, float t_min, float t_max, float& t_enter, float& t_exit) {
  if (box.empty()) return false;
  return prepared(ray).box.intersect(KitAccess::to_aabb(box), t_min, t_max, &t_enter, &t_exit);
}

bool intersect_sphere(const Ray& ray, const Sphere& sphere, float t_min, float t_max, float& t_enter, float& t_exit) {
  if (sphere.radius < 0.0f) return false;
  accel::Ray r;
  r.org = to_core(ray.origin);
  r.dir = to_core(ray.direction);
  r.tmin = ray.tmin;
  r.tmax = ray.tmax;
  return accel::intersect_sphere(r, accel::BoundingSphere{to_core(sphere.center), sphere.radius}, t_min, t_max,
                                 &t_enter, &t_exit);
}

bool test_triangle(const Ray& ray, const Scene& scene, uint32_t prim, Hit& closest, TraversalLog log) {
  Hit h;
  const bool hit = intersect_triangle(ray, scene, prim, closest.t, h);
  log.triangle_tested(prim, hit, hit ? h.t : kInfinity);
  // The core's rule (structure.h, take_triangle_result): the first hit counts at t == t_max,
  // later ones only when strictly closer, and a triangle never replaces itself.
  if (hit && (closest.prim < 0 || (h.t < closest.t && closest.prim != int32_t(prim)))) {
    closest = h;
    log.new_closest(prim, h.t);
    return true;
  }
  return false;
}

}  // namespace accelviz
