// browser.h natively: nothing to do (threads run the background work, files stay files).
#include "browser.h"

namespace viz::browser {

void wait_for_next_frame() {}
void run_background_tasks(double) {}
struct BackgroundTask::State {};
BackgroundTask::BackgroundTask(std::function<void()> work) { work(); }
BackgroundTask::~BackgroundTask() = default;
bool BackgroundTask::done() const { return true; }
void BackgroundTask::finish() {}
void install_input_fetcher() {}
void offer_download(const std::string&) {}
void log_screenshot(const std::string&) {}
void log_line(const std::string&) {}

}  // namespace viz::browser
