#pragma once
// What the viewer does differently when it runs as a web page (emscripten; the page has one
// thread and no files of its own). Natively every function here does nothing, so main() and
// the tools call them unconditionally:
//
//   browser_native.cpp  the empty versions
//   browser_web.cpp     the page: the animation frame, background tasks, files on demand,
//                       downloads, logs
//
// Background tasks: the page cannot start threads, so a build (or a heat map, a comparison)
// runs as a BackgroundTask on a stack of its own (an emscripten fiber). Each frame the main
// loop lends the tasks a slice of time (run_background_tasks); a task hands the thread back
// at its next accel::par::yield() once the slice is used (the builders reach one per node),
// and the frame goes on: the progress bar moves and Cancel works, as with threads.
#include <functional>
#include <memory>
#include <string>

namespace viz::browser {

#ifdef __EMSCRIPTEN__
inline constexpr bool kInBrowser = true;
#else
inline constexpr bool kInBrowser = false;
#endif

/// Ends a frame: hands the thread to the browser until its next animation frame (which
/// shows the canvas and delivers input). Natively: nothing (glfwSwapBuffers waits).
void wait_for_next_frame();

/// Lends the background tasks up to `budget_ms` of this frame, in turn.
void run_background_tasks(double budget_ms);

/// A function running on its own stack, in the slices run_background_tasks() lends it.
/// Natively it is never made (threads do this work).
class BackgroundTask {
 public:
  explicit BackgroundTask(std::function<void()> work);
  /// Runs the task to its end first (a task never dies halfway down its stack).
  ~BackgroundTask();
  BackgroundTask(const BackgroundTask&) = delete;
  BackgroundTask& operator=(const BackgroundTask&) = delete;

  bool done() const;
  /// Runs the rest of the task now, without handing the thread back.
  void finish();

  struct State;

 private:
  std::unique_ptr<State> state_;
};

/// Files on demand: installs the page's accel::InputFetcher, so any file the viewer or the
/// core opens by a path relative to the page's folder (a scene, a playlist, a script and
/// what they name in turn) is fetched from the served folder at the moment it is opened,
/// when the page's file system does not hold it yet. Absolute paths and paths leading out
/// of the served folder are refused in one line. Natively: nothing.
void install_input_fetcher();

/// A file the viewer wrote for the user (F12's screenshot, a recording): the browser saves
/// it as a download.
void offer_download(const std::string& path);

/// A script's screenshot: logs "accelviz: screenshot PATH data:image/png;base64,..." so a
/// test driving the page can keep it.
void log_screenshot(const std::string& path);

/// A line for the page's console (a script's end, a dropped file's error).
void log_line(const std::string& line);

}  // namespace viz::browser
