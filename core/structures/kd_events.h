#pragma once
// The kd-tree builder's event lists (Wald & Havran 2006, "On building fast kd-trees for ray
// tracing, and on doing that in O(N log N)", sec. 4.2 and 5.2): every node keeps, per axis,
// the sorted start/end/planar events of its triangles' (clipped) extents; the SAH sweep
// (kd_sah_sweep.h) reads them, and a split distributes them to the children -- filtered,
// the straddlers re-clipped and merged in -- so no node sorts its lists again.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "build_trace.h"
#include "scene.h"

namespace accel::kd {

/// Event types in sweep order: at one position, ends come before planars before starts
/// (Wald & Havran 2006 sec. 4.2), so a triangle ending at a plane counts left only and one
/// starting there right only.
enum EventType : uint32_t { kEnd = 0, kPlanar = 1, kStart = 2 };

/// One boundary of a triangle's (clipped) extent along one axis. 8 bytes: the triangle id
/// and the type share one word (ids < 2^30).
struct Event {
  float pos;
  uint32_t prim_type;  // prim << 2 | type

  /// Leaves both fields unset: resizing a list that a filter then overwrites costs nothing
  /// (a defaulted constructor would be zero-filled by vector::resize first).
  Event() {}
  Event(float p, uint32_t pt) : pos(p), prim_type(pt) {}
  uint32_t prim() const { return prim_type >> 2; }
  uint32_t type() const { return prim_type & 3u; }
};
static_assert(sizeof(Event) == 8);

inline bool event_less(const Event& a, const Event& b) {
  return a.pos < b.pos || (a.pos == b.pos && a.type() < b.type());
}

/// event_less as a type, so std::sort inlines it. The order std::sort leaves equivalent
/// events in (ties of position and type) is part of the result -- the first event of a
/// position gives the split its bits, -0 or +0 -- so every list is sorted by the same
/// std::sort on the same input order as ever.
struct EventLess {
  bool operator()(const Event& a, const Event& b) const { return event_less(a, b); }
};

/// True when some event lies at -0: only then can the order a sort leaves tied events in
/// show in the tree (the first event of a position gives the split its bits, and -0 and +0
/// are one position). Without one, tied events are equal in everything the build reads.
bool has_negative_zero(const std::vector<Event>& list);

/// Sorts `list` by event_less, stably: an LSD radix sort on the position's bits and the
/// type, ~10x std::sort's speed on the root's lists of millions of events. Its tie order is
/// not std::sort's, so the builder uses it only where no tie can show (has_negative_zero()).
/// Takes a second buffer of the list's size while it runs.
void radix_sort_events(std::vector<Event>& list);

/// The events of one node: per axis, sorted by event_less.
struct EventLists {
  std::vector<Event> axis[3];
  size_t size() const { return axis[0].size() + axis[1].size() + axis[2].size(); }
};

/// Appends the events of `prim` with extent `b` (one planar event on an axis where the extent
/// is flat, else an end and a start).
inline void add_events(EventLists& lists, uint32_t prim, const Aabb& b) {
  for (int k = 0; k < 3; ++k) {
    if (b.min[k] == b.max[k]) {
      lists.axis[k].emplace_back(b.min[k], prim << 2 | kPlanar);
    } else {
      lists.axis[k].emplace_back(b.min[k], prim << 2 | kStart);
      lists.axis[k].emplace_back(b.max[k], prim << 2 | kEnd);
    }
  }
}

/// Spare event lists of one thread, handed to the children of the next nodes: most nodes are
/// small, and a malloc and free per list and node cost more than sweeping them. Lists longer
/// than kMaxPooled events are freed instead, which bounds what a pool holds.
class EventPool {
 public:
  /// An empty list, with the capacity of a spare one when there is one.
  std::vector<Event> take() {
    if (spare_.empty()) return {};
    std::vector<Event> list = std::move(spare_.back());
    spare_.pop_back();
    return list;
  }
  /// Takes `list` back (leaving it empty).
  void give(std::vector<Event>& list) {
    if (list.capacity() > 0 && list.capacity() <= kMaxPooled && spare_.size() < kMaxSpare) {
      list.clear();
      spare_.push_back(std::move(list));
    }
    list = std::vector<Event>();
  }
  void give(EventLists& lists) {
    for (std::vector<Event>& list : lists.axis) give(list);
  }

 private:
  static constexpr size_t kMaxPooled = size_t(1) << 13;  // 64 KiB
  static constexpr size_t kMaxSpare = 256;  // well above the ~3 * (depth + 3) lists alive at once
  std::vector<std::vector<Event>> spare_;
};

/// Where to split a node; axis < 0 = make a leaf.
struct SplitChoice {
  int axis = -1;
  float pos = 0.0f;
  bool planar_left = true;  ///< triangles lying in the plane go left (else right)
};

enum Side : uint8_t { kBoth = 0, kLeft = 1, kRight = 2 };

/// One thread's buffers for classify() and distribute(), reused node after node.
struct DistributeScratch {
  std::vector<uint8_t> side;         ///< per triangle id: Side in the node being split
  std::vector<uint32_t> straddlers;  ///< triangles on both sides
  EventLists fresh[2];               ///< events of re-clipped straddlers, per side
  EventPool pool;
  size_t both = 0;  ///< recorded builds: triangles stored in both children (after clipping)
  /// A straddler's clipped bounds had a -0 (a bound rounded up from within 2^-150 below 0):
  /// a build whose root lists were radix sorted must then be made again with std::sort.
  bool clipped_negative_zero = false;
};

/// The children's events and triangle counts (after clipping).
struct ChildEvents {
  EventLists left, right;
  size_t nl = 0, nr = 0;
};

/// Sides by the split axis' events, consistent with the sweep's counts: extent ending at or
/// before the plane -> left; starting at or after it -> right; lying in it -> the chosen
/// side; crossing it -> both. One pass: a triangle's start precedes its end in the sorted
/// list (a start and an end only for a non-flat extent), so the end can overrule the start.
void classify(DistributeScratch& ws, const EventLists& events, const SplitChoice& s);

/// Wald & Havran 2006 sec. 5.2: the events of one-sided triangles are filtered into the
/// child lists (staying sorted); the straddling triangles are clipped to each child's region
/// (perfect splits) or cut to it (clip=off), their new events sorted -- only these, O(s log s)
/// -- and merged in. This keeps every list sorted without a sort per node: O(N log N). The
/// filter writes each event to both children and advances the side it belongs to, without a
/// branch to mispredict; the merge works in place from the back (merge_fresh()).
/// `clip`: the clip parameter. Instantiated for NullBuildSink and BuildRecorder (which counts
/// ws.both).
template <class Sink>
void distribute(const Scene& scene, bool clip, DistributeScratch& ws, const EventLists& events, const SplitChoice& s,
                const Aabb& box, ChildEvents& d);

}  // namespace accel::kd
