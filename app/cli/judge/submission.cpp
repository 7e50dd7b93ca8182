// A student's submission (a folder of .cpp files) compiled into a worker: the kit's header
// and runtime library (accelviz_kit_worker) and the student's files, nothing of the core.
// The judge copies the submission's regular files into a private folder first (never
// following a link: a link to a lecturer's file would be read with the judge's rights, and
// the student's own copy of the kit's header is left out, so the kit's is used), then runs
// the compiler in the sandbox, which sees that copy, the kit and /usr, and writes only the
// worker's folder.
#include <openssl/evp.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "judge/confinement.h"
#include "judge/grading.h"
#include "student/worker_protocol.h"

namespace cli {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// The most a submission may hold: enough for any assignment, too little to fill a disk.
constexpr size_t kMaxFiles = 64;
constexpr size_t kMaxFileBytes = size_t(1) << 20;
/// What a compile may take.
constexpr double kCompileSeconds = 180.0;
constexpr size_t kCompileMemory = size_t(3) << 30;
constexpr size_t kCompilerOutputKept = size_t(64) << 10;

/// The submission's own files: regular files ending in .cpp, .h, .hpp or .inl, directly in
/// `dir`, sorted by name (the student's accelviz_student.h is not one of them).
std::vector<fs::path> submission_files(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const fs::path& p = entry.path();
    const std::string ext = p.extension().native();
    if (!entry.is_regular_file(ec) || entry.is_symlink(ec)) continue;  // no links: see the file's top
    if (ext != ".cpp" && ext != ".h" && ext != ".hpp" && ext != ".inl") continue;
    if (p.filename() == "accelviz_student.h") continue;
    files.push_back(p);
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string read_file(const fs::path& p, size_t max) {
  std::ifstream in(p, std::ios::binary);
  std::string s(max + 1, '\0');
  in.read(s.data(), std::streamsize(max + 1));
  s.resize(size_t(in.gcount()));
  return s;
}

/// The compiler's first error, for the student: from the first line that says "error" to
/// the next diagnostic (at most 8 lines), the private copy's path replaced by the folder's name.
std::string first_error(const std::string& output, const std::string& private_dir, const std::string& shown_dir) {
  std::vector<std::string> lines;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    for (size_t at; (at = line.find(private_dir)) != std::string::npos;) line.replace(at, private_dir.size(), shown_dir);
    lines.push_back(line);
  }
  auto first = std::find_if(lines.begin(), lines.end(), [](const std::string& l) {
    return l.find("error") != std::string::npos;
  });
  if (first == lines.end()) first = lines.begin();
  std::string out;
  for (auto it = first; it != lines.end() && it - first < 8; ++it) {
    if (it != first && it->find(": note:") == std::string::npos && it->find(": error") != std::string::npos) break;
    out += *it + "\n";
  }
  return out.empty() ? "the compiler failed without a message" : out;
}

/// Runs the compiler confined, its output kept (the first kCompilerOutputKept bytes), for
/// at most kCompileSeconds: the exit status, or -1 when it was stopped for its time.
int run_compiler(const std::vector<std::string>& argv, const judge::Confinement& c, std::string* output) {
  auto started = judge::start_confined(argv, c, false);
  if (!started) {
    *output = started.error().message;
    return -2;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(kCompileSeconds);
  const int fd = started.value().output_fd;
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, int(std::min<long long>(left.count(), 1000))) <= 0) continue;
    char buf[65536];
    const ssize_t n = read(fd, buf, sizeof buf);
    if (n <= 0) break;
    if (output->size() < kCompilerOutputKept) output->append(buf, std::min(size_t(n), kCompilerOutputKept - output->size()));
  }
  close(fd);
  const pid_t pid = started.value().pid;
  if (timed_out) kill(-pid, SIGKILL), kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  if (timed_out) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

}  // namespace

