#pragma once
// The one driver of every parallel top-down build (BVH median / SAH sweep / PCA through
// bvh_top_down.h, binned SAH, SBVH, kd-tree): the upper part of the tree is split into
// tasks, the lower part is built in serial chunks, and the chunks are stitched into the
// serial recursion's pre-order. A builder supplies only how it splits one node and how it
// builds a subtree serially; this header owns the rest, so the rules are written once:
//  - the task threshold (kTaskMinRefs): a subtree of fewer references is one serial chunk;
//  - the cancel check before every task (a cancelled or failed build returns empty chunks,
//    and the caller discards the tree);
//  - the leaf a task's root becomes when the builder does not split it (the depth limit,
//    or a small node of a huge build), written by the builder into the chunk;
//  - the two children as two tasks, and the chunks' sizes;
//  - stitching for any node type (ChunkLinks<Node>: how a node points at its children and
//    triangles, the kd-tree's shifted index included), in parallel.
// Every decision depends only on the node's references, never on which task makes it, so
// the tree is the same, bit for bit, for any thread count (and with no task at all).
//
// The octree does not use it: its eight children are a block of eight consecutive nodes
// (octant = (id - 1) % 8), not a pre-order, and its tasks splice their parts in place
// (octree.cpp); it shares kTaskMinRefs's role through its own 8-way split threshold.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "build_control.h"
#include "parallel.h"

namespace accel::top_down {

/// Subtrees of fewer references than this are one serial chunk: below it a task's overhead
/// outweighs its work (the binned builder: ~0.3 ms per 4096 references; the kd-tree's nodes
/// cost more per reference and were measured equal at 2048 and 4096).
inline constexpr size_t kTaskMinRefs = 4096;

/// How the stitching moves a node type; specialised next to each node type's builder:
///   static void link(Node& inner, uint32_t left, uint32_t right);  // a task's root: its children's final indices
///   static void relocate(Node& n, uint32_t node_offset, uint32_t prim_offset);  // a serial chunk's node, moved
template <class Node>
struct ChunkLinks;

/// What a chunk carries besides its nodes: nothing, for most builders (the kd-tree counts
/// its leaves' reasons and depth per chunk).
struct NoChunkStats {};

/// A subtree built by one task.
template <class Node, class Stats = NoChunkStats>
struct Chunk {
  /// Parallel (left and right set): its root node, whose children are the chunks left and right.
  Node node{};
  std::unique_ptr<Chunk> left, right;
  /// Serial (no children): the whole subtree in local pre-order, child links relative to
  /// nodes[0] ...
  std::vector<Node> nodes;
  /// ... and, for builders whose leaves list triangles of their own (SBVH, kd-tree: a
  /// triangle may be in several leaves), those triangles, leaf offsets relative to prims[0].
  /// Empty for builders whose leaves index one shared triangle order.
  std::vector<uint32_t> prims;
  Stats stats{};
  size_t size = 0;        ///< nodes in the subtree
  size_t prim_count = 0;  ///< leaf triangles in the subtree (chunks with prims of their own)
};

/// What a builder made of a task's root (split_root()).
enum class RootSplit {
  Leaf,   ///< the chunk holds the one leaf (in nodes, and its triangles in prims if own)
  Split,  ///< chunk.node is the inner node, left and right the children's tasks
  Stop,   ///< the build failed (a budget): an empty chunk, the caller reports the error
};

/// The driver, over a Builder that provides:
///   using Node; using Task; using Stats (optional: NoChunkStats);
///   size_t refs(const Task&) const;          the size kTaskMinRefs is compared with
///   bool all_serial() const;                 one chunk for the whole tree (recorded builds:
///                                            the event ids are the final pre-order indices)
///   bool stopped() const;                    cancelled, or another task failed
///   void build_serial(Task&, Chunk&);        the subtree, in local pre-order
///   RootSplit split_root(Task&, Chunk&, Task& left, Task& right);
/// Tasks are consumed (moved from).
template <class Builder>
class TopDownTasks {
 public:
  using Node = typename Builder::Node;
  using Task = typename Builder::Task;
  using ChunkT = Chunk<Node, typename Builder::Stats>;

  explicit TopDownTasks(Builder& builder) : builder_(builder) {}

