// LiveInput (pipeline/live_input.h): live messages become paired stereo frames and time-ordered streams;
// what cannot be used is dropped and counted, never passed on.
#include <gtest/gtest.h>

#include <vector>

#include "pipeline/live_input.h"

namespace vilslam {
namespace {

constexpr TimeNs kMs = 1'000'000;

// An image whose only pixel tells which camera and stamp it came from.
cv::Mat tagged(int camera, TimeNs t_ns) { return cv::Mat(1, 1, CV_8UC1, cv::Scalar((t_ns / kMs) % 100 + 100 * camera)); }
int tag(const cv::Mat& image) { return image.at<std::uint8_t>(0, 0); }

struct Collected {
  std::vector<TimeNs> imu;
  std::vector<StereoFrame> frames;
  std::vector<TimeNs> scans;
};

LiveInput make_input(Collected& c, LiveInputConfig config = {}) {
  return LiveInput(config, LiveInputSink{[&c](const ImuSample& s) { c.imu.push_back(s.t_ns); },
                                         [&c](StereoFrame f) { c.frames.push_back(std::move(f)); },
                                         [&c](LidarScan s) { c.scans.push_back(s.t_ns); }});
}

TEST(LiveInput, PairsImagesInEitherOrderAndWithinTheGap) {
  Collected c;
  LiveInput input = make_input(c);
  input.image(0, 10 * kMs, tagged(0, 10 * kMs));
  EXPECT_TRUE(c.frames.empty());  // half a pair waits
  input.image(1, 10 * kMs, tagged(1, 10 * kMs));
  input.image(1, 60 * kMs, tagged(1, 60 * kMs));  // right first
  input.image(0, 60 * kMs + kMs / 2, tagged(0, 60 * kMs));  // 0.5 ms apart: one frame, the left stamp
  ASSERT_EQ(c.frames.size(), 2u);
  EXPECT_EQ(c.frames[0].t_ns, 10 * kMs);
  EXPECT_EQ(tag(c.frames[0].left), 10);
  EXPECT_EQ(tag(c.frames[0].right), 110);
  EXPECT_EQ(c.frames[1].t_ns, 60 * kMs + kMs / 2);
  EXPECT_EQ(tag(c.frames[1].left), 60);
  EXPECT_EQ(tag(c.frames[1].right), 160);
  EXPECT_EQ(input.drops().unpaired_images, 0u);
}

TEST(LiveInput, AHalfWhoseOtherNeverCameIsDroppedWhenALaterFrameCompletes) {
  Collected c;
  LiveInput input = make_input(c);
  input.image(0, 10 * kMs, tagged(0, 10 * kMs));  // its right image is lost
  input.image(0, 60 * kMs, tagged(0, 60 * kMs));
  input.image(1, 60 * kMs, tagged(1, 60 * kMs));
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(c.frames[0].t_ns, 60 * kMs);
  EXPECT_EQ(input.drops().unpaired_images, 1u);
  // The late right image of 10 ms can no longer make a frame before the one already passed on.
  input.image(1, 10 * kMs, tagged(1, 10 * kMs));
  EXPECT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(input.drops().unpaired_images, 2u);
  // Two images of one camera 2 ms apart are not a pair.
  input.image(0, 100 * kMs, tagged(0, 100 * kMs));
  input.image(0, 102 * kMs, tagged(0, 102 * kMs));
  EXPECT_EQ(c.frames.size(), 1u);
  input.image(1, 102 * kMs, tagged(1, 102 * kMs));
  ASSERT_EQ(c.frames.size(), 2u);
  EXPECT_EQ(c.frames[1].t_ns, 102 * kMs);
  EXPECT_EQ(input.drops().unpaired_images, 3u);
}

TEST(LiveInput, WaitingHalvesAreBounded) {
  Collected c;
  LiveInputConfig config;
  config.max_waiting_images = 3;
  LiveInput input = make_input(c, config);
  for (int k = 0; k < 10; ++k) input.image(0, k * 50 * kMs, tagged(0, k * 50 * kMs));  // the right camera is dead
  EXPECT_EQ(input.drops().unpaired_images, 7u);
  input.image(1, 9 * 50 * kMs, tagged(1, 9 * 50 * kMs));
  ASSERT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(input.drops().unpaired_images, 9u);  // the two older waiting halves went with it
}

TEST(LiveInput, EachStreamStaysInTimeOrder) {
  Collected c;
  LiveInput input = make_input(c);
  for (TimeNs t : {5, 10, 10, 8, 15}) input.imu(ImuSample{t * kMs, Vec3::Zero(), Vec3::Zero()});
  EXPECT_EQ(c.imu, (std::vector<TimeNs>{5 * kMs, 10 * kMs, 15 * kMs}));
  EXPECT_EQ(input.drops().imu_out_of_order, 2u);  // the repeated stamp and the late sample
  for (TimeNs t : {0, 100, 50, 200}) {
    LidarScan scan;
    scan.t_ns = t * kMs;
    input.scan(std::move(scan));
  }
  EXPECT_EQ(c.scans, (std::vector<TimeNs>{0, 100 * kMs, 200 * kMs}));
  EXPECT_EQ(input.drops().scans_out_of_order, 1u);
  // A repeated left stamp that pairs with a newer right image would make a frame at the last one's time.
  input.image(0, 90 * kMs, tagged(0, 90 * kMs));
  input.image(1, 90 * kMs, tagged(1, 90 * kMs));
  input.image(1, 90 * kMs + kMs / 2, tagged(1, 90 * kMs));
  input.image(0, 90 * kMs, tagged(0, 90 * kMs));
  EXPECT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(input.drops().frames_out_of_order, 1u);
}

TEST(LiveInput, RejectsABadCameraIndex) {
  Collected c;
  LiveInput input = make_input(c);
  EXPECT_THROW(input.image(2, 0, tagged(0, 0)), std::invalid_argument);
}

}  // namespace
}  // namespace vilslam
