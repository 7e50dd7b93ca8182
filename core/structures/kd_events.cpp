// Distributing a kd-tree node's sorted event lists to its children (lecture, kd-tree:
// "distribute the geometry among the two children; some polygons need to be assigned to
// both"): Wald & Havran 2006, "On building fast kd-trees for ray tracing, and on doing that
// in O(N log N)", sec. 5.2 -- filter, clip the straddlers, merge, never sort a list again.
#include "structures/kd_events.h"

#include <algorithm>
#include "bit_cast.h"
#include "check.h"
#include "radix_sort.h"
#include "structures/kd_builder.h"
#include "structures/kd_clipping.h"

namespace accel::kd {
namespace {

/// Child lists longer than this many events are trimmed to their size (see distribute()).
constexpr size_t kShrinkMin = size_t(1) << 16;

/// Merges the sorted `fresh` events into `list`, whose first `kept` entries are sorted and
/// whose size is at least kept + fresh.size(); leaves exactly the merged kept + fresh. The
/// same sequence as std::merge(kept, fresh) -- on ties the kept event first -- written from
/// the back, so it needs no second buffer and stops when `fresh` is used up.
void merge_fresh(std::vector<Event>& list, size_t kept, const std::vector<Event>& fresh) {
  size_t i = kept, j = fresh.size(), out = kept + fresh.size();
  ACCEL_DCHECK(list.size() >= out);
  Event* dst = list.data();
  while (j > 0 && i > 0) {  // without a branch on the comparison (random)
    const Event f = fresh[j - 1], k = dst[i - 1];
    const bool take_kept = (f.pos < k.pos) | ((f.pos == k.pos) & (f.type() < k.type()));  // event_less(f, k)
    dst[--out] = take_kept ? k : f;
    i -= take_kept;
    j -= !take_kept;
  }
  while (j > 0) dst[--out] = fresh[--j];
  list.resize(kept + fresh.size());
}

/// -0, which compares equal to +0.
bool is_negative_zero(float f) { return bit_cast<uint32_t>(f) == 0x80000000u; }

/// -0 among the bounds of `b`.
bool has_negative_zero(const Aabb& b) {
  bool found = false;
  for (int k = 0; k < 3; ++k) {
    found |= is_negative_zero(b.min[k]);
    found |= is_negative_zero(b.max[k]);
  }
  return found;
}

/// The radix sort's key: the position's bits made to order as unsigned integers (negative
/// floats reversed, positive ones above them), then the type: event_less's order.
uint64_t sort_key(const Event& e) {
  const uint32_t bits = bit_cast<uint32_t>(e.pos);
  const uint32_t ordered = bits ^ ((bits & 0x80000000u) ? 0xffffffffu : 0x80000000u);
  return uint64_t(ordered) << 2 | e.type();
}

}  // namespace

bool has_negative_zero(const std::vector<Event>& list) {
  bool found = false;
  for (const Event& e : list) found |= is_negative_zero(e.pos);
  return found;
}

void radix_sort_events(std::vector<Event>& list) {
  // 34 key bits in four digits of 9 bits: 512 buckets, whose write positions stay in the cache.
  std::vector<Event> scratch;
  radix_sort_stable<34, 9>(list, scratch, sort_key);
}

void classify(DistributeScratch& ws, const EventLists& events, const SplitChoice& s) {
  uint8_t* side = ws.side.data();
  for (const Event& e : events.axis[s.axis]) {
    const uint32_t prim = e.prim();
    switch (e.type()) {
      case kStart: side[prim] = e.pos >= s.pos ? kRight : kBoth; break;
      case kEnd:
        if (e.pos <= s.pos) side[prim] = kLeft;
        break;
      default:  // planar
        side[prim] = e.pos < s.pos || (e.pos == s.pos && s.planar_left) ? kLeft : kRight;
        break;
    }
  }
}

template <class Sink>
void distribute(const Scene& scene, bool clip, DistributeScratch& ws, const EventLists& events, const SplitChoice& s,
                const Aabb& box, ChildEvents& d) {
  EventLists& new_left = ws.fresh[0];
  EventLists& new_right = ws.fresh[1];
  for (int k = 0; k < 3; ++k) {
    new_left.axis[k].clear();
    new_right.axis[k].clear();
  }
  const uint8_t* side = ws.side.data();
  const Aabb box_l = kd_child_box(box, s.axis, s.pos, false), box_r = kd_child_box(box, s.axis, s.pos, true);
  // The triangles by their one start or planar event on axis 0: counted per side, the
  // straddlers listed (in the list's order, as their fresh events are sorted from it).
  std::vector<uint32_t>& straddlers = ws.straddlers;
  if (straddlers.size() < events.axis[0].size()) straddlers.resize(events.axis[0].size());
  size_t nl = 0, nr = 0, straddling = 0;
  if constexpr (Sink::kRecords) ws.both = 0;
  for (const Event& e : events.axis[0]) {
    const uint32_t prim = e.prim();
    const bool first = e.type() != kEnd;
    const uint8_t sd = side[prim];
    nl += first & (sd == kLeft);
    nr += first & (sd == kRight);
    straddlers[straddling] = prim;
    straddling += first & (sd == kBoth);
  }
  for (size_t i = 0; i < straddling; ++i) {
    // The straddlers' triangles are scattered over the scene: fetch ahead what the clip reads.
    if (i + 8 < straddling) {
      __builtin_prefetch(&scene.triangle_bounds(straddlers[i + 8]));
      __builtin_prefetch(&scene.triangles()[straddlers[i + 8]]);
    }
    if (i + 4 < straddling)
      for (int k = 0; k < 3; ++k) __builtin_prefetch(&scene.vertex(straddlers[i + 4], k));
    const uint32_t prim = straddlers[i];
    Aabb b;
    if (clip) {
      const bool in_left = clip_triangle_bounds(scene, prim, box_l, &b);
      if (in_left) add_events(new_left, prim, b), ++nl, ws.clipped_negative_zero |= has_negative_zero(b);
      const bool in_right = clip_triangle_bounds(scene, prim, box_r, &b);
      if (in_right) add_events(new_right, prim, b), ++nr, ws.clipped_negative_zero |= has_negative_zero(b);
      if constexpr (Sink::kRecords) ws.both += in_left && in_right;
    } else {
      const Aabb& tri = scene.triangle_bounds(prim);
      for (const Aabb* child : {&box_l, &box_r}) {
        b.min = glm::max(tri.min, child->min);
        b.max = glm::min(tri.max, child->max);
        add_events(child == &box_l ? new_left : new_right, prim, b);
        ws.clipped_negative_zero |= has_negative_zero(b);
      }
      ++nl, ++nr;
      if constexpr (Sink::kRecords) ++ws.both;
    }
  }
  d.nl = nl;
  d.nr = nr;
  for (int k = 0; k < 3; ++k) {
    const std::vector<Event>& src = events.axis[k];
    std::vector<Event>& fresh_l = new_left.axis[k];
    std::vector<Event>& fresh_r = new_right.axis[k];
    std::sort(fresh_l.begin(), fresh_l.end(), EventLess{});
    std::sort(fresh_r.begin(), fresh_r.end(), EventLess{});
    std::vector<Event>& left = d.left.axis[k];
    std::vector<Event>& right = d.right.axis[k];
    left = ws.pool.take();
    right = ws.pool.take();
    left.resize(src.size() + fresh_l.size());
    right.resize(src.size() + fresh_r.size());
    Event* l = left.data();
    Event* r = right.data();
    size_t kept_l = 0, kept_r = 0;
    for (const Event& e : src) {
      const uint8_t sd = side[e.prim()];
      l[kept_l] = e;
      r[kept_r] = e;
      kept_l += sd == kLeft;
      kept_r += sd == kRight;
    }
    merge_fresh(left, kept_l, fresh_l);
    merge_fresh(right, kept_r, fresh_r);
    // Long lists were sized for every event going to each side; give back what the other
    // side took (a copy of the kept part), as the above list waits through the below subtree.
    for (std::vector<Event>* list : {&left, &right})
      if (list->capacity() > kShrinkMin && list->size() < list->capacity() / 4 * 3) list->shrink_to_fit();
  }
}

template void distribute<NullBuildSink>(const Scene&, bool, DistributeScratch&, const EventLists&, const SplitChoice&,
                                        const Aabb&, ChildEvents&);
template void distribute<BuildRecorder>(const Scene&, bool, DistributeScratch&, const EventLists&,
                                        const SplitChoice&, const Aabb&, ChildEvents&);

}  // namespace accel::kd
