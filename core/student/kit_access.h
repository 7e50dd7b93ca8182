#pragma once
// The kit's side of student/accelviz_student.h: turns the core's scene and rays into the
// student's types. Only core/student/ uses it. The worker (accelviz-worker) has geometry.h
// but not the core's Scene: the scene arrives as triangles (fill_scene's first form).
#include <vector>

#include "accelviz_student.h"
#include "geometry.h"

namespace accel {
class Scene;
}

namespace accelviz {

struct KitAccess {
  /// The student's scene from its triangles, their zero-area flags, the box around them all
  /// and whether it is a blackboard scene.
  static void fill_scene(Scene& out, std::vector<Triangle> triangles, std::vector<unsigned char> degenerate,
                         const Box& bounds, bool planar);
  /// The student's view of `scene`: every triangle (degenerate ones flagged) and its box
  /// (kit_structure.cpp: the core's side only).
  static void fill_scene(Scene& out, const accel::Scene& scene);
  /// The triangle test `ray` was prepared for (Watertight, Moller, Planar...).
  static accel::Kernel kernel(const Ray& ray);
  /// `r` prepared for the kit's tests with `kernel` (the structure's: Planar over a 2D scene).
  static Ray make_ray(const accel::Ray& r, accel::Kernel kernel);
  static Box to_box(const accel::Aabb& b);
  static accel::Aabb to_aabb(const Box& b);
};

}  // namespace accelviz
