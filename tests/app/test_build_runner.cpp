// BuildRunner: the viewer's background builds. A request while a build runs cancels it; the
// cancelled result is dropped and the newest request is built and handed out.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "build_control.h"
#include "build_runner.h"
#include "viewer_test_support.h"

namespace viz {
namespace {

using test::scene_of;

/// Polls until a result comes out (or ~20 s pass).
std::optional<accel::Result<BuiltPtr>> poll_until_result(BuildRunner& runner) {
  for (int i = 0; i < 20000; ++i) {
    if (auto r = runner.poll()) return r;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return std::nullopt;
}

StructureRequest named(const std::string& name, std::vector<std::string> params = {}) {
  StructureRequest r;
  r.name = name;
  r.params = std::move(params);
  return r;
}

/// A fake build: "slow" runs, reporting progress, until its control is cancelled; any
/// other name returns at once.
struct FakeBuilds {
  std::atomic<int> started{0};
  std::atomic<int> cancelled{0};
  std::atomic<bool> slow_running{false};

  BuildRunner::BuildFn fn() {
    return [this](std::shared_ptr<const accel::Scene> scene, const StructureRequest& request,
                  accel::BuildControl* control) -> accel::Result<BuiltPtr> {
      ++started;
      if (request.name == "slow") {
        slow_running = true;
        for (int i = 0; !control->cancelled(); ++i) {
          control->report(std::min(0.99, 0.001 * i));
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        ++cancelled;
        return accel::cancelled_error();
      }
      auto built = std::make_shared<BuiltStructure>();
      built->scene = std::move(scene);
      built->request = request;
      control->report(1.0);
      return BuiltPtr(std::move(built));
    };
  }
};

TEST(BuildRunner, ANewRequestCancelsTheRunningBuildAndInstallsInstead) {
  auto scene = scene_of("sphere");
  FakeBuilds fake;
  BuildRunner runner(fake.fn());
  runner.request(scene, named("slow"), false);
  EXPECT_TRUE(runner.busy());
  while (!fake.slow_running) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  // Progress is visible from this (the UI) thread while the build runs.
  while (runner.fraction() < 0.005) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_FALSE(runner.poll().has_value());

  runner.request(scene, named("fast-1"), false);
  runner.request(scene, named("fast-2"), false);  // replaces fast-1: only the newest waits
  EXPECT_TRUE(runner.busy());
  auto result = poll_until_result(runner);
  ASSERT_TRUE(result.has_value());
  ASSERT_TRUE(result->ok()) << result->error().message;  // the cancel is not an error shown
  EXPECT_EQ(result->value()->request.name, "fast-2");
  EXPECT_EQ(fake.cancelled.load(), 1);
  EXPECT_EQ(fake.started.load(), 2);  // slow, then fast-2; fast-1 never ran
  EXPECT_FALSE(runner.busy());
  EXPECT_FALSE(runner.poll().has_value());
}

TEST(BuildRunner, SynchronousRequestsRunAtOnceInOrder) {
  auto scene = scene_of("sphere");
  FakeBuilds fake;
  BuildRunner runner(fake.fn());
  runner.request(scene, named("a"), true);
  auto a = runner.poll();
  ASSERT_TRUE(a.has_value() && a->ok());
  EXPECT_EQ(a->value()->request.name, "a");
  runner.request(scene, named("b"), true);
  auto b = runner.poll();
  ASSERT_TRUE(b.has_value() && b->ok());
  EXPECT_EQ(b->value()->request.name, "b");
  EXPECT_EQ(fake.started.load(), 2);
}

TEST(BuildRunner, WaitCancelsTheRunningBuild) {
  auto scene = scene_of("sphere");
  FakeBuilds fake;
  BuildRunner runner(fake.fn());
  runner.request(scene, named("slow"), false);
  runner.wait();  // would never return if the slow build were not cancelled
  EXPECT_EQ(fake.cancelled.load(), 1);
  EXPECT_FALSE(runner.busy());
}

TEST(BuildRunner, CancelStopsTheBuildWithoutWaitingAndDropsItsResult) {
  auto scene = scene_of("sphere");
  FakeBuilds fake;
  BuildRunner runner(fake.fn());
  runner.request(scene, named("slow"), false);
  while (!fake.slow_running) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  runner.request(scene, named("waiting"), false);
  runner.cancel();  // the Cancel button: returns at once, the waiting request is forgotten too
  for (int i = 0; i < 20000 && runner.busy(); ++i) {
    EXPECT_FALSE(runner.poll().has_value());  // a cancelled build hands out nothing
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_FALSE(runner.busy());
  EXPECT_EQ(fake.cancelled.load(), 1);
  EXPECT_EQ(fake.started.load(), 1);
}

TEST(BuildRunner, BuildsRunWithinTheMemoryLimitSet) {
  // A grid of 2^24 cells needs far more than 1 MiB: the viewer's setting reaches the builder,
  // whose error names the parameter and the limit.
  auto scene = scene_of("sphere");
  BuildRunner runner;
  runner.set_memory_limit(size_t(1) << 20);
  runner.request(scene, named("grid", {"res=256,256,256"}), false);
  auto result = poll_until_result(runner);
  ASSERT_TRUE(result.has_value());
  ASSERT_FALSE(result->ok());
  EXPECT_NE(result->error().message.find("'res'"), std::string::npos) << result->error().message;
  EXPECT_NE(result->error().message.find("memory limit 1 MiB"), std::string::npos) << result->error().message;
  runner.set_memory_limit(0);  // back to the default: the same grid fits
  runner.request(scene, named("grid", {"res=256,256,256"}), false);
  result = poll_until_result(runner);
  ASSERT_TRUE(result.has_value());
  EXPECT_TRUE(result->ok()) << result->error().message;
}

TEST(BuildRunner, RealBuildsTheNewestRequestWins) {
  // Real structures: the first (a kd-tree over the stadium) is cancelled mid-way or, on a
  // fast machine, finishes first and is dropped; either way the grid is what comes out.
  auto scene = scene_of("stadium");
  BuildRunner runner;
  runner.request(scene, named("kdtree"), false);
  runner.request(scene, named("grid"), false);
  auto result = poll_until_result(runner);
  ASSERT_TRUE(result.has_value());
  ASSERT_TRUE(result->ok()) << result->error().message;
  EXPECT_EQ(result->value()->request.name, "grid");
  EXPECT_GT(result->value()->stats.prim_references, 0u);
  EXPECT_FALSE(runner.busy());
}

TEST(BuildRunner, BuildStructureNowHonoursACancelledControl) {
  accel::BuildControl control;
  control.cancel();
  auto result = build_structure_now(scene_of("sphere"), named("bvh"), &control);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().message, accel::cancelled_error().message);
}

}  // namespace
}  // namespace viz
