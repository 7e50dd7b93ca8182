// browser.h in the web page (emscripten, built with -sASYNCIFY: the fibers of the background
// tasks and the main loop's wait for the next animation frame both unwind and rewind the
// stack through it).
#include "browser.h"

#include <emscripten.h>
#include <emscripten/fiber.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include "input_files.h"
#include "yield_point.h"

namespace viz::browser {

struct BackgroundTask::State {
  std::function<void()> work;
  emscripten_fiber_t fiber{};
  std::vector<char> c_stack, asyncify_stack;
  bool done = false;
  bool finishing = false;  // finish(): no more handing back, run to the end
};

namespace {

// A task's own stack: builders recurse (a thread's default is 8 MiB natively as well), and
// Asyncify keeps the locals of every frame it unwinds when the task hands the thread back.
constexpr size_t kTaskStack = 8u << 20;
constexpr size_t kTaskAsyncifyStack = 4u << 20;
// Unwinding the main loop (main -> frame -> the tool that waits for a task) keeps far less.
constexpr size_t kMainAsyncifyStack = 1u << 20;
// A yield point reads the clock once every this many calls: builders reach one per node.
constexpr unsigned kYieldsPerClockRead = 16;

emscripten_fiber_t main_fiber;
std::vector<char> main_asyncify_stack;
BackgroundTask::State* running = nullptr;  // the task on the thread now, if any
double slice_end = 0.0;                     // when `running` hands the thread back
unsigned yields_since_clock = 0;
std::vector<BackgroundTask::State*> tasks;  // unfinished tasks, in the order they started
size_t next_task = 0;                       // round robin over `tasks`

void task_entry(void* arg) {
  auto* state = static_cast<BackgroundTask::State*>(arg);
  state->work();
  state->done = true;
  // A fiber's function must not return: go back to the loop for good.
  emscripten_fiber_swap(&state->fiber, &main_fiber);
}

// accel::par::yield() while a task runs: back to the main loop once its slice is used.
void yield_hook() {
  BackgroundTask::State* state = running;
  if (state == nullptr || state->finishing) return;
  if (++yields_since_clock < kYieldsPerClockRead) return;
  yields_since_clock = 0;
  if (emscripten_get_now() < slice_end) return;
  emscripten_fiber_swap(&state->fiber, &main_fiber);
}

// Runs `state` until it yields after `until` (emscripten_get_now() time) or ends.
void resume(BackgroundTask::State* state, double until) {
  if (running != nullptr) {
    // A task waiting for another would need fibers switching among themselves; no tool does.
    std::fprintf(stderr, "accelviz: internal error: a background task waited for another\n");
    std::abort();
  }
  if (main_asyncify_stack.empty()) {
    main_asyncify_stack.resize(kMainAsyncifyStack);
    emscripten_fiber_init_from_current_context(&main_fiber, main_asyncify_stack.data(), main_asyncify_stack.size());
    accel::par::yield_hook() = yield_hook;
  }
  running = state;
  slice_end = until;
  yields_since_clock = 0;
  emscripten_fiber_swap(&main_fiber, &state->fiber);
  running = nullptr;
}

}  // namespace

BackgroundTask::BackgroundTask(std::function<void()> work) : state_(std::make_unique<State>()) {
  state_->work = std::move(work);
  state_->c_stack.resize(kTaskStack);
  state_->asyncify_stack.resize(kTaskAsyncifyStack);
  emscripten_fiber_init(&state_->fiber, task_entry, state_.get(), state_->c_stack.data(), state_->c_stack.size(),
                        state_->asyncify_stack.data(), state_->asyncify_stack.size());
  tasks.push_back(state_.get());
}

BackgroundTask::~BackgroundTask() {
  finish();
  tasks.erase(std::remove(tasks.begin(), tasks.end(), state_.get()), tasks.end());
}

bool BackgroundTask::done() const { return state_->done; }

void BackgroundTask::finish() {
  state_->finishing = true;
  while (!state_->done) resume(state_.get(), std::numeric_limits<double>::infinity());
}

void run_background_tasks(double budget_ms) {
  const double end = emscripten_get_now() + budget_ms;
  for (size_t tried = 0; tried < tasks.size() && emscripten_get_now() < end; ++tried) {
    next_task = next_task % tasks.size();
    BackgroundTask::State* state = tasks[next_task++];
    if (!state->done) resume(state, end);
  }
}

EM_ASYNC_JS(void, accelviz_wait_for_animation_frame, (), {
  await new Promise((resolve) => requestAnimationFrame(() => resolve()));
});

void wait_for_next_frame() { accelviz_wait_for_animation_frame(); }

// Files on demand (install_input_fetcher): the served folder is the page's folder, which
// the working directory /app stands for. The fetch runs while the viewer waits (Asyncify
// unwinds the C++ stack meanwhile), so the file is there when the reader goes on. Writes ""
// to `why` when the file now exists, else the reason, naming the URL tried. The URL, as the
// browser resolves it, must lie in the page's folder: this also refuses what the path check
// of install_input_fetcher cannot see ("http://...", "%2e%2e/").
EM_ASYNC_JS(void, accelviz_fetch_input, (const char* path_ptr, char* why_ptr, int why_size), {
  const path = UTF8ToString(path_ptr);
  const folder = new URL(".", document.baseURI).href;
  let why;
  try {
    const url = new URL(path, document.baseURI).href;
    if (!url.startsWith(folder)) {
      why = url + " is outside the page's folder, which is all the page may read";
    } else {
      const response = await fetch(url);
      if (response.ok) {
        const data = new Uint8Array(await response.arrayBuffer());
        const target = PATH_FS.resolve(FS.cwd(), path);
        const dir = PATH.dirname(target);
        if (dir !== "/") FS.mkdirTree(dir);
        FS.writeFile(target, data);
        why = "";
      } else {
        why = "fetched " + url + ": the server answered " + response.status +
              (response.statusText ? " " + response.statusText : "");
      }
    }
  } catch (e) {
    why = "fetching " + path + ": " + e.message;
  }
  stringToUTF8(why, why_ptr, why_size);
});

// The page's side of offer_download(), log_screenshot() and log_line(). Lines go out as the
// viewer's standard output does (Module.print: page.js adds "accelviz: ").
EM_JS(void, accelviz_offer_download, (const char* path_ptr), {
  const path = UTF8ToString(path_ptr);
  const link = document.createElement('a');
  link.href = URL.createObjectURL(new Blob([FS.readFile(path)], {type: 'application/octet-stream'}));
  link.download = path.split('/').pop();
  document.body.appendChild(link);
  link.click();
  link.remove();
  setTimeout(() => URL.revokeObjectURL(link.href), 10000);
});

EM_JS(void, accelviz_log_screenshot, (const char* path_ptr), {
  const path = UTF8ToString(path_ptr);
  const data = FS.readFile(path);
  let text = "";
  for (let i = 0; i < data.length; i += 0x8000) text += String.fromCharCode.apply(null, data.subarray(i, i + 0x8000));
  out('screenshot ' + path + ' data:image/png;base64,' + btoa(text));
});

EM_JS(void, accelviz_log_line, (const char* line_ptr), { out(UTF8ToString(line_ptr)); });

void install_input_fetcher() {
  // fetch_missing_input asks only for relative paths below /app (the working directory).
  accel::set_input_fetcher([](const std::string& path) -> accel::Status {
    char why[1024] = "";
    accelviz_fetch_input(path.c_str(), why, int(sizeof why));
    if (why[0] == 0) return {};
    return accel::make_error(path + ": cannot open (" + std::string(why) + ")");
  });
}

void offer_download(const std::string& path) { accelviz_offer_download(path.c_str()); }
void log_screenshot(const std::string& path) { accelviz_log_screenshot(path.c_str()); }
void log_line(const std::string& line) { accelviz_log_line(line.c_str()); }

}  // namespace viz::browser
