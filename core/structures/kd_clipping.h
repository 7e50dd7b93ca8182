#pragma once
// Perfect splits for the kd-tree builder: the bounds of the part of a triangle inside a
// node's region, so a straddling triangle's events (and the SAH counts) describe only what
// lies on each side of a split, not its whole box.
#include <cstdint>

#include "scene.h"

namespace accel::kd {

/// Bounds of the part of triangle `prim` inside the closed box `box`, for perfect splits
/// (Havran 2000; Wald & Havran 2006 sec. 4.3): Sutherland-Hodgman clipping against the six
/// slabs, in double. Conservative both ways rounding could hurt:
///  * the box is enlarged by delta = 2^-30 of the largest coordinate involved (far above the
///    double rounding of the clip, far below a float ulp), so a triangle touching the box is
///    never clipped away;
///  * the polygon's bounds are widened by delta and rounded outward to float, then cut to
///    the triangle's own box and to `box` (both exact bounds of the true clipped part).
/// Returns false only when the triangle certainly misses the box.
bool clip_triangle_bounds(const Scene& scene, uint32_t prim, const Aabb& box, Aabb* out);

}  // namespace accel::kd
