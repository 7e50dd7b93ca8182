// accelviz-worker: a student's structures and the kit's runtime, nothing else (no structure,
// registry or grader of the core). The judge (`accelviz-cli check`) starts it in a sandbox
// and sends it scenes and rays on fd 3; it answers on fd 4 with what the student's code did:
// every build-log and traversal-log call as a frame, then the answer or the exception
// (core/student/worker_protocol.h). It decides nothing: the judge checks every answer and
// every logged claim itself.
//
//   accelviz-worker --list     the structures built in, one per line (for people)
//   accelviz-worker --serve    answer the judge on fds 3 and 4
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "accelviz_student.h"
#include "geometry.h"
#include "student/kit_access.h"
#include "student/kit_registrations.h"
#include "student/worker_protocol.h"

namespace {

using accel::wire::Msg;
using accel::wire::Payload;

/// Budget of one traversal's logged steps before the worker calls it endless: the same
/// number as the kit's (kit_structure.h); the judge counts again and holds the same line.
constexpr uint64_t kStepBudget = 20'000'000;
/// The most traversal frames sent for one ray: more than the judge's recorder keeps (64 MB of
/// events). Past it the steps are still counted against the budget, but not sent: an
/// endless loop that logs costs the judge a megabyte-sized stream, not 20 million frames.
constexpr uint64_t kFramesPerRay = 1'000'000;
/// The most rays one Query or Time request may carry.
constexpr uint32_t kMaxRays = 2'000'000;
/// The most triangles one Build request may carry.
constexpr uint32_t kMaxTriangles = 5'000'000;

/// A stop of the worker for a broken channel: the judge went away or sent garbage.
struct ChannelClosed {};

/// Blocking frame I/O on the two pipe ends; answers are buffered and flushed at the end of
/// each ray, so a crash is seen by the judge at the ray it happened on.
class Channel {
 public:
  Msg receive(std::string& payload) {
    uint32_t header[2];
    read_all(header, sizeof header);
    if (header[1] > accel::wire::kMaxPayload) throw ChannelClosed{};
    payload.resize(header[1]);
    read_all(payload.data(), payload.size());
    return Msg(header[0]);
  }
  void send(Msg type, const std::string& payload) { send(type, payload.data(), payload.size()); }
  void send(Msg type, const void* data, size_t size) {
    const uint32_t header[2] = {uint32_t(type), uint32_t(size)};
    out_.append(reinterpret_cast<const char*>(header), sizeof header);
    out_.append(static_cast<const char*>(data), size);
    if (out_.size() >= (64u << 10)) flush();
  }
  template <class T>
  void send_pod(Msg type, const T& value) {
    send(type, &value, sizeof value);
  }
  void flush() {
    size_t done = 0;
    while (done < out_.size()) {
      const ssize_t n = ::write(accel::wire::kAnswerFd, out_.data() + done, out_.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw ChannelClosed{};
      done += size_t(n);
    }
    out_.clear();
  }

 private:
  static void read_all(void* to, size_t size) {
    auto* p = static_cast<char*>(to);
    while (size) {
      const ssize_t n = ::read(accel::wire::kRequestFd, p, size);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw ChannelClosed{};
      p += n, size -= size_t(n);
    }
  }
  std::string out_;
};

/// The build log's calls, each sent as it is made.
class WireBuildListener final : public accelviz::detail::BuildListener {
 public:
  WireBuildListener(Channel& ch, bool records) : ch_(ch), records_(records) {}
  bool records() const override { return records_; }
  void node(uint32_t id, uint32_t parent, int depth, const accelviz::Box& box, const uint32_t* prims,
            size_t n) override {
    Payload p;
    p.put(id).put(parent).put(int32_t(depth)).put(box).put(uint32_t(n)).put_bytes(prims, n * sizeof(uint32_t));
    ch_.send(Msg::Node, p.bytes());
  }
  void sphere(uint32_t id, const accelviz::Sphere& s) override {
    Payload p;
    ch_.send(Msg::Sphere, p.put(id).put(s).bytes());
  }
  void split(uint32_t id, int axis, float position, float cost, float leaf_cost, uint32_t left,
             uint32_t right) override {
    Payload p;
    ch_.send(Msg::Split, p.put(id).put(int32_t(axis)).put(position).put(cost).put(leaf_cost).put(left).put(right).bytes());
  }
  void candidates(uint32_t id, int axis, const accelviz::Candidate* c, size_t n) override {
    Payload p;
    p.put(id).put(int32_t(axis)).put(uint32_t(n)).put_bytes(c, n * sizeof(accelviz::Candidate));
    ch_.send(Msg::Candidates, p.bytes());
  }
  void leaf(uint32_t id, const uint32_t* prims, size_t n, accelviz::LeafWhy why) override {
    Payload p;
    p.put(id).put(int32_t(why)).put(uint32_t(n)).put_bytes(prims, n * sizeof(uint32_t));
    ch_.send(Msg::Leaf, p.bytes());
  }
  void grid_resolution(const accelviz::Box& box, int nx, int ny, int nz) override {
    Payload p;
    ch_.send(Msg::GridResolution, p.put(box).put(int32_t(nx)).put(int32_t(ny)).put(int32_t(nz)).bytes());
  }
  void cell_filled(int x, int y, int z, uint32_t prim) override {
    Payload p;
    ch_.send(Msg::CellFilled, p.put(int32_t(x)).put(int32_t(y)).put(int32_t(z)).put(prim).bytes());
  }

