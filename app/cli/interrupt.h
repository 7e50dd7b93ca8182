#pragma once
// SIGINT and SIGTERM in accelviz-cli: the handler only records the signal; the long loops
// (builds through BuildControl's cancel flag, trace_all's blocks, bench's timing passes,
// write_file_atomic's chunks) poll the flag and stop, and the command then returns
// interrupted_exit(): one line on stderr, exit 128 + signal (130, 143), no output file and
// no temporary file left. Phases that only read input (a FIFO may block in read()) run
// under ExitOnInterrupt, where the handler itself ends the process, as they have nothing
// to clean up. A second signal always ends the process at once.
#include <atomic>

namespace cli {

/// Installs the SIGINT/SIGTERM handlers and ignores SIGPIPE (a closed pipe is then a write
/// error, reported like any other). Call once, before any thread starts.
void install_interrupt_handlers();

/// The flag the handler sets: pass it to BuildControl::set_cancel_flag, trace_all and
/// write_file_atomic.
const std::atomic<bool>* interrupt_flag();
/// True once SIGINT or SIGTERM arrived.
bool interrupted();
/// Prints "accelviz-cli: interrupted (SIGINT)" (or SIGTERM) and returns 128 + the signal.
int interrupted_exit();

/// While one is alive, a signal ends the process from the handler (same line, same code).
/// For phases without side effects that may block or do not poll: loading the scene,
/// reading the rays. Not nestable.
class ExitOnInterrupt {
 public:
  ExitOnInterrupt();
  ~ExitOnInterrupt();
  ExitOnInterrupt(const ExitOnInterrupt&) = delete;
  ExitOnInterrupt& operator=(const ExitOnInterrupt&) = delete;
};

}  // namespace cli
