#include "judge/remote_student.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <thread>

#include "student/kit_access.h"

namespace judge {

using accel::StudentProcessLost;
using accel::wire::Cursor;
using accel::wire::Msg;
using accel::wire::Payload;
using Clock = std::chrono::steady_clock;

// --- WorkerBudget ---------------------------------------------------------------------------

void WorkerBudget::restart_deadline() {
  std::lock_guard<std::mutex> lock(mutex_);
  deadline_ = timeout_seconds > 0 ? Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                         std::chrono::duration<double>(timeout_seconds))
                                   : Clock::time_point::max();
}

void WorkerBudget::start_check() {
  restart_deadline();
  std::lock_guard<std::mutex> lock(mutex_);
  output_.clear();
  output_bytes_ = 0;
}

Clock::time_point WorkerBudget::deadline() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return deadline_;
}

std::string WorkerBudget::output() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return output_;
}

size_t WorkerBudget::output_bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return output_bytes_;
}

bool WorkerBudget::take_output(const char* data, size_t size) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (output_.size() < kOutputKept) output_.append(data, std::min(size, kOutputKept - output_.size()));
  output_bytes_ += size;
  return output_bytes_ <= output_limit;
}

// --- WorkerChannel --------------------------------------------------------------------------

namespace {

std::string mib(size_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g MiB", double(bytes) / double(1 << 20));
  return buf;
}

}  // namespace

WorkerChannel::WorkerChannel(std::shared_ptr<WorkerBudget> budget) : budget_(std::move(budget)) {
  auto started = start_confined({budget_->worker, "--serve"}, budget_->confinement, true);
  if (!started) throw StudentProcessLost("could not start the worker (" + started.error().message + ")");
  process_ = started.value();
  for (int fd : {process_.output_fd, process_.request_fd, process_.answer_fd})
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
}

WorkerChannel::~WorkerChannel() { stop(); }

void WorkerChannel::stop() {
  if (process_.pid > 0 && !reaped_) {
    kill(-process_.pid, SIGKILL);
    kill(process_.pid, SIGKILL);
    waitpid(process_.pid, &status_, 0);
    reaped_ = true;
  }
  for (int* fd : {&process_.output_fd, &process_.request_fd, &process_.answer_fd})
    if (*fd >= 0) close(*fd), *fd = -1;
}

void WorkerChannel::lost(const std::string& what, const std::string& hint) {
  stop();
  throw StudentProcessLost(what, hint);
}

