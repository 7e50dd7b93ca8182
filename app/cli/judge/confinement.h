#pragma once
// Where the judge runs student code: a process confined by bubblewrap (Debian `bubblewrap`,
// the sandbox Flatpak uses) with limits set before it starts, and a seccomp filter made by
// libseccomp. Inside it the student's code has no network, a read-only view of /usr and of
// the paths the judge names (the worker binary; for a compile, the submission and the kit's
// header), a private empty /tmp and home, no view of the judge's output, the hidden cases,
// other submissions or the lecturer's files, and limits on CPU time, memory, file size and
// (the worker) no new processes. The judge never runs student code itself.
//
// Without user namespaces bubblewrap cannot run: the judge then refuses to grade, unless
// --no-sandbox was given. That mode (a course platform's container, which isolates each
// submission already) keeps the limits and the seccomp filter, and where the judge is root
// runs the student's code as the unprivileged user nobody, so it cannot write the judge's
// files (PrairieLearn's approach); the report says which mode graded it.
#include <sys/types.h>

#include <string>
#include <vector>

#include "result.h"

namespace judge {

struct Confinement {
  bool sandbox = true;             ///< under bubblewrap; false: --no-sandbox
  size_t memory_bytes = 0;         ///< address-space limit (0: none; never under AddressSanitizer)
  double cpu_seconds = 0.0;        ///< CPU-time limit (0: none)
  size_t file_bytes = 64u << 20;   ///< the largest file it may write (its private /tmp)
  bool allow_processes = false;    ///< the compiler's driver forks; the worker may not
  std::vector<std::string> read_only;  ///< host paths it sees, at the same path, read-only
  std::vector<std::string> writable;   ///< host paths it sees, at the same path, writable
  std::string workdir;                 ///< its working folder ("": its private home)
};

/// A started confined process: its pid (bwrap's, in the sandbox), its output (stdout and
/// stderr together) and, with the wire, the judge's ends of fds 3 and 4.
struct Confined {
  pid_t pid = -1;
  int output_fd = -1;
  int request_fd = -1;  ///< the judge writes requests here (the process's fd 3)
  int answer_fd = -1;   ///< and reads answers here (the process's fd 4)
};

/// Starts `argv` (argv[0] a full path) confined as `c` says; `wire`: with fds 3 and 4.
accel::Result<Confined> start_confined(const std::vector<std::string>& argv, const Confinement& c, bool wire);

/// "" when bubblewrap can make a sandbox here, else one line saying why not.
const std::string& sandbox_unavailable_reason();

/// The confinement in words, for reports ("bubblewrap 0.8.0: no network, ...").
std::string describe_confinement(const Confinement& c);

/// How a confined process ended, from waitpid's status: "exited with code 3", "crashed
/// (Segmentation fault)". Under bubblewrap a signal arrives as exit code 128 + signal.
std::string describe_end(int status, bool sandboxed);
/// Whether that end was a crash (a signal), not an exit.
bool ended_by_signal(int status, bool sandboxed);

}  // namespace judge
