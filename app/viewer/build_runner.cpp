#include "build_runner.h"

namespace viz {

BuildRunner::BuildRunner() : BuildRunner(BuildFn(build_structure_now)) {}

BuildRunner::BuildRunner(BuildFn build) : build_(std::move(build)) {}

BuildRunner::~BuildRunner() { wait(); }

void BuildRunner::request(std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                          bool synchronous) {
  Pending pending{std::move(scene), request};
  if (job_.busy() && !synchronous) {
    // Only the newest request matters: stop the running build rather than finish it.
    if (control_) control_->cancel();
    next_ = std::move(pending);
    return;
  }
  next_.reset();
  start(std::move(pending), synchronous);
}

void BuildRunner::start(Pending pending, bool synchronous) {
  control_ = std::make_shared<accel::BuildControl>();
  control_->set_memory_limit(memory_limit_);
  job_.start(
      [build = build_, control = control_, pending = std::move(pending)](const std::atomic<bool>&) {
        return build(pending.scene, pending.request, control.get());
      },
      synchronous);
}

std::optional<accel::Result<BuiltPtr>> BuildRunner::poll() {
  if (!job_.ready()) return std::nullopt;
  accel::Result<BuiltPtr> result = job_.take();
  // Cancelled means superseded: even a build that finished before it noticed is stale.
  const bool superseded = control_ && control_->cancelled();
  if (next_) {
    Pending next = std::move(*next_);
    next_.reset();
    start(std::move(next), false);
  }
  if (superseded) return std::nullopt;
  return result;
}

double BuildRunner::fraction() const {
  if (!control_ || control_->cancelled()) return 0.0;
  return control_->fraction();
}

void BuildRunner::wait() {
  cancel();
  job_.wait();
}

void BuildRunner::cancel() {
  next_.reset();
  if (control_) control_->cancel();
}

}  // namespace viz