/// The answers ended: the worker is gone. Says how, from its exit status.
void WorkerChannel::ended() {
  // Its last words may still be in the output pipe; it is exiting, so this is short.
  for (int i = 0; i < 50 && process_.output_fd >= 0; ++i) {
    char buf[65536];
    const ssize_t n = read(process_.output_fd, buf, sizeof buf);
    if (n > 0) {
      budget_->take_output(buf, size_t(n));
      continue;
    }
    if (n == 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (!reaped_) {
    // It closed the channel: it ends now, or is made to (a worker that closed fd 4 and went on).
    for (int i = 0; i < 100 && !reaped_; ++i) {
      if (waitpid(process_.pid, &status_, WNOHANG) == process_.pid) reaped_ = true;
      else std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  const bool sandboxed = budget_->confinement.sandbox;
  const bool signalled = reaped_ && ended_by_signal(status_, sandboxed);
  const std::string end = reaped_ ? describe_end(status_, sandboxed) : "closed the kit's channel";
  stop();
  if (signalled) throw StudentProcessLost(end);
  throw StudentProcessLost("the worker " + end + " before it answered",
                           "the student's code ended its process (exit, _Exit, abort?)");
}

void WorkerChannel::pump(bool for_writing) {
  const auto deadline = budget_->deadline();
  pollfd fds[2] = {{for_writing ? process_.request_fd : process_.answer_fd, short(for_writing ? POLLOUT : POLLIN), 0},
                   {process_.output_fd, POLLIN, 0}};
  const nfds_t count = process_.output_fd >= 0 ? 2 : 1;
  for (;;) {
    int wait_ms = -1;
    if (deadline != Clock::time_point::max()) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%g", budget_->timeout_seconds);
        lost(std::string("no answer within the time limit of ") + buf + " s",
             "an endless loop? (--timeout sets the limit)");
      }
      wait_ms = int(std::min<long long>(left, 1000));
    }
    const int ready = poll(fds, count, wait_ms);
    if (ready < 0 && errno != EINTR) lost(std::string("the judge could not wait for the worker: ") + strerror(errno), "");
    if (ready <= 0) continue;
    if (count == 2 && fds[1].revents) {
      char buf[65536];
      const ssize_t n = read(process_.output_fd, buf, sizeof buf);
      if (n > 0 && !budget_->take_output(buf, size_t(n)))
        lost("printed more than " + mib(budget_->output_limit),
             "the output limit: print less (no output per ray or per node)");
      if (n == 0) {
        close(process_.output_fd);
        process_.output_fd = -1;
        return;  // the worker closed its output: look at the channel again
      }
    }
    if (fds[0].revents) return;
  }
}

void WorkerChannel::send(Msg type, const std::string& payload) {
  std::string frame(8 + payload.size(), '\0');
  const uint32_t header[2] = {uint32_t(type), uint32_t(payload.size())};
  std::memcpy(frame.data(), header, 8);
  std::memcpy(frame.data() + 8, payload.data(), payload.size());
  size_t done = 0;
  while (done < frame.size()) {
    if (process_.request_fd < 0) ended();
    const ssize_t n = write(process_.request_fd, frame.data() + done, frame.size() - done);
    if (n > 0) {
      done += size_t(n);
      continue;
    }
    if (n < 0 && errno == EAGAIN) {
      pump(true);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    ended();  // EPIPE: it is gone
  }
}

Msg WorkerChannel::receive(std::string& payload) {
  for (;;) {
    if (in_.size() - in_at_ >= 8) {
      uint32_t header[2];
      std::memcpy(header, in_.data() + in_at_, 8);
      if (header[1] > accel::wire::kMaxPayload)
        lost("broke the kit's channel (a frame of " + std::to_string(header[1]) + " bytes)",
             "the student's code wrote to file descriptor 4?");
      if (in_.size() - in_at_ >= 8 + size_t(header[1])) {
        payload.assign(in_, in_at_ + 8, header[1]);
        in_at_ += 8 + header[1];
        if (in_at_ > (1u << 20) && in_at_ * 2 > in_.size()) in_.erase(0, in_at_), in_at_ = 0;
        return Msg(header[0]);
      }
    }
    if (answers_closed_) ended();
    char buf[1 << 16];
    const ssize_t n = read(process_.answer_fd, buf, sizeof buf);
    if (n > 0) {
      in_.append(buf, size_t(n));
    } else if (n == 0) {
      answers_closed_ = true;
    } else if (errno == EAGAIN) {
      pump(false);
    } else if (errno != EINTR) {
      answers_closed_ = true;
    }
  }
}

// --- listing --------------------------------------------------------------------------------

accel::Result<std::vector<accel::StudentRegistration>> list_worker(const std::shared_ptr<WorkerBudget>& budget) {
  std::vector<accel::StudentRegistration> out;
  try {
    WorkerChannel ch(budget);
    ch.send(Msg::Hello, "");
    std::string payload;
    for (;;) {
      const Msg m = ch.receive(payload);
      Cursor c(payload);
      if (m == Msg::HelloDone) {
        const auto version = c.get<uint32_t>();
        if (!c.complete() || version != accel::wire::kVersion)
          return accel::make_error(budget->worker + ": a worker of another accelviz version: rebuild it");
        return out;
      }
      if (m != Msg::Registration || out.size() >= 64)
        return accel::make_error(budget->worker + ": the worker's list of structures is not readable");
      accel::StudentRegistration r;
      const uint8_t kind = c.get<uint8_t>();
      r.optimized = c.get<uint8_t>() != 0;
      r.name = c.get_string(200);
      r.file = c.get_string(1000);
      if (!c.complete() || kind > uint8_t(accelviz::Kind::spheretree))
        return accel::make_error(budget->worker + ": the worker's list of structures is not readable");
      r.kind = accelviz::Kind(kind);
      out.push_back(std::move(r));
    }
  } catch (const StudentProcessLost& e) {
    return accel::make_error(std::string(e.what()) + (e.hint().empty() ? "" : ": " + e.hint()));
  }
}

std::vector<accel::StudentEntry> remote_entries(const std::vector<accel::StudentRegistration>& registrations,
                                                const std::shared_ptr<WorkerBudget>& budget) {
  std::vector<accel::StudentEntry> out;
  for (const accel::StudentRegistration& r : registrations) {
    const std::string name = r.name;
    out.push_back({r, [name, budget] { return std::make_unique<RemoteStudent>(name, budget); }});
  }
  return out;
}

// --- RemoteStudent --------------------------------------------------------------------------

namespace {

/// A frame the protocol does not allow here: the worker is not speaking the kit's language.
[[noreturn]] void garbled(Msg m) {
  throw StudentProcessLost("broke the kit's channel (an unexpected frame " + std::to_string(uint32_t(m)) + ")",
                           "the student's code wrote to file descriptor 4?");
}

/// The exception the student's code threw, as the in-process adapter would see it.
[[noreturn]] void rethrow(const std::string& payload) {
  Cursor c(payload);
  const bool kit = c.get<uint8_t>() != 0;
  const std::string message = c.get_string();
  if (kit) throw accel::KitError(message);
  throw std::runtime_error(message);
}

accel::wire::WireRay to_wire(const accelviz::Ray& r) {
  return {{r.origin.x, r.origin.y, r.origin.z}, {r.direction.x, r.direction.y, r.direction.z}, r.tmin, r.tmax};
}

accel::wire::WireRay to_wire(const accel::Ray& r) {
  return {{r.org.x, r.org.y, r.org.z}, {r.dir.x, r.dir.y, r.dir.z}, r.tmin, r.tmax};
}

bool same_ray(const accel::wire::WireRay& a, const accel::wire::WireRay& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Appends a request's rays: their count, then each ray.
Payload& put_rays(Payload& p, const std::vector<accel::wire::WireRay>& rays) {
  return p.put(uint32_t(rays.size())).put_bytes(rays.data(), rays.size() * sizeof(rays[0]));
}

/// Replays one build-log frame onto `log`; false for a frame that is not one.
bool replay_build(Msg m, Cursor& c, accelviz::BuildLog& log) {
  switch (m) {
    case Msg::Node: {
      const auto id = c.get<uint32_t>(), parent = c.get<uint32_t>();
      const auto depth = c.get<int32_t>();
      const auto box = c.get<accelviz::Box>();
      const auto prims = c.get_array<uint32_t>(c.get<uint32_t>());
      if (c.complete()) log.node(id, parent, depth, box, prims.data(), prims.size());
      break;
    }
    case Msg::Sphere: {
      const auto id = c.get<uint32_t>();
      const auto s = c.get<accelviz::Sphere>();
      if (c.complete()) log.sphere(id, s);
      break;
    }
    case Msg::Split: {
      const auto id = c.get<uint32_t>();
      const auto axis = c.get<int32_t>();
      const auto pos = c.get<float>(), cost = c.get<float>(), leaf_cost = c.get<float>();
      const auto left = c.get<uint32_t>(), right = c.get<uint32_t>();
      if (c.complete()) log.split(id, axis, pos, cost, leaf_cost, left, right);
      break;
    }
    case Msg::Candidates: {
      const auto id = c.get<uint32_t>();
      const auto axis = c.get<int32_t>();
      const auto list = c.get_array<accelviz::Candidate>(c.get<uint32_t>());
      if (c.complete()) log.candidates(id, axis, list);
      break;
    }
    case Msg::Leaf: {
      const auto id = c.get<uint32_t>();
      const auto why = c.get<int32_t>();
      const auto prims = c.get_array<uint32_t>(c.get<uint32_t>());
      if (c.complete()) log.leaf(id, prims.data(), prims.size(), accelviz::LeafWhy(std::clamp(why, 0, 3)));
      break;
    }
    case Msg::GridResolution: {
      const auto box = c.get<accelviz::Box>();
      const auto nx = c.get<int32_t>(), ny = c.get<int32_t>(), nz = c.get<int32_t>();
      if (c.complete()) log.grid_resolution(box, nx, ny, nz);
      break;
    }
    case Msg::CellFilled: {
      const auto x = c.get<int32_t>(), y = c.get<int32_t>(), z = c.get<int32_t>();
      const auto prim = c.get<uint32_t>();
      if (c.complete()) log.cell_filled(x, y, z, prim);
      break;
    }
    default:
      return false;
  }
  if (!c.complete()) garbled(m);
  return true;
}

/// Replays one traversal-log frame onto `log`; false for a frame that is not one.
bool replay_traversal(Msg m, Cursor& c, accelviz::TraversalLog log) {
  switch (m) {
    case Msg::Visit:
    case Msg::Push:
    case Msg::Pop: {
      const auto node = c.get<uint32_t>();
      const auto depth = c.get<int32_t>();
      const auto a = c.get<float>(), b = c.get<float>();
      if (!c.complete()) break;
      if (m == Msg::Visit) log.visit(node, depth, a, b);
      else if (m == Msg::Push) log.push(node, depth, a);
      else log.pop(node, depth, a);
      break;
    }
    case Msg::EnterCell: {
      const auto x = c.get<int32_t>(), y = c.get<int32_t>(), z = c.get<int32_t>();
      const auto t0 = c.get<float>(), t1 = c.get<float>();
      if (c.complete()) log.enter_cell(x, y, z, t0, t1);
      break;
    }
    case Msg::Cull: {
      const auto node = c.get<uint32_t>();
      const auto depth = c.get<int32_t>(), why = c.get<int32_t>();
      const auto t = c.get<float>();
      if (c.complete()) log.cull(node, depth, why == 0 ? accelviz::Cull::MissedBounds : accelviz::Cull::BeyondClosestHit, t);
      break;
    }
    case Msg::Tested: {
      const auto prim = c.get<uint32_t>();
      const bool hit = c.get<uint8_t>() != 0;
      const auto t = c.get<float>();
      if (c.complete()) log.triangle_tested(prim, hit, t);
      break;
    }
    case Msg::NewClosest: {
      const auto prim = c.get<uint32_t>();
      const auto t = c.get<float>();
      if (c.complete()) log.new_closest(prim, t);
      break;
    }
    case Msg::GridDda: {
      const auto cell = c.get_array<int32_t>(3), step = c.get_array<int32_t>(3);
      const auto t_max = c.get_array<float>(3), t_delta = c.get_array<float>(3);
      if (!c.complete()) break;
      const int ci[3] = {cell[0], cell[1], cell[2]}, si[3] = {step[0], step[1], step[2]};
      log.grid_dda(ci, si, t_max.data(), t_delta.data());
      break;
    }
    case Msg::KdSplit: {
      const auto t_min = c.get<float>(), t_split = c.get<float>(), t_max = c.get<float>();
      const auto near_child = c.get<uint32_t>(), far_child = c.get<uint32_t>();
      const auto axis = c.get<int32_t>();
      if (c.complete()) log.kd_split(t_min, t_split, t_max, near_child, far_child, axis);
      break;
    }
    case Msg::KdFarPop: {
      const auto t_hit = c.get<float>(), t_split = c.get<float>();
      const auto far_child = c.get<uint32_t>();
      const bool exits = c.get<uint8_t>() != 0;
      if (c.complete()) log.kd_far_pop(t_hit, t_split, far_child, exits);
      break;
    }
    case Msg::OctreeChildren: {
      const auto mask = c.get<uint32_t>();
      const auto n = c.get<int32_t>();
      const auto children = c.get_array<accelviz::OctreeChild>(size_t(std::clamp(n, 0, 8)));
      if (c.complete()) log.octree_children(mask, children.data(), int(children.size()));
      break;
    }
    default:
      return false;
  }
  if (!c.complete()) garbled(m);
  return true;
}

}  // namespace

RemoteStudent::RemoteStudent(std::string name, std::shared_ptr<WorkerBudget> budget)
    : name_(std::move(name)), budget_(std::move(budget)) {}

WorkerChannel& RemoteStudent::channel() const {
  if (!channel_) throw accel::KitError("no structure was built");
  return *channel_;
}

void RemoteStudent::build(const accelviz::Scene& scene, accelviz::BuildLog& log) {
  std::lock_guard<std::mutex> lock(mutex_);
  pending_.clear();
  channel_.reset();  // a new build is a new object: a new process, nothing left of the last
  channel_ = std::make_unique<WorkerChannel>(budget_);
  const uint32_t n = scene.size();
  std::vector<accelviz::Triangle> triangles(n);
  std::vector<unsigned char> degenerate(n);
  for (uint32_t i = 0; i < n; ++i) triangles[i] = scene.triangle(i), degenerate[i] = scene.is_degenerate(i);
  Payload p;
  p.put_string(name_).put(uint8_t(scene.is_2d())).put(uint8_t(log.recording())).put(scene.bounds()).put(n);
  p.put_bytes(triangles.data(), n * sizeof(accelviz::Triangle)).put_bytes(degenerate.data(), n);
  channel_->send(Msg::Build, p.bytes());
  // The kit's listener may refuse a call (a KitError): the worker goes on building, so its
  // frames are read to the end before the first refusal is thrown.
  std::exception_ptr refused;
  std::string payload;
  for (;;) {
    const Msg m = channel_->receive(payload);
    if (m == Msg::BuildDone) break;
    if (m == Msg::Threw) rethrow(payload);
    Cursor c(payload);
    if (refused) {
      if (m < Msg::Node || m > Msg::CellFilled) garbled(m);
      continue;
    }
    try {
      if (!replay_build(m, c, log)) garbled(m);
    } catch (const StudentProcessLost&) {
      throw;
    } catch (...) {
      refused = std::current_exception();
    }
  }
  if (refused) std::rethrow_exception(refused);
}

accelviz::Hit RemoteStudent::take_answer(accelviz::TraversalLog log) const {
  std::exception_ptr refused;
  std::string payload;
  for (;;) {
    const Msg m = channel().receive(payload);
    Cursor c(payload);
    if (m == Msg::Answer) {
      const auto h = c.get<accel::wire::WireHit>();
      if (!c.complete()) garbled(m);
      if (refused) std::rethrow_exception(refused);
      return accelviz::Hit{h.prim, h.t, h.u, h.v};
    }
    if (m == Msg::Threw) {
      if (refused) std::rethrow_exception(refused);
      rethrow(payload);
    }
    if (refused || !log.listening()) {
      if (m < Msg::Visit || m > Msg::OctreeChildren) garbled(m);
      continue;
    }
    try {
      if (!replay_traversal(m, c, log)) garbled(m);
    } catch (const StudentProcessLost&) {
      throw;
    } catch (...) {
      refused = std::current_exception();  // e.g. the kit's step budget: the rest is read, not replayed
    }
  }
}

void RemoteStudent::skip_pending() const {
  const Pending skipped = pending_.front();
  pending_.pop_front();
  try {
    take_answer(accelviz::TraversalLog());
  } catch (const StudentProcessLost&) {
    throw;
  } catch (...) {
    drop_fast_after_throw(skipped);
  }
}

void RemoteStudent::drop_fast_after_throw(const Pending& traced) const {
  // The worker runs no fast query for a ray whose listened-to query threw (an endless loop
  // stopped by the step budget would loop on without a log): none is owed.
  if (traced.mode == accel::wire::kTraced && !pending_.empty() && pending_.front().mode == accel::wire::kFast &&
      same_ray(pending_.front().ray, traced.ray))
    pending_.pop_front();
}

void RemoteStudent::drop_pending() const {
  while (!pending_.empty()) skip_pending();
}

accelviz::Hit RemoteStudent::intersect(const accelviz::Ray& ray, accelviz::TraversalLog log) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const accel::wire::WireRay wire = to_wire(ray);
  const uint8_t mode = log.listening() ? accel::wire::kTraced : accel::wire::kFast;
  // The answers the grader announced arrive in order; one it did not ask for after all (it
  // moves on after an exception) is read and dropped.
  while (!pending_.empty()) {
    const Pending next = pending_.front();
    if (next.mode != mode || !same_ray(next.ray, wire)) {
      skip_pending();
      continue;
    }
    pending_.pop_front();
    try {
      return take_answer(log);
    } catch (const StudentProcessLost&) {
      throw;
    } catch (...) {
      drop_fast_after_throw(next);
      throw;
    }
  }
  Payload p;
  put_rays(p.put(mode).put(uint8_t(accelviz::KitAccess::kernel(ray))), {wire});
  channel().send(Msg::Query, p.bytes());
  return take_answer(log);
}

void RemoteStudent::expect(const std::vector<accel::Ray>& rays, accel::Kernel kernel, uint8_t modes) {
  std::lock_guard<std::mutex> lock(mutex_);
  drop_pending();
  std::vector<accel::wire::WireRay> wire(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    wire[i] = to_wire(rays[i]);
    for (const uint8_t mode : {accel::wire::kTraced, accel::wire::kFast})
      if (modes & mode) pending_.push_back({wire[i], mode});
  }
  Payload p;
  put_rays(p.put(modes).put(uint8_t(kernel)), wire);
  channel().send(Msg::Query, p.bytes());
}

double RemoteStudent::time_rays(const std::vector<accel::Ray>& rays, accel::Kernel kernel, unsigned threads,
                                std::vector<accel::Hit>* answers) {
  std::lock_guard<std::mutex> lock(mutex_);
  drop_pending();
  std::vector<accel::wire::WireRay> wire(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) wire[i] = to_wire(rays[i]);
  Payload p;
  put_rays(p.put(uint8_t(kernel)).put(uint32_t(threads)), wire);
  const auto start = Clock::now();
  channel().send(Msg::Time, p.bytes());
  std::string payload;
  const Msg m = channel().receive(payload);
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (m == Msg::Threw) rethrow(payload);
  if (m != Msg::Hits) garbled(m);
  Cursor c(payload);
  const auto hits = c.get_array<accel::wire::WireHit>(c.get<uint32_t>());
  if (!c.complete() || hits.size() != rays.size()) garbled(m);
  answers->resize(rays.size());
  for (size_t i = 0; i < hits.size(); ++i) (*answers)[i] = accel::Hit{hits[i].prim, hits[i].t, hits[i].u, hits[i].v};
  return seconds;
}

}  // namespace judge
