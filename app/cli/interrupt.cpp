#include "interrupt.h"

#include <csignal>
#include <cstdio>
#include <cstring>

#include <unistd.h>

namespace cli {
namespace {

// Everything the handler touches is a lock-free atomic or a sig_atomic_t, and it calls only
// write(2) and _exit(2), both async-signal-safe.
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free);
std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
std::atomic<bool> g_exit_at_once{false};

constexpr char kSigintLine[] = "accelviz-cli: interrupted (SIGINT)\n";
constexpr char kSigtermLine[] = "accelviz-cli: interrupted (SIGTERM)\n";

/// The line and code for `sig` (SIGINT or SIGTERM).
const char* line_for(int sig) { return sig == SIGTERM ? kSigtermLine : kSigintLine; }

[[noreturn]] void exit_now(int sig) {
  const char* line = line_for(sig);
  ssize_t ignored = ::write(2, line, std::strlen(line));  // strlen is async-signal-safe too
  (void)ignored;
  ::_exit(128 + sig);
}

extern "C" void on_signal(int sig) {
  int none = 0;
  g_signal.compare_exchange_strong(none, sig);  // the first signal names the exit code
  const bool second = g_interrupted.exchange(true);
  if (second || g_exit_at_once.load()) exit_now(g_signal.load());
}

}  // namespace

void install_interrupt_handlers() {
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  // SA_RESTART: the libraries' system calls (TBB's waits, file I/O) carry on after the
  // handler; the loops see the flag at their next poll.
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  std::signal(SIGPIPE, SIG_IGN);
}

const std::atomic<bool>* interrupt_flag() { return &g_interrupted; }

bool interrupted() { return g_interrupted.load(std::memory_order_relaxed); }

int interrupted_exit() {
  const int sig = g_signal.load();
  std::fputs(line_for(sig), stderr);
  return 128 + sig;
}

ExitOnInterrupt::ExitOnInterrupt() {
  g_exit_at_once.store(true);
  if (g_interrupted.load()) {  // arrived before this phase began
    std::fflush(stdout);
    exit_now(g_signal.load());
  }
}

ExitOnInterrupt::~ExitOnInterrupt() { g_exit_at_once.store(false); }

}  // namespace cli
