#include "judge/confinement.h"

#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <linux/filter.h>
#include <linux/seccomp.h>
#include <sched.h>
#include <seccomp.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <thread>

namespace judge {
namespace {

namespace fs = std::filesystem;

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ACCEL_JUDGE_UNDER_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define ACCEL_JUDGE_UNDER_ASAN 1
#endif

/// The unprivileged user the student's code runs as when the judge is root and no sandbox
/// makes a user of its own (--no-sandbox): Debian's nobody.
constexpr uid_t kNobody = 65534;

/// The worker's seccomp filter, as a BPF program (libseccomp writes it once; the children
/// load it, or bubblewrap does, without calling into the library after fork). Everything is
/// allowed but new processes (fork, vfork, a clone that is not a thread: EPERM; clone3:
/// ENOSYS, so the C library falls back to clone, whose flags the filter can read), sockets,
/// signals to other processes, tracing and new namespaces.
const std::vector<sock_filter>& worker_filter() {
  static const std::vector<sock_filter> program = [] {
    std::vector<sock_filter> out;
    scmp_filter_ctx ctx = seccomp_init(SCMP_ACT_ALLOW);
    if (!ctx) return out;
    bool ok = true;
    auto deny = [&](int syscall, int error) { ok = ok && seccomp_rule_add(ctx, SCMP_ACT_ERRNO(error), syscall, 0) == 0; };
    deny(SCMP_SYS(fork), EPERM);
    deny(SCMP_SYS(vfork), EPERM);
    deny(SCMP_SYS(clone3), ENOSYS);
    // clone's first argument (its flags) without CLONE_THREAD: a new process, not a thread.
    const scmp_arg_cmp not_a_thread{0, SCMP_CMP_MASKED_EQ, CLONE_THREAD, 0};
    ok = ok && seccomp_rule_add_array(ctx, SCMP_ACT_ERRNO(EPERM), SCMP_SYS(clone), 1, &not_a_thread) == 0;
    for (int sc : {SCMP_SYS(socket), SCMP_SYS(socketpair), SCMP_SYS(kill), SCMP_SYS(tkill), SCMP_SYS(ptrace),
                   SCMP_SYS(process_vm_readv), SCMP_SYS(process_vm_writev), SCMP_SYS(unshare), SCMP_SYS(setns),
                   SCMP_SYS(mount), SCMP_SYS(pidfd_open), SCMP_SYS(pidfd_send_signal), SCMP_SYS(rt_sigqueueinfo),
                   SCMP_SYS(io_uring_setup), SCMP_SYS(bpf), SCMP_SYS(perf_event_open), SCMP_SYS(keyctl),
                   SCMP_SYS(add_key), SCMP_SYS(request_key), SCMP_SYS(userfaultfd)})
      deny(sc, EPERM);
    // tgkill stays: abort() signals its own thread with it. A tgkill to another process is
    // harmless in the sandbox (its own pid namespace) and refused to nobody outside it.
    const int fd = ok ? memfd_create("accelviz-seccomp", MFD_CLOEXEC) : -1;
    if (fd >= 0 && seccomp_export_bpf(ctx, fd) == 0) {
      const off_t size = lseek(fd, 0, SEEK_END);
      if (size > 0 && size % off_t(sizeof(sock_filter)) == 0) {
        out.resize(size_t(size) / sizeof(sock_filter));
        if (pread(fd, out.data(), size_t(size), 0) != size) out.clear();
      }
    }
    if (fd >= 0) close(fd);
    seccomp_release(ctx);
    return out;
  }();
  return program;
}

/// The filter in a fresh memfd at offset 0, for bubblewrap's --seccomp (each start its own:
/// two starts reading one file description would race for its offset).
int filter_fd() {
  const auto& program = worker_filter();
  if (program.empty()) return -1;
  const int fd = memfd_create("accelviz-seccomp", MFD_CLOEXEC);
  if (fd < 0) return -1;
  const size_t size = program.size() * sizeof(sock_filter);
  if (write(fd, program.data(), size) != ssize_t(size) || lseek(fd, 0, SEEK_SET) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

/// bubblewrap: Debian's, or $ACCELVIZ_BWRAP (the lecturer's environment, never the student's:
/// the tests point it at a missing program to see the judge refuse to grade).
std::string bwrap_path() {
  if (const char* chosen = getenv("ACCELVIZ_BWRAP")) return access(chosen, X_OK) == 0 ? chosen : "";
  for (const char* p : {"/usr/bin/bwrap", "/bin/bwrap", "/usr/local/bin/bwrap"})
    if (access(p, X_OK) == 0) return p;
  return "";
}

/// Whether this bubblewrap takes --size (0.7 and later; Ubuntu 22.04 has 0.6): without it
/// the private /tmp is bounded by the file-size limit alone.
bool bwrap_takes_size() {
  static const bool takes = [] {
    FILE* p = popen((bwrap_path() + " --version 2>/dev/null").c_str(), "r");
    if (!p) return false;
    int major = 0, minor = 0;
    const bool read = std::fscanf(p, "bubblewrap %d.%d", &major, &minor) == 2;
    pclose(p);
    return read && (major > 0 || minor >= 7);
  }();
  return takes;
}

/// bubblewrap's arguments before the command: namespaces, the read-only system, the private
/// /tmp and home, the paths the judge names.
std::vector<std::string> bwrap_arguments(const Confinement& c, bool seccomp) {
  std::vector<std::string> a = {bwrap_path(), "--unshare-all", "--die-with-parent", "--new-session",
                                "--cap-drop",  "ALL",          "--ro-bind",         "/usr",
                                "/usr"};
  // /bin, /lib... are links into /usr on a merged-/usr system, folders on older ones.
  for (const char* top : {"/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32"}) {
    std::error_code ec;
    if (fs::is_symlink(top, ec))
      a.insert(a.end(), {"--symlink", fs::read_symlink(top, ec).native(), top});
    else if (fs::is_directory(top, ec))
      a.insert(a.end(), {"--ro-bind", top, top});
  }
  a.insert(a.end(), {"--proc", "/proc", "--dev", "/dev"});
  for (const char* tmpfs : {"/tmp", "/home"}) {
    if (bwrap_takes_size()) a.insert(a.end(), {"--size", std::to_string(c.file_bytes)});
    a.insert(a.end(), {"--tmpfs", tmpfs});
  }
  a.insert(a.end(), {"--dir", "/home/student", "--setenv", "HOME", "/home/student", "--setenv", "TMPDIR", "/tmp"});
  for (const std::string& p : c.read_only) a.insert(a.end(), {"--ro-bind", p, p});
  for (const std::string& p : c.writable) a.insert(a.end(), {"--bind", p, p});
  a.insert(a.end(), {"--chdir", c.workdir.empty() ? "/home/student" : c.workdir});
  if (seccomp) a.insert(a.end(), {"--seccomp", "5"});
  return a;
}

/// An fd at 10 or above: the child moves its fds onto 0-5, and none of them may already sit there.
int high_fd(int fd) {
  const int moved = fcntl(fd, F_DUPFD_CLOEXEC, 10);
  close(fd);
  return moved;
}

void close_all(std::initializer_list<int> fds) {
  for (int fd : fds)
    if (fd >= 0) close(fd);
}

}  // namespace

accel::Result<Confined> start_confined(const std::vector<std::string>& argv, const Confinement& c, bool wire) {
  if (argv.empty()) return accel::make_error("nothing to start");
  const bool seccomp = !c.allow_processes;
  if (seccomp && worker_filter().empty()) return accel::make_error("cannot make the seccomp filter (libseccomp)");
  int out[2] = {-1, -1}, req[2] = {-1, -1}, ans[2] = {-1, -1};
  if (pipe2(out, O_CLOEXEC) != 0 || (wire && (pipe2(req, O_CLOEXEC) != 0 || pipe2(ans, O_CLOEXEC) != 0))) {
    close_all({out[0], out[1], req[0], req[1], ans[0], ans[1]});
    return accel::make_error(std::string("cannot make a pipe: ") + std::strerror(errno));
  }
  // A worker's answers stream fast: a 1 MiB pipe keeps it from waiting on every frame.
  if (wire) fcntl(ans[1], F_SETPIPE_SZ, 1 << 20);
  const int child_out = high_fd(out[1]);
  const int child_req = wire ? high_fd(req[0]) : -1;
  const int child_ans = wire ? high_fd(ans[1]) : -1;
  const int dev_null = high_fd(open("/dev/null", O_RDONLY | O_CLOEXEC));
  const int seccomp_fd = c.sandbox && seccomp ? high_fd(filter_fd()) : -1;

  // Everything the child needs, made before fork: after it, only system calls.
  std::vector<std::string> full = argv;
  if (c.sandbox) {
    std::vector<std::string> b = bwrap_arguments(c, seccomp);
    full.insert(full.begin(), b.begin(), b.end());
  }
  std::vector<char*> args;
  for (std::string& s : full) args.push_back(s.data());
  args.push_back(nullptr);
  // A clean environment: nothing of the judge's but, in the sanitizer build, its sanitizers'
  // options (abort_on_error turns a student's crash into the signal the report names).
  std::vector<std::string> environment = {"PATH=/usr/bin:/bin", "LANG=C.UTF-8",
                                          c.sandbox ? "HOME=/home/student" : "HOME=/nonexistent"};
  for (const char* name : {"ASAN_OPTIONS", "UBSAN_OPTIONS", "LSAN_OPTIONS"})
    if (const char* value = getenv(name)) environment.push_back(std::string(name) + "=" + value);
  std::vector<char*> env;
  for (std::string& e : environment) env.push_back(e.data());
  env.push_back(nullptr);
  const std::string workdir = c.workdir.empty() ? "/" : c.workdir;
  const auto& program = worker_filter();
  sock_fprog fprog{static_cast<unsigned short>(program.size()), const_cast<sock_filter*>(program.data())};
  const bool as_root = geteuid() == 0;

  const pid_t pid = fork();
  if (pid < 0) {
    close_all({out[0], child_out, req[1], child_req, ans[0], child_ans, dev_null, seccomp_fd});
    return accel::make_error(std::string("cannot start a process: ") + std::strerror(errno));
  }
  if (pid == 0) {
    setpgid(0, 0);  // its own group: a timeout ends the compiler's children too
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (dup2(dev_null, 0) < 0 || dup2(child_out, 1) < 0 || dup2(child_out, 2) < 0) _exit(126);
    if (wire && (dup2(child_req, 3) < 0 || dup2(child_ans, 4) < 0)) _exit(126);
    if (seccomp_fd >= 0 && dup2(seccomp_fd, 5) < 0) _exit(126);
    syscall(SYS_close_range, seccomp_fd >= 0 ? 6u : wire ? 5u : 3u, ~0u, 0u);
    auto limit = [](int resource, rlim_t soft, rlim_t hard) {
      const rlimit l{soft, hard};
      setrlimit(resource, &l);
    };
#ifndef ACCEL_JUDGE_UNDER_ASAN  // ASan reserves terabytes of address space
    if (c.memory_bytes) limit(RLIMIT_AS, c.memory_bytes, c.memory_bytes);
#endif
    if (c.cpu_seconds > 0) {
      const rlim_t s = rlim_t(std::ceil(c.cpu_seconds));
      limit(RLIMIT_CPU, s, s + 2);
    }
    limit(RLIMIT_FSIZE, c.file_bytes, c.file_bytes);
    limit(RLIMIT_CORE, 0, 0);
    if (!c.sandbox) {
      if (as_root && (setgroups(0, nullptr) != 0 || setgid(kNobody) != 0 || setuid(kNobody) != 0)) _exit(126);
      if (chdir(workdir.c_str()) != 0) _exit(126);
      if (prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) != 0) _exit(126);
      if (seccomp && prctl(PR_SET_SECCOMP, SECCOMP_MODE_FILTER, &fprog) != 0) _exit(126);
    }
    execve(args[0], args.data(), env.data());
    _exit(127);
  }
  close_all({child_out, child_req, child_ans, dev_null, seccomp_fd});
  Confined r;
  r.pid = pid;
  r.output_fd = out[0];
  r.request_fd = wire ? req[1] : -1;
  r.answer_fd = wire ? ans[0] : -1;
  return r;
}

const std::string& sandbox_unavailable_reason() {
  static const std::string reason = []() -> std::string {
    if (bwrap_path().empty())
      return "bubblewrap (bwrap) is not installed: scripts/deps.sh installs it (Debian package bubblewrap)";
    // A sandbox that runs `true`: the same namespaces and mounts a worker gets.
    Confinement probe;
    probe.allow_processes = true;
    auto started = start_confined({"/usr/bin/true"}, probe, false);
    if (!started) return "cannot start bubblewrap: " + started.error().message;
    std::string said;
    char buf[512];
    ssize_t n;
    while ((n = read(started.value().output_fd, buf, sizeof buf)) > 0 && said.size() < 2000) said.append(buf, size_t(n));
    close(started.value().output_fd);
    int status = 0;
    waitpid(started.value().pid, &status, 0);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
    while (!said.empty() && (said.back() == '\n' || said.back() == '\r')) said.pop_back();
    if (const size_t nl = said.find('\n'); nl != std::string::npos) said.resize(nl);
    return "bubblewrap cannot make a sandbox here (user namespaces unavailable?): " +
           (said.empty() ? describe_end(status, false) : said);
  }();
  return reason;
}

std::string describe_confinement(const Confinement& c) {
  std::string limits;
  if (c.memory_bytes) limits += ", " + std::to_string(c.memory_bytes >> 20) + " MiB of memory";
  if (c.cpu_seconds > 0) limits += ", " + std::to_string(int(std::ceil(c.cpu_seconds))) + " s of CPU";
  limits += ", files up to " + std::to_string(c.file_bytes >> 20) + " MiB";
  if (!c.allow_processes) limits += ", no new processes, no sockets (seccomp)";
  if (c.sandbox)
    return "bubblewrap: no network, read-only /usr and the worker only, private empty /tmp and home" + limits;
  return std::string("none (--no-sandbox): the student's code runs as ") +
         (geteuid() == 0 ? "the user nobody" : "the grader's own user") +
         " with the grader's view of the files and network" + limits;
}

bool ended_by_signal(int status, bool sandboxed) {
  if (WIFSIGNALED(status)) return true;
  return sandboxed && WIFEXITED(status) && WEXITSTATUS(status) > 128 && WEXITSTATUS(status) < 128 + 65;
}

std::string describe_end(int status, bool sandboxed) {
  int signal = 0;
  if (WIFSIGNALED(status)) signal = WTERMSIG(status);
  else if (ended_by_signal(status, sandboxed)) signal = WEXITSTATUS(status) - 128;
  if (signal == SIGXCPU || signal == SIGKILL)
    return std::string("was stopped (") + strsignal(signal) + ": the CPU-time or memory limit?)";
  if (signal) return std::string("crashed (") + strsignal(signal) + ")";
  if (WIFEXITED(status)) return "exited with code " + std::to_string(WEXITSTATUS(status));
  return "ended";
}

}  // namespace judge
