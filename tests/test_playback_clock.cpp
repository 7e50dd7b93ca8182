// PlaybackClock (time -> step), the one clock under the traversal's and the construction's
// players: stepping and clamping, play at speed with the carry, the end, the speed limits
// and the guards against NaN and non-positive times.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "playback_clock.h"

namespace accel {
namespace {

/// A clock with its positions set from outside, as the players set them.
class Clock : public PlaybackClock {
 public:
  explicit Clock(size_t positions = 0) { restart(positions); }
  using PlaybackClock::resize;
  using PlaybackClock::restart;
};

TEST(PlaybackClock, EmptyIsInert) {
  Clock c;
  EXPECT_TRUE(c.empty());
  EXPECT_TRUE(c.at_end());
  EXPECT_EQ(c.last_step(), 0u);
  EXPECT_FALSE(c.step_forward());
  EXPECT_FALSE(c.step_back());
  EXPECT_FALSE(c.jump_to_end());
  EXPECT_FALSE(c.seek(5));
  c.play();
  EXPECT_FALSE(c.playing());
  EXPECT_FALSE(c.advance(10.0));
  EXPECT_EQ(c.step(), 0u);
}

TEST(PlaybackClock, StepsSeekAndClamp) {
  Clock c(5);  // steps 0..4
  EXPECT_EQ(c.last_step(), 4u);
  EXPECT_TRUE(c.step_forward());
  EXPECT_EQ(c.step(), 1u);
  EXPECT_TRUE(c.step_forward(std::numeric_limits<size_t>::max()));  // clamped, no overflow
  EXPECT_EQ(c.step(), 4u);
  EXPECT_TRUE(c.at_end());
  EXPECT_FALSE(c.step_forward());
  EXPECT_TRUE(c.step_back(3));
  EXPECT_EQ(c.step(), 1u);
  EXPECT_TRUE(c.step_back(99));
  EXPECT_EQ(c.step(), 0u);
  EXPECT_FALSE(c.step_back());
  EXPECT_TRUE(c.seek(99));
  EXPECT_EQ(c.step(), 4u);
  EXPECT_FALSE(c.jump_to_end());
  EXPECT_TRUE(c.seek(2));
  EXPECT_FALSE(c.seek(2));
}

TEST(PlaybackClock, PlaysAtSpeedCarryingTheRest) {
  Clock c(10);
  c.set_speed(4.0);
  EXPECT_FALSE(c.advance(1.0));  // paused: time does not count
  c.play();
  EXPECT_FALSE(c.advance(0.2));  // 0.8 of a step
  EXPECT_TRUE(c.advance(0.1));   // 1.2: one taken, 0.2 carried
  EXPECT_EQ(c.step(), 1u);
  EXPECT_TRUE(c.advance(0.5));  // 2.2
  EXPECT_EQ(c.step(), 3u);
  EXPECT_TRUE(c.advance(100.0));
  EXPECT_EQ(c.step(), 9u);
  EXPECT_FALSE(c.playing());  // stopped at the end
  c.play();                   // at the end, play starts over
  EXPECT_EQ(c.step(), 0u);
  EXPECT_TRUE(c.playing());
  // play() starts on a whole step: a quarter second at 4 steps/s is one step.
  EXPECT_FALSE(c.advance(0.2));
  EXPECT_TRUE(c.advance(0.05));
  EXPECT_EQ(c.step(), 1u);
  c.toggle();
  EXPECT_FALSE(c.playing());
}

TEST(PlaybackClock, TimeThatIsNotPositiveDoesNothing) {
  Clock c(10);
  c.play();
  EXPECT_FALSE(c.advance(0.0));
  EXPECT_FALSE(c.advance(-1.0));
  EXPECT_FALSE(c.advance(std::nan("")));
  EXPECT_EQ(c.step(), 0u);
  EXPECT_TRUE(c.playing());
  // The NaN left no trace in the carry: a quarter second at 4 steps/s is one step.
  EXPECT_TRUE(c.advance(0.25));
  EXPECT_EQ(c.step(), 1u);
  // An infinite time plays to the end.
  EXPECT_TRUE(c.advance(std::numeric_limits<double>::infinity()));
  EXPECT_EQ(c.step(), 9u);
  EXPECT_FALSE(c.playing());
}

TEST(PlaybackClock, SpeedIsClampedAndNaNIsTheDefault) {
  Clock c;
  EXPECT_EQ(c.speed(), PlaybackClock::kDefaultSpeed);
  c.set_speed(0.0);
  EXPECT_EQ(c.speed(), PlaybackClock::kMinSpeed);
  c.set_speed(1e9);
  EXPECT_EQ(c.speed(), PlaybackClock::kMaxSpeed);
  EXPECT_EQ(PlaybackClock::kMaxSpeed, 5000.0);  // the construction's steps need it
  c.set_speed(std::nan(""));
  EXPECT_EQ(c.speed(), PlaybackClock::kDefaultSpeed);
  c.set_speed(10.0);
  EXPECT_EQ(c.speed(), 10.0);
}

TEST(PlaybackClock, ResizeKeepsTheStepAndRestartRewinds) {
  Clock c(10);
  c.seek(7);
  c.play();
  c.resize(20);  // the same recording, longer: the step stays, playing goes on
  EXPECT_EQ(c.step(), 7u);
  EXPECT_TRUE(c.playing());
  c.resize(5);  // shorter: clamped to the new end, where playing stops
  EXPECT_EQ(c.step(), 4u);
  EXPECT_FALSE(c.playing());
  c.restart(8);
  EXPECT_EQ(c.step(), 0u);
  EXPECT_EQ(c.last_step(), 7u);
  EXPECT_FALSE(c.playing());
}

}  // namespace
}  // namespace accel
