#pragma once
// accelviz's assignment kit: everything a student's acceleration structure needs, and nothing
// of accelviz's internals. Write a class that derives from accelviz::StudentStructure, give it
// build() and intersect(), call the two logs where the lecture's algorithm takes a step, and
// register it with ACCELVIZ_STUDENT_STRUCTURE. accelviz then builds it into the CLI, the viewer
// and the web page, checks it (`accelviz-cli check`) and animates it. student/README.md is
// the ten-minute start, docs/student.md the whole reference.
//
//   class MyBvh : public accelviz::StudentStructure {
//    public:
//     void build(const accelviz::Scene& scene, accelviz::BuildLog& log) override;
//     accelviz::Hit intersect(const accelviz::Ray& ray, accelviz::TraversalLog log) const override;
//   };
//   ACCELVIZ_STUDENT_STRUCTURE(MyBvh, "my_bvh", bvh)
//
// What counts as a hit (docs/hits.md): the ray o + t*d hits a closed triangle at t with
// tmin <= t <= tmax (both inclusive); zero-area triangles and triangles whose plane contains
// the ray are never hit; the closest hit is the smallest t (on an exact tie any tied
// triangle is right). intersect_triangle() below implements that rule exactly.
//
// The logs cost nothing when nobody listens (a batch query, a benchmark): each call is one
// predictable branch on a null pointer. Compiled with -DACCELVIZ_STUDENT_NO_LOG they are
// removed altogether (the kit's README measures the difference).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace accelviz {

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();
/// "No node": the root's parent.
inline constexpr uint32_t kNoParent = 0xffffffffu;

// ---------------------------------------------------------------------------------------
// Vectors, boxes, spheres, triangles

