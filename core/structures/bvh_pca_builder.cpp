// PCA sweep (lecture, BVH top-down: "represent all polygons by their midpoints, calculate the
// axis of largest extent using PCA, project all midpoints onto that axis and sort, search the
// minimum of C(B) by plane sweep"). The SAH sweep is MacDonald & Booth 1990's; the axis
// changes per node, so this builder sorts per node (the all-axes sweep of
// bvh_sweep_builder.cpp sorts once). The recursion and its tasks are bvh_top_down.h's.
#include "structures/bvh_pca_builder.h"

#include <numeric>

#include "structures/bvh_top_down.h"

namespace accel {
namespace {

using namespace top_down;

/// Sweeps the n refs base[order[0..n)] in that order: the best split position (reported as
/// begin + i) and its cost. The first minimum wins. `right_area` is scratch. kCosts (recorded
/// builds): costs[i] = the cost of position i, for i in [1, n).
template <bool kCosts = false>
Split sweep_order(const BvhBuildOptions& o, const PrimRef* base, const uint32_t* order, size_t n, size_t begin,
                  float parent_area, std::vector<float>& right_area, [[maybe_unused]] float* costs = nullptr) {
  right_area.resize(n);
  Aabb acc;
  for (size_t i = n; i-- > 1;) {
    acc.extend(base[order[i]].box);
    right_area[i] = acc.area();
  }
  Split best;
  acc = Aabb{};
  for (size_t i = 1; i < n; ++i) {
    acc.extend(base[order[i - 1]].box);
    const float cost = sah_split_cost(o, parent_area, acc.area(), i, right_area[i], n - i);
    if constexpr (kCosts) costs[i] = cost;
    if (!best.valid || cost < best.cost) best = {true, begin + i, cost};
  }
  return best;
}

/// Splits a node by the SAH sweep along the principal axis of its centres.
template <class Sink>
class PcaSplitter : public InPlaceSplitter<PcaSplitter<Sink>, Sink> {
 public:
  static constexpr bool kSahLeafRule = true;
  struct Scratch : ScratchBase {
    std::vector<float> right_area;
    std::vector<uint32_t> order;
    std::vector<double> key;
    std::vector<PrimRef> refs;
  };

  using InPlaceSplitter<PcaSplitter<Sink>, Sink>::InPlaceSplitter;

  Split split(Scratch& scratch, RefRange& w, const Aabb& box, [[maybe_unused]] int depth,
              [[maybe_unused]] uint32_t id) {
    const size_t begin = w.begin, end = w.end, n = end - begin;
    const DVec3 axis = principal_axis(begin, end);
    std::vector<uint32_t>& order = scratch.order;
    std::vector<double>& key = scratch.key;
    order.resize(n);
    key.resize(n);
    for (size_t i = 0; i < n; ++i) key[i] = glm::dot(DVec3(refs_[begin + i].centroid), axis);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return key[a] < key[b] || (key[a] == key[b] && refs_[begin + a].prim < refs_[begin + b].prim);
    });
    if constexpr (Sink::kRecords) {
      if (sink_.records(depth)) {
        // The PCA direction is axis 3; the candidates lie along it, each halfway between two
        // consecutive projections of the sorted centres.
        sink_.axis(id, 3, Vec3(axis));
        scratch.rec_costs.resize(n);
        Split s = sweep_order<true>(o_, refs_.data() + begin, order.data(), n, begin, box.area(), scratch.right_area,
                                    scratch.rec_costs.data());
        std::vector<SplitCandidate>& cands = scratch.rec_candidates;
        cands.resize(n - 1);
        for (size_t i = 1; i < n; ++i)
          cands[i - 1] = {float(0.5 * (key[order[i - 1]] + key[order[i]])), scratch.rec_costs[i], uint32_t(i),
                          uint32_t(n - i)};
        sink_.candidates(id, 3, cands.data(), cands.size());
        s.plane_axis = 3;
        s.plane_pos = cands[s.mid - begin - 1].pos;
        if (s.valid) apply_order(scratch, order, begin);
        return s;
      }
    }
    const Split s = sweep_order(o_, refs_.data() + begin, order.data(), n, begin, box.area(), scratch.right_area);
    if (s.valid) apply_order(scratch, order, begin);
    return s;
  }

 private:
  /// The dominant eigenvector of the centres' covariance, by power iteration started on the
  /// longest centroid axis.
  DVec3 principal_axis(size_t begin, size_t end) const {
    DVec3 mean(0.0);
    for (size_t i = begin; i < end; ++i) mean += DVec3(refs_[i].centroid);
    mean /= double(end - begin);
    glm::dmat3 cov(0.0);
    for (size_t i = begin; i < end; ++i) {
      const DVec3 d = DVec3(refs_[i].centroid) - mean;
      cov += glm::outerProduct(d, d);
    }
    DVec3 axis(0.0);
    axis[centroid_bounds_of(refs_, begin, end).longest_axis()] = 1.0;
    for (int it = 0; it < 32; ++it) {
      const DVec3 next = cov * axis;
      const double len = glm::length(next);
      if (!(len > 0.0)) break;  // all centres equal: any axis will do
      axis = next / len;
    }
    return axis;
  }

  /// Applies a sweep order to refs[begin, begin + order.size()).
  void apply_order(Scratch& scratch, const std::vector<uint32_t>& order, size_t begin) {
    scratch.refs.resize(order.size());
    for (size_t i = 0; i < order.size(); ++i) scratch.refs[i] = refs_[begin + order[i]];
    std::copy(scratch.refs.begin(), scratch.refs.end(), refs_.begin() + long(begin));
  }

  using InPlaceSplitter<PcaSplitter<Sink>, Sink>::o_;
  using InPlaceSplitter<PcaSplitter<Sink>, Sink>::sink_;
  using InPlaceSplitter<PcaSplitter<Sink>, Sink>::refs_;
};

}  // namespace

BuildTree build_pca_tree(const Scene& scene, const BvhBuildOptions& options, ProgressSpan* progress,
                         BuildRecorder* recorder) {
  return build_top_down<PcaSplitter>(scene, options, progress, recorder);
}

}  // namespace accel
