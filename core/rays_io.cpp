#include "rays_io.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "from_chars_real.h"
#include "input_files.h"

namespace accel {

bool parse_ray_number(std::string_view token, float* out) {
  bool negative = false;
  if (!token.empty() && (token[0] == '+' || token[0] == '-')) {
    negative = token[0] == '-';
    token.remove_prefix(1);
  }
  if (token.empty() || token[0] == '+' || token[0] == '-') return false;
  auto format = std::chars_format::general;
  if (token.size() > 2 && token[0] == '0' && (token[1] == 'x' || token[1] == 'X')) {
    token.remove_prefix(2);  // from_chars' hex format takes the digits without "0x"
    format = std::chars_format::hex;
  }
  float value;
  const char* end = token.data() + token.size();
  auto [ptr, ec] = from_chars_real(token.data(), end, value, format);
  if (ec != std::errc() || ptr != end) return false;
  *out = negative ? -value : value;
  return true;
}

TokenLines::TokenLines(const std::string& text, std::string source_name)
    : in_(text), source_name_(std::move(source_name)) {}

bool TokenLines::next() {
  while (std::getline(in_, line_)) {
    ++line_no_;
    tokens_.clear();
    const std::string_view s(line_);
    size_t i = 0;
    while (i < s.size()) {
      while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
      size_t j = i;
      while (j < s.size() && !std::isspace(static_cast<unsigned char>(s[j]))) ++j;
      if (j > i) tokens_.push_back(s.substr(i, j - i));
      i = j;
    }
    if (!tokens_.empty() && tokens_[0][0] != '#') return true;
  }
  return false;
}

Error TokenLines::error(const std::string& what) const {
  return make_error(source_name_ + ":" + std::to_string(line_no_) + ": " + what);
}

Result<std::string> read_text_file(const std::string& path, const std::string& what) {
  if (Status fetched = fetch_missing_input(path); !fetched) return fetched.error();  // the page: from its folder
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    return make_error(path + ": cannot open " + what + " for reading: Is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(path + ": cannot open " + what + " for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();  // to the end: a FIFO is read until its writer closes it
  if (in.bad()) return make_error(path + ": read error");
  return buffer.str();
}

Result<std::vector<Ray>> parse_rays(const std::string& text, const std::string& source_name) {
  std::vector<Ray> rays;
  TokenLines lines(text, source_name);
  auto fail = [&](const std::string& what) { return lines.error(what); };
  while (lines.next()) {
    const std::vector<std::string_view>& tok = lines.tokens();
    if (tok.size() != 6 && tok.size() != 8)
      return fail("expected 6 or 8 numbers (ox oy oz dx dy dz [tmin tmax]), got " + std::to_string(tok.size()));
    float v[8] = {0, 0, 0, 0, 0, 0, 0, kInf};
    for (size_t k = 0; k < tok.size(); ++k) {
      if (!parse_ray_number(tok[k], &v[k]))
        return fail("malformed number '" + printable(tok[k]) + "' (field " + std::to_string(k + 1) + ")");
      if (std::isnan(v[k])) return fail("NaN in field " + std::to_string(k + 1));
      if (k < 6 && std::isinf(v[k]))
        return fail("origin and direction must be finite (field " + std::to_string(k + 1) + " is '" +
                    printable(tok[k]) + "')");
    }
    if (v[3] == 0.0f && v[4] == 0.0f && v[5] == 0.0f) return fail("direction is the zero vector");
    if (v[6] == kInf) return fail("tmin is +inf");
    if (v[7] == -kInf) return fail("tmax is -inf");
    Ray r;
    r.org = Vec3(v[0], v[1], v[2]);
    r.dir = Vec3(v[3], v[4], v[5]);
    r.tmin = v[6];
    r.tmax = v[7];
    rays.push_back(r);
  }
  return rays;
}

Result<std::vector<Ray>> read_rays(const std::string& path) {
  auto text = read_text_file(path, "rays file");
  if (!text) return text.error();
  return parse_rays(text.value(), path);
}

std::string format_ray_number(float v) {
  if (std::isinf(v)) return v > 0.0f ? "inf" : "-inf";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%a", double(v));
  return buf;
}

std::string format_ray_line(const Ray& ray, bool interval) {
  std::string line;
  // Appended piece by piece: GCC 12 warns (-Wrestrict, falsely) on `" " + std::string`.
  const float values[8] = {ray.org.x, ray.org.y, ray.org.z, ray.dir.x, ray.dir.y, ray.dir.z, ray.tmin, ray.tmax};
  for (int i = 0; i < (interval ? 8 : 6); ++i) {
    if (i > 0) line += ' ';
    line += format_ray_number(values[i]);
  }
  return line;
}

std::string format_hit_row(size_t ray_index, const Hit& hit) {
  char buf[128];
  if (!hit.valid()) {
    std::snprintf(buf, sizeof buf, "%zu,-1,inf,0,0\n", ray_index);
  } else {
    std::snprintf(buf, sizeof buf, "%zu,%d,%.9g,%.9g,%.9g\n", ray_index, hit.prim, double(hit.t), double(hit.u),
                  double(hit.v));
  }
  return buf;
}

namespace {

/// Writes all of `data` to `fd` in chunks, retrying short writes and EINTR; stops (false,
/// errno 0) once `*cancel` is set. On an error returns false with errno set.
bool write_all(int fd, std::string_view data, const std::atomic<bool>* cancel) {
  constexpr size_t kChunk = size_t(1) << 20;
  while (!data.empty()) {
    if (cancel && cancel->load(std::memory_order_relaxed)) {
      errno = 0;
      return false;
    }
    const ssize_t n = ::write(fd, data.data(), std::min(data.size(), kChunk));
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data.remove_prefix(size_t(n));
  }
  return true;
}

/// "path: what: strerror(err)", or "path: not written (interrupted)" for err == 0.
Error io_error(const std::string& path, const char* what, int err) {
  if (err == 0) return make_error(path + ": not written (interrupted)");
  return make_error(path + ": " + what + ": " + std::strerror(err));
}

/// Writes straight into an existing device, FIFO, socket or open file (/dev/full,
/// /dev/stdout, a pipe): there is no file to replace atomically, and a temporary file beside
/// it would be created in /dev. O_APPEND, so /dev/stdout redirected to a log adds to it;
/// O_NONBLOCK only for the open, so a FIFO without a reader is an error (ENXIO) instead of
/// a wait.
Status write_special(const std::string& path, std::string_view content, const std::atomic<bool>* cancel) {
  // /dev/stdout and /dev/fd/N name a descriptor this process has: write through a copy of
  // it, which shares its offset (opening the path anew would not, and would write over what
  // the shell writes into the same file).
  int own_fd = -1;
  if (path == "/dev/stdout") own_fd = 1;
  if (path == "/dev/stderr") own_fd = 2;
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    const std::string_view p(prefix);
    if (path.rfind(p, 0) != 0) continue;
    int n = -1;
    const char* end = path.data() + path.size();
    auto [ptr, ec] = std::from_chars(path.data() + p.size(), end, n);
    if (ec == std::errc() && ptr == end && n >= 0) own_fd = n;
  }
  const int fd = own_fd >= 0 ? ::fcntl(own_fd, F_DUPFD_CLOEXEC, 0)
                             : ::open(path.c_str(), O_WRONLY | O_APPEND | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return io_error(path, "cannot open for writing", errno);
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0 && own_fd < 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  const bool ok = write_all(fd, content, cancel);
  const int err = errno;
  if (::close(fd) != 0 && ok) return io_error(path, "write failed", errno);
  if (!ok) return io_error(path, "write failed", err);
  return {};
}

/// Where write_file_atomic puts `path`'s content.
struct OutputTarget {
  bool special = false;  ///< written directly (write_special)
  std::string file;      ///< else: the regular file replaced (a link resolved)
};

Result<OutputTarget> output_target(const std::string& path) {
  OutputTarget out{false, path};
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return out;  // a new file (or an error the open reports)
  const bool link = S_ISLNK(st.st_mode);
  if (link && ::stat(path.c_str(), &st) != 0) return out;  // a dangling link: replaced
  if (S_ISDIR(st.st_mode)) return make_error(path + ": cannot open for writing: Is a directory");
  // /dev/stdout, /dev/fd/N, /proc/self/fd/N name an open file even when it is a regular
  // one: write into it rather than replace what it points to.
  const bool names_fd = path.rfind("/dev/", 0) == 0 || path.rfind("/proc/", 0) == 0;
  if (!S_ISREG(st.st_mode) || names_fd) {
    out.special = true;
  } else if (link) {
    if (char* resolved = ::realpath(path.c_str(), nullptr)) {
      out.file = resolved;
      std::free(resolved);
    }
  }
  return out;
}

/// Creates a new temporary file beside `file` (same file system, so rename() is atomic):
/// its descriptor (-1 with errno set on failure) and name.
int create_temp(const std::string& file, std::string* tmp) {
  int fd = -1;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    *tmp = file + ".tmp." + std::to_string(::getpid());
    if (attempt) *tmp += '.' + std::to_string(attempt);
    fd = ::open(tmp->c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST) break;
  }
  return fd;
}

}  // namespace

Status check_writable(const std::string& path) {
  auto target = output_target(path);
  if (!target) return target.error();
  if (target.value().special) return {};  // opening a FIFO to probe it would end its reader's input
  std::string tmp;
  const int fd = create_temp(target.value().file, &tmp);
  if (fd < 0) return io_error(path, "cannot open for writing", errno);
  ::close(fd);
  ::unlink(tmp.c_str());
  return {};
}

Status write_file_atomic(const std::string& path, const std::string& content, const std::atomic<bool>* cancel) {
  auto target = output_target(path);
  if (!target) return target.error();
  if (target.value().special) return write_special(path, content, cancel);
  std::string tmp;
  const int fd = create_temp(target.value().file, &tmp);
  if (fd < 0) return io_error(path, "cannot open for writing", errno);
  const bool ok = write_all(fd, content, cancel);
  int err = errno;
  const bool closed = ::close(fd) == 0;
  if (ok && !closed) err = errno;
  if (!ok || !closed || (cancel && cancel->load(std::memory_order_relaxed))) {
    ::unlink(tmp.c_str());
    return io_error(path, "write failed", ok && closed ? 0 : err);
  }
  if (::rename(tmp.c_str(), target.value().file.c_str()) != 0) {
    err = errno;
    ::unlink(tmp.c_str());
    return io_error(path, "cannot replace the output file", err);
  }
  return {};
}

Status write_hits_csv(const std::string& path, const std::vector<Hit>& hits, const std::atomic<bool>* cancel) {
  std::string content = "ray,prim,t,u,v\n";
  content.reserve(content.size() + hits.size() * 40);
  for (size_t i = 0; i < hits.size(); ++i) {
    if (cancel && i % 65536 == 0 && cancel->load(std::memory_order_relaxed)) return io_error(path, "", 0);
    content += format_hit_row(i, hits[i]);
  }
  return write_file_atomic(path, content, cancel);
}

}  // namespace accel