 private:
  Channel& ch_;
  bool records_;
};

/// The step budget's stop: thrown through the student's intersect, sent as the kit's own.
struct StepBudgetExceeded {};

/// The traversal log's calls, each sent as it is made.
class WireTraversalListener final : public accelviz::detail::TraversalListener {
 public:
  explicit WireTraversalListener(Channel& ch) : ch_(ch) {}
  void visit(uint32_t node, int depth, float t0, float t1) override { node_step(Msg::Visit, node, depth, t0, t1); }
  void enter_cell(int x, int y, int z, float t0, float t1) override {
    step();
    if (!sending()) return;
    Payload p;
    send(Msg::EnterCell, p.put(int32_t(x)).put(int32_t(y)).put(int32_t(z)).put(t0).put(t1).bytes());
  }
  void cull(uint32_t node, int depth, accelviz::Cull why, float t) override {
    step();
    if (!sending()) return;
    Payload p;
    send(Msg::Cull, p.put(node).put(int32_t(depth)).put(int32_t(why)).put(t).bytes());
  }
  void push(uint32_t node, int depth, float key) override { node_step(Msg::Push, node, depth, key, 0.0f); }
  void pop(uint32_t node, int depth, float key) override { node_step(Msg::Pop, node, depth, key, 0.0f); }
  void triangle_tested(uint32_t prim, bool hit, float t) override {
    step();
    if (!sending()) return;
    Payload p;
    send(Msg::Tested, p.put(prim).put(uint8_t(hit)).put(t).bytes());
  }
  void new_closest(uint32_t prim, float t) override {
    step();
    if (!sending()) return;
    Payload p;
    send(Msg::NewClosest, p.put(prim).put(t).bytes());
  }
  void grid_dda(const int cell[3], const int step_[3], const float t_max[3], const float t_delta[3]) override {
    if (!sending()) return;
    Payload p;
    p.put_bytes(cell, 3 * sizeof(int)).put_bytes(step_, 3 * sizeof(int));
    p.put_bytes(t_max, 3 * sizeof(float)).put_bytes(t_delta, 3 * sizeof(float));
    send(Msg::GridDda, p.bytes());
  }
  void kd_split(float t_min, float t_split, float t_max, uint32_t near_child, uint32_t far_child, int axis) override {
    if (!sending()) return;
    Payload p;
    send(Msg::KdSplit, p.put(t_min).put(t_split).put(t_max).put(near_child).put(far_child).put(int32_t(axis)).bytes());
  }
  void kd_far_pop(float t_hit, float t_split, uint32_t far_child, bool exits) override {
    if (!sending()) return;
    Payload p;
    send(Msg::KdFarPop, p.put(t_hit).put(t_split).put(far_child).put(uint8_t(exits)).bytes());
  }
  void octree_children(unsigned mask, const accelviz::OctreeChild* children, int count) override {
    if (!sending()) return;
    const int n = std::clamp(count, 0, 8);
    Payload p;
    p.put(uint32_t(mask)).put(int32_t(n)).put_bytes(children, size_t(n) * sizeof(accelviz::OctreeChild));
    send(Msg::OctreeChildren, p.bytes());
  }