struct Vec3 {
  float x = 0.0f, y = 0.0f, z = 0.0f;
  constexpr Vec3() = default;
  constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
  constexpr explicit Vec3(float s) : x(s), y(s), z(s) {}
  /// Component `axis` (0 = x, 1 = y, 2 = z).
  float& operator[](int axis) { return axis == 0 ? x : axis == 1 ? y : z; }
  float operator[](int axis) const { return axis == 0 ? x : axis == 1 ? y : z; }
};
inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(float s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline Vec3 operator*(Vec3 a, float s) { return s * a; }
inline Vec3 operator/(Vec3 a, float s) { return {a.x / s, a.y / s, a.z / s}; }
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 min(Vec3 a, Vec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
inline Vec3 max(Vec3 a, Vec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }

/// Axis-aligned box; default-constructed it is empty, so grow() starts it.
struct Box {
  Vec3 lo{kInfinity}, hi{-kInfinity};
  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  void grow(Vec3 p) { lo = min(lo, p), hi = max(hi, p); }
  void grow(const Box& b) { lo = min(lo, b.lo), hi = max(hi, b.hi); }
  Vec3 center() const { return 0.5f * (lo + hi); }
  Vec3 extent() const { return empty() ? Vec3(0.0f) : hi - lo; }
  /// Surface area (0 for an empty box): the SAH's weight.
  float area() const {
    const Vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  /// The axis along which the box is longest (0, 1 or 2).
  int longest_axis() const {
    const Vec3 e = extent();
    return e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
  }
  /// Closed: points on the faces are inside.
  bool contains(Vec3 p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
  bool contains(const Box& b) const { return b.empty() || (contains(b.lo) && contains(b.hi)); }
};

/// Bounding sphere; radius < 0 is "none".
struct Sphere {
  Vec3 center;
  float radius = -1.0f;
};

/// One triangle of the scene, its vertices in file order.
struct Triangle {
  Vec3 v0, v1, v2;
  Box box() const {
    Box b;
    b.grow(v0), b.grow(v1), b.grow(v2);
    return b;
  }
  /// The vertices' average (Scene::centroid() is the box's centre).
  Vec3 centroid() const { return (v0 + v1 + v2) / 3.0f; }
};

/// The triangles to build over, numbered 0 .. size()-1 as in the scene file. Read-only; it
/// outlives the structure built over it.
class Scene {
 public:
  uint32_t size() const { return uint32_t(triangles_.size()); }
  const Triangle& triangle(uint32_t prim) const { return triangles_[prim]; }
  /// The triangle's bounding box.
  const Box& box(uint32_t prim) const { return boxes_[prim]; }
  /// The centre of the triangle's box: what builders sort and split by (Triangle::centroid()
  /// is the vertices' average, a different point).
  Vec3 centroid(uint32_t prim) const { return boxes_[prim].center(); }
  /// The box around every triangle (degenerate ones included).
  const Box& bounds() const { return bounds_; }
  /// A zero-area triangle: never hit. You may leave it out of your structure (the checks
  /// only ask that every other triangle is referenced).
  bool is_degenerate(uint32_t prim) const { return degenerate_[prim] != 0; }
  /// A blackboard scene: every triangle in the plane z = 0 (the viewer's 2D mode).
  bool is_2d() const { return planar_; }

 private:
  friend struct KitAccess;  // the kit fills it from accelviz's scene
  std::vector<Triangle> triangles_;
  std::vector<Box> boxes_;
  std::vector<unsigned char> degenerate_;
  Box bounds_;
  bool planar_ = false;
};

// ---------------------------------------------------------------------------------------
// Rays and hits

/// A ray o + t*d over [tmin, tmax]. The kit gives your intersect() rays ready for the tests
/// below; make your own (in your tests) with make_ray().
struct Ray {
  Vec3 origin;
  Vec3 direction;  ///< not normalised: t is in units of it
  float tmin = 0.0f;
  float tmax = kInfinity;
  Vec3 inv_direction;  ///< 1 / direction per component (+-inf where it is +-0)
  /// The triangle test's per-ray constants, prepared once by make_ray(): not yours to touch.
  alignas(16) unsigned char kit_prepared[128] = {};
};
/// A ray ready for intersect_triangle / intersect_box / intersect_sphere.
Ray make_ray(Vec3 origin, Vec3 direction, float tmin = 0.0f, float tmax = kInfinity);

/// A closest hit: prim -1 and t = inf for a miss. The hit point is (1-u-v)*v0 + u*v1 + v*v2.
struct Hit {
  int32_t prim = -1;
  float t = kInfinity;
  float u = 0.0f, v = 0.0f;
  bool valid() const { return prim >= 0; }
};

// ---------------------------------------------------------------------------------------
// The tests (call them, or write your own)

/// The watertight ray/triangle test (Woop, Benthin & Wald 2013, with accelviz's
/// double-precision fallback): true when the ray hits triangle `prim` at some t in
/// [ray.tmin, t_max]; then `hit` holds prim, t, u, v. Never true for a zero-area triangle.
bool intersect_triangle(const Ray& ray, const Scene& scene, uint32_t prim, float t_max, Hit& hit);
/// The slab test: true when the ray meets the closed box within [t_min, t_max]; the ray's
/// part inside it is [t_enter, t_exit]. Conservative (widened by a few ulps, Ize 2013), so
/// rounding never culls a box that holds a hit.
bool intersect_box(const Ray& ray, const Box& box, float t_min, float t_max, float& t_enter, float& t_exit);
/// The same for a sphere.
bool intersect_sphere(const Ray& ray, const Sphere& sphere, float t_min, float t_max, float& t_enter, float& t_exit);

class TraversalLog;
/// The lecture's "test the triangle, keep the closest hit" in one call: tests `prim` against
/// `closest` (t_max = closest.t; start with closest.t = ray.tmax), logs the test, and when
/// it hits closer replaces `closest` and logs the new closest hit. Returns true then. A tie
/// keeps the triangle found first, and a triangle never replaces itself (a triangle held by
/// several cells or leaves may be tested again).
bool test_triangle(const Ray& ray, const Scene& scene, uint32_t prim, Hit& closest, TraversalLog log);
/// The answer of a traversal whose running closest hit is `closest`: a miss when no
/// triangle was taken (t back to inf).
inline Hit finish(const Hit& closest) { return closest.valid() ? closest : Hit{}; }

// ---------------------------------------------------------------------------------------
// The two logs. Node ids are yours (any numbers, unique within one build); the viewer and
// the checks relate the two logs through them. Grid cells are named by (x, y, z).

/// Why a node was skipped.
enum class Cull { MissedBounds, BeyondClosestHit };
/// Why a node became a leaf.
enum class LeafWhy { FewTriangles, MaxDepth, NoGain, NoProgress };
/// A kd-tree inner node's case (the lecture's three): computed by kd_split() for you.
enum class KdCase { Both, NearOnly, FarOnly };
/// One octree child at an inner node, in the order visited (for octree_children()).
struct OctreeChild {
  enum class Fate { Pushed, Missed, BeyondClosestHit, Empty };
  uint32_t node = kNoParent;  ///< the child's id (kNoParent for an empty octant)
  int octant = 0;             ///< 0..7: bit 0 = x high half, bit 1 = y, bit 2 = z
  Fate fate = Fate::Empty;
  float t_enter = 0.0f, t_exit = 0.0f;
};
/// One candidate split plane and its SAH cost C(B), for the viewer's cost curve.
struct Candidate {
  float position = 0.0f;
  float cost = 0.0f;
  uint32_t left = 0, right = 0;  ///< triangles on each side
};

namespace detail {
/// What the kit listens with; students never implement it.
class TraversalListener {
 public:
  virtual ~TraversalListener() = default;
  virtual void visit(uint32_t node, int depth, float t_enter, float t_exit) = 0;
  virtual void enter_cell(int x, int y, int z, float t_enter, float t_exit) = 0;
  virtual void cull(uint32_t node, int depth, Cull why, float t_enter) = 0;
  virtual void push(uint32_t node, int depth, float key) = 0;
  virtual void pop(uint32_t node, int depth, float key) = 0;
  virtual void triangle_tested(uint32_t prim, bool hit, float t) = 0;
  virtual void new_closest(uint32_t prim, float t) = 0;
  virtual void grid_dda(const int cell[3], const int step[3], const float t_max[3], const float t_delta[3]) = 0;
  virtual void kd_split(float t_min, float t_split, float t_max, uint32_t near_child, uint32_t far_child, int axis) = 0;
  virtual void kd_far_pop(float t_hit, float t_split, uint32_t far_child, bool exits) = 0;
  virtual void octree_children(unsigned mask, const OctreeChild* children, int count) = 0;
};
class BuildListener {
 public:
  virtual ~BuildListener() = default;
  virtual bool records() const = 0;
  virtual void node(uint32_t id, uint32_t parent, int depth, const Box& box, const uint32_t* prims, size_t n) = 0;
  virtual void sphere(uint32_t id, const Sphere& s) = 0;
  virtual void split(uint32_t id, int axis, float position, float cost, float leaf_cost, uint32_t left,
                     uint32_t right) = 0;
  virtual void candidates(uint32_t id, int axis, const Candidate* c, size_t n) = 0;
  virtual void leaf(uint32_t id, const uint32_t* prims, size_t n, LeafWhy why) = 0;
  virtual void grid_resolution(const Box& box, int nx, int ny, int nz) = 0;
  virtual void cell_filled(int x, int y, int z, uint32_t prim) = 0;
};
}  // namespace detail

// Every log call is forced inline, so a file compiled with ACCELVIZ_STUDENT_NO_LOG (the kit's
// measurement of what the calls cost) never shares a copy of them with the rest of the program.
#define ACCELVIZ_LOG_FN [[gnu::always_inline]] inline
#ifdef ACCELVIZ_STUDENT_NO_LOG
#define ACCELVIZ_LOG(call)      \
  do {                          \
    if (false && to_) to_->call; \
  } while (false)
#else
#define ACCELVIZ_LOG(call) \
  do {                     \
    if (to_) to_->call;    \
  } while (false)
#endif

/// The traversal's steps, as the lecture names them. Call each where your loop takes it;
/// the viewer animates exactly these calls, and `check` reads them. A handle the size of a
/// pointer: pass it by value (then it stays in a register, and each call is one branch).
class TraversalLog {
 public:
  TraversalLog() = default;
  explicit TraversalLog(detail::TraversalListener* to) : to_(to) {}
  /// True while something records: skip work done only to log (e.g. computing a culled
  /// child's entry distance).
  bool listening() const { return to_ != nullptr; }

  /// Entering node `node` at `depth` (root 0); the ray is inside it over [t_enter, t_exit].
  ACCELVIZ_LOG_FN void visit(uint32_t node, int depth, float t_enter, float t_exit) {
    ACCELVIZ_LOG(visit(node, depth, t_enter, t_exit));
  }
  /// Grid: stepping into cell (x, y, z), inside it over [t_enter, t_exit].
  ACCELVIZ_LOG_FN void enter_cell(int x, int y, int z, float t_enter, float t_exit) {
    ACCELVIZ_LOG(enter_cell(x, y, z, t_enter, t_exit));
  }
  /// Skipping a node (and its subtree): it was missed, or it starts beyond the closest hit.
  ACCELVIZ_LOG_FN void cull(uint32_t node, int depth, Cull why, float t_enter = kInfinity) {
    ACCELVIZ_LOG(cull(node, depth, why, t_enter));
  }
  /// Putting a node on the stack or priority queue (key: its entry distance).
  ACCELVIZ_LOG_FN void push(uint32_t node, int depth, float key) { ACCELVIZ_LOG(push(node, depth, key)); }
  /// Taking one off.
  ACCELVIZ_LOG_FN void pop(uint32_t node, int depth, float key) { ACCELVIZ_LOG(pop(node, depth, key)); }
  /// A ray/triangle test and its outcome (t when hit). test_triangle() logs it for you.
  ACCELVIZ_LOG_FN void triangle_tested(uint32_t prim, bool hit, float t) {
    ACCELVIZ_LOG(triangle_tested(prim, hit, t));
  }
  /// The closest hit improved. test_triangle() logs it for you.
  ACCELVIZ_LOG_FN void new_closest(uint32_t prim, float t) { ACCELVIZ_LOG(new_closest(prim, t)); }

  // The lecture's variables, shown in the viewer's Variables panel.
  /// Grid 3D-DDA, on entering a cell: X, Y, Z, stepX.., tMaxX.., tDeltaX.. (the axis that
  /// steps next is the smallest tMax).
  ACCELVIZ_LOG_FN void grid_dda(const int cell[3], const int step[3], const float t_max[3], const float t_delta[3]) {
    ACCELVIZ_LOG(grid_dda(cell, step, t_max, t_delta));
  }
  /// kd-tree inner node, after its visit: [t_min, t_max], t_split and the near / far child
  /// (near = the side the ray is on before t_split). The case (a, b, c) is derived.
  ACCELVIZ_LOG_FN void kd_split(float t_min, float t_split, float t_max, uint32_t near_child, uint32_t far_child,
                                int axis) {
    ACCELVIZ_LOG(kd_split(t_min, t_split, t_max, near_child, far_child, axis));
  }
  /// kd-tree, when a pending far child is taken: the lecture's "if t_hit < t_split return".
  ACCELVIZ_LOG_FN void kd_far_pop(float t_hit, float t_split, uint32_t far_child, bool exits) {
    ACCELVIZ_LOG(kd_far_pop(t_hit, t_split, far_child, exits));
  }
  /// Octree inner node: its children in visiting order (mask: the axes the ray runs down).
  ACCELVIZ_LOG_FN void octree_children(unsigned mask, const OctreeChild* children, int count) {
    ACCELVIZ_LOG(octree_children(mask, children, count));
  }

 private:
  detail::TraversalListener* to_ = nullptr;
};

/// The construction's steps. The kit always listens (the viewer draws your structure from
/// these calls, and `check` verifies them), so log every node and leaf you make.
class BuildLog {
 public:
  BuildLog() = default;
  explicit BuildLog(detail::BuildListener* to) : to_(to) {}
  /// True while the construction is being recorded for playback: skip preparing arguments
  /// only the playback needs (candidates()).
  bool recording() const { return to_ && to_->records(); }

  /// A node made over `prims` (the root: parent kNoParent, depth 0), with its box.
  ACCELVIZ_LOG_FN void node(uint32_t id, uint32_t parent, int depth, const Box& box,
                            const std::vector<uint32_t>& prims) {
    ACCELVIZ_LOG(node(id, parent, depth, box, prims.data(), prims.size()));
  }
  ACCELVIZ_LOG_FN void node(uint32_t id, uint32_t parent, int depth, const Box& box, const uint32_t* prims, size_t n) {
    ACCELVIZ_LOG(node(id, parent, depth, box, prims, n));
  }
  /// Sphere tree: the node's bounding sphere (after node()).
  ACCELVIZ_LOG_FN void sphere(uint32_t id, const Sphere& s) { ACCELVIZ_LOG(sphere(id, s)); }
  /// The split chosen for node `id`: the axis, the plane, its cost C(B) against the leaf's,
  /// and the triangles going left and right.
  ACCELVIZ_LOG_FN void split(uint32_t id, int axis, float position, float cost, float leaf_cost, uint32_t left,
                             uint32_t right) {
    ACCELVIZ_LOG(split(id, axis, position, cost, leaf_cost, left, right));
  }
  /// The candidate planes evaluated along `axis`: the viewer's C(B) curve.
  ACCELVIZ_LOG_FN void candidates(uint32_t id, int axis, const std::vector<Candidate>& c) {
    ACCELVIZ_LOG(candidates(id, axis, c.data(), c.size()));
  }
  /// Node `id` becomes a leaf holding `prims`.
  ACCELVIZ_LOG_FN void leaf(uint32_t id, const std::vector<uint32_t>& prims, LeafWhy why = LeafWhy::FewTriangles) {
    ACCELVIZ_LOG(leaf(id, prims.data(), prims.size(), why));
  }
  ACCELVIZ_LOG_FN void leaf(uint32_t id, const uint32_t* prims, size_t n, LeafWhy why = LeafWhy::FewTriangles) {
    ACCELVIZ_LOG(leaf(id, prims, n, why));
  }
  /// Grid: its box and cells per axis (call once, before cell_filled()).
  ACCELVIZ_LOG_FN void grid_resolution(const Box& box, int nx, int ny, int nz) {
    ACCELVIZ_LOG(grid_resolution(box, nx, ny, nz));
  }
  /// Grid: cell (x, y, z) receives triangle `prim`.
  ACCELVIZ_LOG_FN void cell_filled(int x, int y, int z, uint32_t prim) { ACCELVIZ_LOG(cell_filled(x, y, z, prim)); }

 private:
  detail::BuildListener* to_ = nullptr;
};
#undef ACCELVIZ_LOG
#undef ACCELVIZ_LOG_FN

// ---------------------------------------------------------------------------------------
// The structure and its registration

/// Which of the lecture's structures a student structure implements: picks the pseudo code
/// beside its animation, the Variables panel's rows, the built-in structure it is compared
/// and timed against, and the traps `check` looks for.
enum class Kind { grid, octree, kdtree, bvh, spheretree };

/// A student's acceleration structure. build() is called once per scene (on a new object);
/// intersect() then from any number of threads at once (so it must not change the object).
class StudentStructure {
 public:
  virtual ~StudentStructure() = default;
  /// Builds over `scene` (which outlives this object), logging every node and leaf.
  virtual void build(const Scene& scene, BuildLog& log) = 0;
  /// The closest hit of `ray` in [ray.tmin, ray.tmax] by the hit rule above, or Hit{}.
  virtual Hit intersect(const Ray& ray, TraversalLog log) const = 0;
};

/// How a registered structure presents itself. Filled by ACCELVIZ_STUDENT_STRUCTURE.
struct Registration {
  std::string name;  ///< what --structure takes: lower case, digits and '_'
  Kind kind = Kind::bvh;
  std::string file;       ///< the source file that registered it
  bool optimized = true;  ///< that file was compiled with optimisation (check times only these)
  std::unique_ptr<StudentStructure> (*create)() = nullptr;
};
/// Called by the macro below at program start.
bool register_student_structure(const Registration& r);

}  // namespace accelviz

// Timings mean something only for optimised code without sanitizers (check refuses others).
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(undefined_behavior_sanitizer)
#define ACCELVIZ_STUDENT_SANITIZED_ 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define ACCELVIZ_STUDENT_SANITIZED_ 1
#endif
#if defined(__OPTIMIZE__) && !defined(ACCELVIZ_STUDENT_SANITIZED_)
#define ACCELVIZ_STUDENT_OPTIMIZED_ true
#else
#define ACCELVIZ_STUDENT_OPTIMIZED_ false
#endif
#define ACCELVIZ_STUDENT_CONCAT2_(a, b) a##b
#define ACCELVIZ_STUDENT_CONCAT_(a, b) ACCELVIZ_STUDENT_CONCAT2_(a, b)

/// Registers class `Class` (a StudentStructure) as structure `name` (a string literal)
/// implementing the lecture's `kind` (grid, octree, kdtree, bvh or spheretree).
#define ACCELVIZ_STUDENT_STRUCTURE(Class, name, kind)                                                              \
  namespace {                                                                                                      \
  [[maybe_unused]] const bool ACCELVIZ_STUDENT_CONCAT_(accelviz_registered_, __LINE__) =                           \
      ::accelviz::register_student_structure({name, ::accelviz::Kind::kind, __FILE__, ACCELVIZ_STUDENT_OPTIMIZED_, \
                                              []() -> std::unique_ptr<::accelviz::StudentStructure> {              \
                                                return std::make_unique<Class>();                                  \
                                              }});                                                                 \
  }
