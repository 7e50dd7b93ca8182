#pragma once
// The wire between the judge (`accelviz-cli check`, which holds no student code) and a
// student's worker process (`accelviz-worker`: the student's files and the kit's runtime,
// nothing of the core's structures, registry or grader).
//
// A frame is a 4-byte type, a 4-byte payload size, then the payload, in the machine's byte
// order (both ends run on one machine). The judge sends requests (a scene to build over,
// rays to answer); the worker answers with what the student's code did: each build-log
// and traversal-log call as one frame, then the answer or the exception. What comes back
// is data for the judge to check, never a verdict, and the judge reads it as it would
// read a hostile file: every size and count is bounded and checked.
//
// The worker reads requests on fd 3 and writes frames on fd 4 (kRequestFd, kAnswerFd), so
// whatever the student's code prints on stdout or stderr cannot be taken for a frame.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

namespace accel::wire {

inline constexpr int kRequestFd = 3;
inline constexpr int kAnswerFd = 4;
/// The largest payload either side accepts (a 300k-ray request is 10 MB).
inline constexpr uint32_t kMaxPayload = 64u << 20;
/// Bumped whenever a frame's layout changes; the judge refuses a worker of another version.
inline constexpr uint32_t kVersion = 1;

enum class Msg : uint32_t {
  // judge -> worker
  Hello = 1,  ///< -> Registration*, then HelloDone {version}
  Build,      ///< {name, scene} -> the build log's frames, then BuildDone or Threw
  Query,      ///< {mode, kernel, rays} -> per ray: [traversal frames..., Answer|Threw] per mode
  Time,       ///< {kernel, threads, rays} -> Hits (every ray, no log listening)
  Quit,
  // worker -> judge
  Registration = 100,  ///< {kind, optimized, name, file}
  HelloDone,
  Node,  ///< the build log's calls, one frame each
  Sphere,
  Split,
  Candidates,
  Leaf,
  GridResolution,
  CellFilled,
  BuildDone,
  Visit,  ///< the traversal log's calls, one frame each
  EnterCell,
  Cull,
  Push,
  Pop,
  Tested,
  NewClosest,
  GridDda,
  KdSplit,
  KdFarPop,
  OctreeChildren,
  Answer,  ///< {prim, t, u, v}
  Threw,   ///< {kit, message}: the student's code threw (kit: the kit's own check, e.g. the step budget)
  Hits,    ///< {count, (prim, t, u, v)*}
};

/// Query modes: the grader asks for each ray listened to, then on the fast path.
enum QueryMode : uint8_t { kTraced = 1, kFast = 2 };

/// The longest exception message carried (the rest is cut).
inline constexpr size_t kMaxMessage = 2000;

/// A payload being written: plain values and length-prefixed arrays and strings.
class Payload {
 public:
  template <class T>
  Payload& put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&v);
    bytes_.append(p, sizeof(T));
    return *this;
  }
  Payload& put_bytes(const void* p, size_t n) {
    bytes_.append(static_cast<const char*>(p), n);
    return *this;
  }
  Payload& put_string(const std::string& s) {
    put(uint32_t(s.size()));
    return put_bytes(s.data(), s.size());
  }
  const std::string& bytes() const { return bytes_; }
  void clear() { bytes_.clear(); }

 private:
  std::string bytes_;
};

/// Reads a received payload. Every read is bounds-checked: past the end (or a count that
/// cannot fit) it sets failed() and yields zeros, so a malformed frame is one check at the
/// end, never a read out of bounds.
class Cursor {
 public:
  Cursor(const char* data, size_t size) : p_(data), end_(data + size) {}
  explicit Cursor(const std::string& s) : Cursor(s.data(), s.size()) {}

  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v{};
    if (size_t(end_ - p_) < sizeof(T)) {
      failed_ = true;
      p_ = end_;
      return v;
    }
    std::memcpy(&v, p_, sizeof(T));
    p_ += sizeof(T);
    return v;
  }
  /// `count` elements of T, or none (and failed()) when they are not all there.
  template <class T>
  std::vector<T> get_array(size_t count) {
    std::vector<T> out;
    if (count > size_t(end_ - p_) / sizeof(T)) {
      failed_ = true;
      p_ = end_;
      return out;
    }
    out.resize(count);
    if (count) std::memcpy(out.data(), p_, count * sizeof(T));
    p_ += count * sizeof(T);
    return out;
  }
  std::string get_string(size_t max = kMaxMessage) {
    const uint32_t n = get<uint32_t>();
    if (n > size_t(end_ - p_) || n > max) {
      failed_ = true;
      p_ = end_;
      return {};
    }
    std::string s(p_, n);
    p_ += n;
    return s;
  }
  bool failed() const { return failed_; }
  /// Everything read, nothing left over, nothing missing.
  bool complete() const { return !failed_ && p_ == end_; }

 private:
  const char* p_;
  const char* end_;
  bool failed_ = false;
};

/// A ray as it travels: the core's Ray fields, in floats.
struct WireRay {
  float org[3], dir[3], tmin, tmax;
};
/// A triangle as it travels: its three vertices.
struct WireTriangle {
  float v[9];
};
struct WireHit {
  int32_t prim;
  float t, u, v;
};

}  // namespace accel::wire