  /// The chunk tree of the subtree of `task`.
  std::unique_ptr<ChunkT> build(Task& task) {
    auto chunk = std::make_unique<ChunkT>();
    if (builder_.stopped()) return chunk;  // cancelled or failed: empty, the tree is discarded
    if (builder_.all_serial() || builder_.refs(task) < kTaskMinRefs) {
      builder_.build_serial(task, *chunk);
      return sized(std::move(chunk));
    }
    Task left, right;
    switch (builder_.split_root(task, *chunk, left, right)) {
      case RootSplit::Stop: return chunk;
      case RootSplit::Leaf: return sized(std::move(chunk));
      case RootSplit::Split: break;
    }
    task = Task{};  // the children own their parts now: free the parent's before they allocate
    par::parallel_invoke([&] { chunk->left = build(left); }, [&] { chunk->right = build(right); });
    chunk->size = 1 + chunk->left->size + chunk->right->size;
    chunk->prim_count = chunk->left->prim_count + chunk->right->prim_count;
    return chunk;
  }

 private:
  static std::unique_ptr<ChunkT> sized(std::unique_ptr<ChunkT> chunk) {
    chunk->size = chunk->nodes.size();
    chunk->prim_count = chunk->prims.size();
    return chunk;
  }

  Builder& builder_;
};

/// The part of the driver's interface most builders share: recording builds the whole tree
/// as one chunk (its event ids are then the final pre-order indices), and a cancel seen by
/// the progress counter stops the tasks.
template <class Sink>
class SinkTasks {
 public:
  SinkTasks(ProgressCounter& progress, Sink& sink) : progress_(progress), sink_(sink) {}
  bool all_serial() const { return Sink::kRecords; }
  bool stopped() const { return progress_.stopped(); }

 protected:
  ProgressCounter& progress_;
  Sink& sink_;
};

/// Calls f(chunk) for every chunk, the task roots and the serial ones, in pre-order.
template <class C, class F>
void for_each_chunk(const C& chunk, F&& f) {
  f(chunk);
  if (!chunk.left) return;
  for_each_chunk(*chunk.left, f);
  for_each_chunk(*chunk.right, f);
}

namespace detail {

/// A serial chunk and the offsets of its nodes and triangles in the whole tree.
template <class C>
struct Placed {
  const C* chunk;
  uint32_t node, prim;
};

/// Numbers the task roots in pre-order from the subtree sizes and collects the serial
/// chunks with their offsets.
template <class C, class Node>
void place(const C& c, uint32_t node, uint32_t prim, std::vector<Node>& nodes, std::vector<Placed<C>>& serial) {
  if (!c.left) {
    serial.push_back({&c, node, prim});
    return;
  }
  const uint32_t left = node + 1, right = node + 1 + uint32_t(c.left->size);
  nodes[node] = c.node;
  ChunkLinks<Node>::link(nodes[node], left, right);
  place(*c.left, left, prim, nodes, serial);
  place(*c.right, right, prim + uint32_t(c.left->prim_count), nodes, serial);
}

}  // namespace detail

/// Lays the chunk tree out in the serial recursion's pre-order (node, left subtree, right
/// subtree) into `nodes`, and, for chunks with triangles of their own, their triangles in the
/// same order into *prims (leaves moved along). A tree of one serial chunk is moved, not copied.
template <class Node, class Stats>
void stitch(Chunk<Node, Stats>& root, std::vector<Node>& nodes, std::vector<uint32_t>* prims = nullptr) {
  using C = Chunk<Node, Stats>;
  if (!root.left) {
    nodes = std::move(root.nodes);
    if (prims) *prims = std::move(root.prims);
    return;
  }
  nodes.resize(root.size);
  if (prims) prims->resize(root.prim_count);
  std::vector<detail::Placed<C>> serial;
  detail::place(root, 0, 0, nodes, serial);
  par::parallel_for(size_t(0), serial.size(), [&](size_t k) {
    const detail::Placed<C>& p = serial[k];
    Node* dst = nodes.data() + p.node;
    for (const Node& src : p.chunk->nodes) {
      *dst = src;
      ChunkLinks<Node>::relocate(*dst++, p.node, p.prim);
    }
    if (prims) std::copy(p.chunk->prims.begin(), p.chunk->prims.end(), prims->begin() + long(p.prim));
  });
}

}  // namespace accel::top_down
