#pragma once
// Spatial-split BVH builder (builder=sbvh), after Stich, Friedrich & Dietrich 2009, "Spatial
// Splits in Bounding Volume Hierarchies": at each node the binned SAH object split of the
// binned builder (bvh_binned_detail.h) and, where that split's children overlap, a spatial
// split -- a plane that cuts the triangles straddling it into two references, each with the
// box of its triangle's part on its side. A triangle can then be in several leaves.
#include "structures/bvh_build_types.h"

namespace accel {

/// Builds the spatial-split tree over scene.valid_prims() with the guarantees of
/// build_bvh_tree() (the sbvh clause: a triangle may be in several leaves, never twice in
/// one). At most options.sbvh_budget references per triangle in total; a node of n
/// references bins its object split into min(bins, 4 + n / 4) bins per axis as the binned
/// builder does, its spatial split into min(kSpatialBins, 4 + n / 2) over the node's box. Parallel (TBB tasks for the upper levels);
/// the tree does not depend on the thread count. With a `recorder` the build runs serially
/// and records every step (build_trace.h): spatial splits are Split steps with values[1] = 1
/// and count = the references that went to both sides.
BuildTree build_spatial_split_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress = nullptr,
                                   BuildRecorder* recorder = nullptr);

/// Spatial bins per axis of a node's spatial split (Stich et al. and Embree use 32 to 256).
inline constexpr int kSpatialBins = 32;

/// The two references a spatial split makes of one: the boxes of the triangle's parts on
/// either closed side of the plane, each intersected with the reference's box.
struct TriangleSplit {
  Aabb left, right;
  bool has_left = false;   ///< false: no point of the triangle inside `box` is left of the plane (left is empty)
  bool has_right = false;  ///< likewise on the right
};

/// Clips triangle (v0, v1, v2) against the plane x[axis] = pos. The boxes are conservative:
/// the polygon on each side is clipped in double precision, the edge crossings rounded
/// outward to float (with their double rounding error), and the result intersected with
/// `box` (never larger than it). For a reference whose `box` contains its triangle's part
/// inside the reference's region, `left` contains that part left of the plane, `right` the
/// part right of it (a point on the plane is in both); a side is empty only when no such
/// point exists. A triangle lying in the plane has both sides.
TriangleSplit split_triangle_box(const Vec3& v0, const Vec3& v1, const Vec3& v2, const Aabb& box, int axis, float pos);

}  // namespace accel
