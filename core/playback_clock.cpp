#include "playback_clock.h"

#include <algorithm>
#include <cmath>

namespace accel {

void PlaybackClock::restart(size_t positions) {
  positions_ = positions;
  step_ = 0;
  playing_ = false;
  carry_ = 0.0;
}

void PlaybackClock::resize(size_t positions) {
  positions_ = positions;
  step_ = std::min(step_, last_step());
  if (at_end()) playing_ = false;
}

void PlaybackClock::play() {
  if (empty()) return;
  if (at_end()) step_ = 0;
  playing_ = true;
  carry_ = 0.0;
}

void PlaybackClock::set_speed(double steps_per_second) {
  // NaN compares false both ways: treat it as the default.
  if (std::isnan(steps_per_second)) steps_per_second = kDefaultSpeed;
  speed_ = std::clamp(steps_per_second, kMinSpeed, kMaxSpeed);
}

bool PlaybackClock::advance(double seconds) {
  // `!(seconds > 0)` and not `seconds <= 0`: a NaN must not reach the carry.
  if (!playing_ || empty() || !(seconds > 0.0)) return false;
  carry_ += seconds * speed_;
  const double whole = std::floor(carry_);
  carry_ -= whole;
  const size_t before = step_;
  // More steps than there are positions (a long frame, an infinite time): to the end.
  if (whole >= 1.0) step_forward(whole >= double(positions_) ? positions_ : size_t(whole));
  if (at_end()) {
    playing_ = false;
    carry_ = 0.0;
  }
  return step_ != before;
}

bool PlaybackClock::step_forward(size_t n) {
  const size_t last = last_step();
  return seek(n >= last - step_ ? last : step_ + n);
}

bool PlaybackClock::step_back(size_t n) { return seek(n >= step_ ? 0 : step_ - n); }

bool PlaybackClock::seek(size_t step) {
  const size_t clamped = std::min(step, last_step());
  const bool changed = clamped != step_;
  step_ = clamped;
  return changed;
}

}  // namespace accel
