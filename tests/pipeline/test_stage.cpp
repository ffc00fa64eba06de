// One link of the pipeline's chain: messages handled in push order on the stage's thread (or inline), a
// bounded queue that blocks the producer instead of growing, and a handler's error carried to finish().
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "pipeline/stage.h"

namespace vilslam {
namespace {

class StageModes : public ::testing::TestWithParam<bool> {};

TEST_P(StageModes, HandlesEveryMessageInPushOrder) {
  std::vector<int> seen;
  Stage<int> stage([&](int&& m) { seen.push_back(m); }, GetParam(), 4);
  for (int i = 0; i < 1000; ++i) stage.push(i);
  stage.finish();
  ASSERT_EQ(seen.size(), 1000u);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(seen[i], i);
}

TEST_P(StageModes, ErrorReachesFinishAndLaterMessagesAreDropped) {
  int handled = 0;
  Stage<int> stage(
      [&](int&& m) {
        if (m == 3) throw std::runtime_error("bad message 3");
        ++handled;
      },
      GetParam(), 2);
  for (int i = 0; i < 100; ++i) stage.push(i);
  EXPECT_THROW(
      {
        try {
          stage.finish();
        } catch (const std::runtime_error& e) {
          EXPECT_STREQ(e.what(), "bad message 3");
          throw;
        }
      },
      std::runtime_error);
  EXPECT_EQ(handled, 3);
  EXPECT_TRUE(stage.failed());
}

INSTANTIATE_TEST_SUITE_P(ThreadedOrInline, StageModes, ::testing::Bool());

TEST(Stage, FullQueueBlocksTheProducer) {
  std::atomic<bool> release{false};
  std::atomic<int> handled{0};
  Stage<int> stage(
      [&](int&&) {
        while (!release) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        ++handled;
      },
      true, 2);
  std::atomic<int> pushed{0};
  std::thread producer([&] {
    for (int i = 0; i < 10; ++i) {
      stage.push(i);
      ++pushed;
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  // One message in the handler, two in the queue: the fourth push waits.
  EXPECT_LE(pushed.load(), 3);
  release = true;
  producer.join();
  stage.finish();
  EXPECT_EQ(handled.load(), 10);
}

}  // namespace
}  // namespace vilslam
