#pragma once
// Live sensor messages on their way into a System (pipeline/system.h): a robot's drivers deliver each stream on
// a connection of its own and each camera of a stereo pair separately. LiveInput pairs the two images of a
// stereo frame by their stamps and keeps every stream in time order on its own: a message not after its
// stream's last one (a repeated IMU stamp, an overtaken sweep) is dropped and counted, never passed on. The
// streams are not held back against each other: the System waits for the IMU to pass a frame's time itself,
// so an image arriving a little after the IMU samples that follow it is still used as the offline run would.
// docs/pipeline.md, "The ROS1 node".
#include <cstddef>
#include <functional>
#include <map>

#include "common/types.h"

namespace vilslam {

struct LiveInputConfig {
  // Two images are one stereo frame when their stamps differ by at most this (hardware-triggered pairs: 0).
  TimeNs max_pair_gap_ns = 1'000'000;
  // Images waiting for their other half; the oldest is dropped (unpaired) when one more arrives.
  std::size_t max_waiting_images = 8;
};

// Where the ordered, paired messages go: a System's push_imu / push_stereo / push_scan, or a test's lists.
struct LiveInputSink {
  std::function<void(const ImuSample&)> imu;
  std::function<void(StereoFrame)> stereo;
  std::function<void(LidarScan)> scan;
};

// What LiveInput dropped, per reason.
struct LiveInputDrops {
  std::size_t imu_out_of_order = 0;     // IMU samples not after the previous one (duplicated or late stamps)
  std::size_t frames_out_of_order = 0;  // stereo frames not after the previous one
  std::size_t scans_out_of_order = 0;   // sweeps not starting after the previous one
  std::size_t unpaired_images = 0;      // images whose other half never came
};

class LiveInput {
 public:
  LiveInput(const LiveInputConfig& config, LiveInputSink sink);

  void imu(const ImuSample& sample);
  // camera: 0 (left, cam0) or 1 (right, cam1); an 8-bit grey image.
  void image(int camera, TimeNs t_ns, cv::Mat grey);
  void scan(LidarScan scan);

  const LiveInputDrops& drops() const { return drops_; }

 private:
  struct HalfPair {
    cv::Mat images[2];
  };
  // The waiting image nearest t_ns within max_pair_gap_ns that lacks this camera's half, or end().
  std::map<TimeNs, HalfPair>::iterator partner(int camera, TimeNs t_ns);

  LiveInputConfig config_;
  LiveInputSink sink_;
  std::map<TimeNs, HalfPair> waiting_;  // by the first half's stamp
  TimeNs last_imu_ns_;
  TimeNs last_frame_ns_;
  TimeNs last_scan_ns_;
  LiveInputDrops drops_;
};

}  // namespace vilslam