 private:
  void node_step(Msg type, uint32_t node, int depth, float a, float b) {
    step();
    if (!sending()) return;
    Payload p;
    send(type, p.put(node).put(int32_t(depth)).put(a).put(b).bytes());
  }
  void step() {
    if (++steps_ > kStepBudget) throw StepBudgetExceeded{};
  }
  bool sending() const { return steps_ <= kFramesPerRay; }
  void send(Msg type, const std::string& payload) { ch_.send(type, payload); }
  Channel& ch_;
  uint64_t steps_ = 0;
};

std::string cut(std::string s) {
  if (s.size() > accel::wire::kMaxMessage) s.resize(accel::wire::kMaxMessage);
  return s;
}

void send_threw(Channel& ch, bool kit, const std::string& message) {
  Payload p;
  ch.send(Msg::Threw, p.put(uint8_t(kit)).put_string(cut(message)).bytes());
}

/// Runs `fn` (the student's code), sending what it threw; true when it returned.
template <class Fn>
bool guarded(Channel& ch, Fn&& fn) {
  try {
    fn();
    return true;
  } catch (const StepBudgetExceeded&) {
    send_threw(ch, true,
               "more than " + std::to_string(kStepBudget) +
                   " logged steps for one ray: an endless loop? (the step budget of the traversal log)");
  } catch (const ChannelClosed&) {
    throw;
  } catch (const std::exception& e) {
    send_threw(ch, false, e.what());
  } catch (...) {
    send_threw(ch, false, "a non-standard exception");
  }
  return false;
}

const accelviz::Registration* find_registration(const std::string& name) {
  for (const accelviz::Registration& r : accel::student_registrations())
    if (r.name == name) return &r;
  return nullptr;
}

/// The structure built last, over the scene it was built over.
struct Built {
  std::unique_ptr<accelviz::Scene> scene;
  std::unique_ptr<accelviz::StudentStructure> structure;
};

void hello(Channel& ch) {
  for (const accelviz::Registration& r : accel::student_registrations()) {
    Payload p;
    p.put(uint8_t(r.kind)).put(uint8_t(r.optimized)).put_string(cut(r.name)).put_string(cut(r.file));
    ch.send(Msg::Registration, p.bytes());
  }
  ch.send_pod(Msg::HelloDone, accel::wire::kVersion);
  ch.flush();
}

/// Build {name, planar, records, bounds, count, triangles, degenerate flags}.
void build(Channel& ch, const std::string& payload, Built& built) {
  accel::wire::Cursor c(payload);
  const std::string name = c.get_string();
  const bool planar = c.get<uint8_t>() != 0, records = c.get<uint8_t>() != 0;
  const auto bounds = c.get<accelviz::Box>();
  const uint32_t n = c.get<uint32_t>();
  if (n > kMaxTriangles) throw ChannelClosed{};
  auto wire_triangles = c.get_array<accelviz::Triangle>(n);
  auto degenerate = c.get_array<unsigned char>(n);
  if (!c.complete()) throw ChannelClosed{};
  built = Built{};
  const accelviz::Registration* reg = find_registration(name);
  if (!reg) {
    send_threw(ch, true, "no student structure named '" + name + "' in this worker");
    ch.flush();
    return;
  }
  built.scene = std::make_unique<accelviz::Scene>();
  accelviz::KitAccess::fill_scene(*built.scene, std::move(wire_triangles), std::move(degenerate), bounds, planar);
  WireBuildListener listener(ch, records);
  accelviz::BuildLog log(&listener);
  const bool ok = guarded(ch, [&] {
    built.structure = reg->create();
    built.structure->build(*built.scene, log);
  });
  if (ok) ch.send(Msg::BuildDone, nullptr, 0);
  else built.structure.reset();
  ch.flush();
}

/// The rays of a request, as they travel: each is prepared for the kit's tests just before
/// its query (on the stack, in the cache, as the in-process adapter does), not all at once
/// into an array six times their size.
std::vector<accel::wire::WireRay> read_rays(accel::wire::Cursor& c) {
  const uint32_t n = c.get<uint32_t>();
  if (n > kMaxRays) throw ChannelClosed{};
  auto rays = c.get_array<accel::wire::WireRay>(n);
  if (!c.complete()) throw ChannelClosed{};
  return rays;
}

accelviz::Ray prepared(const accel::wire::WireRay& w, accel::Kernel kernel) {
  accel::Ray r;
  r.org = accel::Vec3(w.org[0], w.org[1], w.org[2]);
  r.dir = accel::Vec3(w.dir[0], w.dir[1], w.dir[2]);
  r.tmin = w.tmin;
  r.tmax = w.tmax;
  return accelviz::KitAccess::make_ray(r, kernel);
}

void send_answer(Channel& ch, const accelviz::Hit& h) {
  ch.send_pod(Msg::Answer, accel::wire::WireHit{h.prim, h.t, h.u, h.v});
}

/// Query {modes, kernel, rays}: per ray, listened to (its log's frames, then the answer or
/// the exception) and / or on the fast path (the answer or the exception); after an
/// exception, nothing more for that ray.
void query(Channel& ch, const std::string& payload, const Built& built) {
  accel::wire::Cursor c(payload);
  const uint8_t modes = c.get<uint8_t>();
  const auto kernel = accel::Kernel(c.get<uint8_t>());
  for (const accel::wire::WireRay& wire : read_rays(c)) {
    const accelviz::Ray ray = prepared(wire, kernel);
    for (const uint8_t mode : {accel::wire::kTraced, accel::wire::kFast}) {
      if (!(modes & mode)) continue;
      if (!built.structure) {
        send_threw(ch, true, "no structure was built");
        break;
      }
      WireTraversalListener listener(ch);
      const accelviz::TraversalLog log(mode == accel::wire::kTraced ? &listener : nullptr);
      accelviz::Hit h;
      // A ray whose listened-to query threw gets no fast query: an endless loop that the
      // step budget stopped would loop on with nobody counting.
      if (!guarded(ch, [&] { h = built.structure->intersect(ray, log); })) break;
      send_answer(ch, h);
    }
    ch.flush();
  }
}

/// Time {kernel, threads, rays}: every ray on the fast path, on `threads` threads, the
/// answers in one frame. The judge measures the time from its request to this frame.
void time_rays(Channel& ch, const std::string& payload, const Built& built) {
  accel::wire::Cursor c(payload);
  const auto kernel = accel::Kernel(c.get<uint8_t>());
  const uint32_t threads = std::clamp<uint32_t>(c.get<uint32_t>(), 1, 256);
  const std::vector<accel::wire::WireRay> rays = read_rays(c);
  std::vector<accel::wire::WireHit> hits(rays.size(), accel::wire::WireHit{-1, accelviz::kInfinity, 0.0f, 0.0f});
  std::vector<std::string> errors(threads);
  if (built.structure) {
    std::vector<std::thread> pool;
    for (uint32_t k = 0; k < threads; ++k)
      pool.emplace_back([&, k] {
        try {
          for (size_t i = k; i < rays.size(); i += threads) {
            const accelviz::Hit h = built.structure->intersect(prepared(rays[i], kernel), accelviz::TraversalLog());
            hits[i] = {h.prim, h.t, h.u, h.v};
          }
        } catch (const std::exception& e) {
          errors[k] = e.what();
        } catch (...) {
          errors[k] = "a non-standard exception";
        }
      });
    for (std::thread& t : pool) t.join();
  }
  for (const std::string& e : errors)
    if (!e.empty()) {
      send_threw(ch, false, e);
      ch.flush();
      return;
    }
  Payload p;
  p.put(uint32_t(hits.size())).put_bytes(hits.data(), hits.size() * sizeof(hits[0]));
  ch.send(Msg::Hits, p.bytes());
  ch.flush();
}

int serve() {
  Channel ch;
  Built built;
  std::string payload;
  try {
    for (;;) {
      switch (ch.receive(payload)) {
        case Msg::Hello:
          hello(ch);
          break;
        case Msg::Build:
          build(ch, payload, built);
          break;
        case Msg::Query:
          query(ch, payload, built);
          break;
        case Msg::Time:
          time_rays(ch, payload, built);
          break;
        case Msg::Quit:
          return 0;
        default:
          return 3;  // not a request: the judge's channel is not ours
      }
    }
  } catch (const ChannelClosed&) {
    return 3;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "--serve") return serve();
  if (mode == "--list") {
    for (const accelviz::Registration& r : accel::student_registrations())
      std::printf("%s (%d) from %s%s\n", r.name.c_str(), int(r.kind), r.file.c_str(),
                  r.optimized ? "" : " (not optimised)");
    return 0;
  }
  std::fprintf(stderr,
               "accelviz-worker: the student structures' process that accelviz-cli check talks to.\n"
               "usage: accelviz-worker --list | --serve (fds 3 and 4: the judge's channel)\n");
  return 2;
}
