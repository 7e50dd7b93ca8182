#pragma once
// The BVH builders shared by the AABB tree (bvh) and the sphere tree (spheretree): each
// produces the same binary topology over the scene's triangles (bvh_build_types.h); the
// structure then fits its bounding volumes (boxes or spheres) to it and flattens it. Every
// builder is its own file pair (bvh_<name>_builder.h/.cpp) and one row of the table below,
// which names it everywhere: the parameter's choices and help (hierarchy_params.cpp),
// build_bvh_tree()'s dispatch, builder_name(), and the viewer's labels and listings.
#include <span>

#include "structures/bvh_build_types.h"

namespace accel {

/// One line of a builder's construction listing (the viewer's pseudo code): the recorded
/// step it stands for (a BuildEventKind's name, "" for none) and its text.
struct ListingLine {
  const char* anchor;
  const char* text;
};

/// A builder's construction listing, in the lecture's words. A top-down builder lists how
/// it chooses the split; the viewer puts the one recursion's lines around it (build(objects):
/// ... build(left); build(right), the leaf). A bottom-up builder lists its whole loop. The
/// hierarchies' common tail (collapse, fit the volumes) follows either.
struct BuilderListing {
  const char* title;  ///< "BVH: top-down, binned SAH"
  std::span<const ListingLine> lines;
};

/// One builder: its row in the table.
struct BvhBuilderInfo {
  BvhBuilderKind kind;
  const char* name;   ///< the `builder` parameter's value: "median", "sah", ...
  const char* label;  ///< short label the viewer shows: "SAH sweep"
  const char* help;   ///< its phrase in the parameter's help: "SAH plane sweep on all axes"
  /// Spatial splits: a triangle may be referenced by several leaves (tests that compare trees
  /// or count references treat these apart; their own tests cover them).
  bool splits_triangles;
  /// A splitter of the one top-down recursion (bvh_top_down.h); false: bottom-up (clusters
  /// merged, or objects inserted one by one), whose depth limit is a rebuild of the tree.
  bool top_down;
  /// Its construction listing, beside its row (a row without one does not compile: the
  /// build function would land here).
  const BuilderListing* listing;
  /// build_bvh_tree()'s contract for this builder.
  BuildTree (*build)(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                     BuildRecorder* recorder);
};

/// Every builder, in the order the parameter lists them: the built-in rows, then any added
/// by add_bvh_builder().
std::span<const BvhBuilderInfo> bvh_builder_table();
/// Adds a builder from outside the core, such as a test's own (tests/test_bvh_custom_builder.cpp;
/// docs/structures.md, "Adding a BVH builder"): its row goes after the others, with the next
/// free kind, which is returned (row.kind is ignored). Only before the table is first read,
/// i.e. at static initialisation: the table is then fixed, so the `builder` parameter and
/// every reader see the same rows.
BvhBuilderKind add_bvh_builder(BvhBuilderInfo row);
/// The row of `kind`.
const BvhBuilderInfo& bvh_builder(BvhBuilderKind kind);

/// The builder's parameter name: "median", "sah", ... (the declaration is hierarchy_params.h).
const char* builder_name(BvhBuilderKind kind);

}  // namespace accel
