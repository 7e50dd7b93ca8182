#pragma once
// The animation's clock: time -> step over the positions 0..last_step() of a recording, with
// play / pause, speed, single steps and seeking. GL-free, so the tests drive it without a
// window. The viewer's two players are clocks with what is theirs on top:
//   TracePlayer (trace_player.h)      a traversal's events, jump to the hit
//   BuildStepPlayer (tools/build_playback.h in the viewer)  a build's steps, 0 = nothing built
#include <cstddef>

namespace accel {

/// Plays positions 0..last_step(). An empty clock (no positions) stays at step 0 and never
/// plays. Derived players say how many positions there are (restart(), resize()).
class PlaybackClock {
 public:
  /// Default and limits of the playback speed, in steps per second. One maximum for the
  /// traversal and the construction: 5000, the construction's, because a recorded build
  /// has up to hundreds of thousands of steps and should play through in under a minute;
  /// a traversal of a few hundred steps simply reaches its end sooner at that speed.
  static constexpr double kDefaultSpeed = 4.0;
  static constexpr double kMinSpeed = 0.25;
  static constexpr double kMaxSpeed = 5000.0;

  /// Starts playing; at the last step it starts over from step 0. Nothing without positions.
  void play();
  void pause() { playing_ = false; }
  void toggle() { playing_ ? pause() : play(); }
  bool playing() const { return playing_; }

  /// Steps per second, clamped to [kMinSpeed, kMaxSpeed]; NaN sets kDefaultSpeed.
  void set_speed(double steps_per_second);
  double speed() const { return speed_; }

  /// Advances by `seconds` of playing time (nothing while paused, nor for a time that is not
  /// positive: zero, negative, NaN). Whole steps are taken and the remainder carried to the
  /// next call; at the last step playing stops and the carry is dropped, so the next play()
  /// starts on a whole step. Returns true when the step changed.
  bool advance(double seconds);
  /// Moves `n` steps forward / back, clamped. Returns true when the step changed.
  bool step_forward(size_t n = 1);
  bool step_back(size_t n = 1);
  /// Goes to `step`, clamped to [0, last_step()]. Returns true when the step changed.
  bool seek(size_t step);
  /// Goes to the last step.
  bool jump_to_end() { return seek(last_step()); }

  size_t step() const { return step_; }
  /// The last position (0 without positions).
  size_t last_step() const { return positions_ ? positions_ - 1 : 0; }
  /// No positions: nothing recorded.
  bool empty() const { return positions_ == 0; }
  bool at_end() const { return step_ >= last_step(); }

 protected:
  /// `positions` positions, back to step 0, paused.
  void restart(size_t positions);
  /// `positions` positions, the step kept (clamped to the new last step); playing stops
  /// there when that is the end.
  void resize(size_t positions);

 private:
  size_t positions_ = 0;
  size_t step_ = 0;
  bool playing_ = false;
  double speed_ = kDefaultSpeed;
  double carry_ = 0.0;  ///< fraction of a step accumulated by advance()
};

}  // namespace accel