std::string submission_hash(const std::string& dir, const CheckOptions& o) {
  EVP_MD_CTX* ctx = EVP_MD_CTX_new();
  EVP_DigestInit_ex(ctx, EVP_sha256(), nullptr);
  auto add = [&](const std::string& s) {
    const uint64_t n = s.size();  // length first: ("ab","c") and ("a","bc") differ
    EVP_DigestUpdate(ctx, &n, sizeof n);
    EVP_DigestUpdate(ctx, s.data(), s.size());
  };
  // This grader (the judge's program, the kit's header and runtime, the options that
  // change a verdict) and the submission's files: a new grader grades everyone again.
  static const std::string grader = read_file("/proc/self/exe", size_t(256) << 20) +
                                    read_file(ACCEL_KIT_WORKER_LIB, size_t(256) << 20) +
                                    read_file(fs::path(ACCEL_KIT_INCLUDE_DIR) / "accelviz_student.h", size_t(8) << 20);
  add("accelviz-grade " + std::to_string(accel::wire::kVersion));
  add(grader);
  char opts[128];
  std::snprintf(opts, sizeof opts, "%.17g %d %d %.17g", o.ray_scale, int(o.time), int(o.sandbox), o.timeout);
  add(opts);
  add(o.shared);
  for (const fs::path& f : submission_files(dir)) {
    add(f.filename().native());
    add(read_file(f, kMaxFileBytes));
  }
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  EVP_DigestFinal_ex(ctx, digest, &len);
  EVP_MD_CTX_free(ctx);
  std::string hex;
  char b[3];
  for (unsigned i = 0; i < len; ++i) std::snprintf(b, sizeof b, "%02x", digest[i]), hex += b;
  return hex;
}

Submission compile_submission(const std::string& dir, const std::string& build_dir, const CheckOptions& o) {
  Submission sub;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    sub.error_for_user = dir + ": no such folder";
    return sub;
  }
  const auto start = std::chrono::steady_clock::now();
  auto compile_failed = [&](const std::string& error) {
    sub.compile = {{"ok", false},
                   {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
                   {"error", error}};
    return sub;
  };
  // A fresh private folder: the copy of the sources (read-only to the compiler) and the
  // worker's folder (the only place it writes).
  const fs::path build = fs::absolute(build_dir, ec);
  fs::remove_all(build, ec);
  const fs::path src = build / "src", out = build / "bin";
  fs::create_directories(src, ec);
  fs::create_directories(out, ec);
  if (ec) {
    sub.error_for_user = build.native() + ": cannot create the folder: " + ec.message();
    return sub;
  }
  const std::vector<fs::path> files = submission_files(dir);
  size_t sources = 0;
  for (const fs::path& f : files) sources += f.extension() == ".cpp";
  if (sources == 0) return compile_failed(dir + ": no .cpp file in the submission");
  if (files.size() > kMaxFiles) return compile_failed(dir + ": more than " + std::to_string(kMaxFiles) + " files");
  std::vector<std::string> argv = {fs::canonical(ACCEL_KIT_CXX, ec).native(), "-std=c++20", "-O2", "-pthread",
                                   "-fdiagnostics-color=never", "-fmax-errors=5", "-I", ACCEL_KIT_INCLUDE_DIR};
  for (const fs::path& f : files) {
    if (fs::file_size(f, ec) > kMaxFileBytes) return compile_failed(f.filename().native() + ": larger than 1 MiB");
    fs::copy_file(f, src / f.filename(), fs::copy_options::overwrite_existing, ec);
    if (ec) return compile_failed(f.filename().native() + ": cannot be read");
    if (f.extension() == ".cpp") argv.push_back((src / f.filename()).native());
  }
  const std::string worker = (out / "accelviz-worker").native();
  argv.insert(argv.end(), {ACCEL_KIT_WORKER_LIB, "-o", worker});
  if (std::string(ACCEL_KIT_CXX_FLAGS) != "") argv.insert(argv.begin() + 1, ACCEL_KIT_CXX_FLAGS);

  judge::Confinement c;
  c.sandbox = o.sandbox;
  c.allow_processes = true;  // the compiler's driver runs cc1plus, as and ld
  c.memory_bytes = kCompileMemory;
  c.cpu_seconds = kCompileSeconds;
  c.file_bytes = size_t(256) << 20;
  c.read_only = {src.native(), ACCEL_KIT_INCLUDE_DIR, ACCEL_KIT_WORKER_LIB};
  c.writable = {out.native()};
  c.workdir = out.native();
  if (!o.sandbox && geteuid() == 0) {
    // The compiler runs as nobody without a sandbox: it writes only the worker's folder.
    if (chown(out.c_str(), 65534, 65534) != 0) return compile_failed(out.native() + ": cannot hand it to nobody");
  }
  std::string output;
  const int status = run_compiler(argv, c, &output);
  if (status == -1) return compile_failed("the compiler took longer than " + std::to_string(int(kCompileSeconds)) + " s");
  if (status != 0 || !fs::exists(worker, ec))
    return compile_failed(first_error(output, src.native(), fs::path(dir).filename().native()));
  sub.worker = worker;
  sub.compile = {{"ok", true},
                 {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()},
                 {"error", ""}};
  return sub;
}

}  // namespace cli
