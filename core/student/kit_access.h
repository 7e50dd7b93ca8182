#pragma once
// The kit's side of student/accelviz_student.h: turns the core's scene and rays into the
// student's types. Only core/student/ uses it.
#include "accelviz_student.h"
#include "geometry.h"
#include "scene.h"

namespace accelviz {

struct KitAccess {
  /// The student's view of `scene`: every triangle (degenerate ones flagged) and its box.
  static void fill_scene(Scene& out, const accel::Scene& scene);
  /// `r` prepared for the kit's tests with `kernel` (the structure's: Planar over a 2D scene).
  static Ray make_ray(const accel::Ray& r, accel::Kernel kernel);
  static Box to_box(const accel::Aabb& b);
  static accel::Aabb to_aabb(const Box& b);
};

}  // namespace accelviz
