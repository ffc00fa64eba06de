#include "pipeline/live_input.h"

#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <utility>

namespace vilslam {

LiveInput::LiveInput(const LiveInputConfig& config, LiveInputSink sink)
    : config_(config),
      sink_(std::move(sink)),
      last_imu_ns_(std::numeric_limits<TimeNs>::min()),
      last_frame_ns_(std::numeric_limits<TimeNs>::min()),
      last_scan_ns_(std::numeric_limits<TimeNs>::min()) {
  if (config.max_pair_gap_ns < 0 || config.max_waiting_images == 0) {
    throw std::invalid_argument("live input: max_pair_gap_ns must be >= 0 and max_waiting_images > 0");
  }
}

void LiveInput::imu(const ImuSample& sample) {
  if (sample.t_ns <= last_imu_ns_) {
    ++drops_.imu_out_of_order;
    return;
  }
  last_imu_ns_ = sample.t_ns;
  sink_.imu(sample);
}

std::map<TimeNs, LiveInput::HalfPair>::iterator LiveInput::partner(int camera, TimeNs t_ns) {
  auto best = waiting_.end();
  for (auto it = waiting_.lower_bound(t_ns - config_.max_pair_gap_ns);
       it != waiting_.end() && it->first <= t_ns + config_.max_pair_gap_ns; ++it) {
    if (!it->second.images[camera].empty()) continue;  // that stamp already has this camera's image
    if (best == waiting_.end() || std::llabs(it->first - t_ns) < std::llabs(best->first - t_ns)) best = it;
  }
  return best;
}

void LiveInput::image(int camera, TimeNs t_ns, cv::Mat grey) {
  if (camera != 0 && camera != 1) throw std::invalid_argument("live input: camera must be 0 (left) or 1 (right)");
  auto it = partner(camera, t_ns);
  if (it == waiting_.end()) {
    if (t_ns <= last_frame_ns_ || waiting_.count(t_ns) > 0) {  // too late to make a frame, or a repeated stamp
      ++drops_.unpaired_images;
      return;
    }
    if (waiting_.size() == config_.max_waiting_images) {
      waiting_.erase(waiting_.begin());
      ++drops_.unpaired_images;
    }
    waiting_[t_ns].images[camera] = std::move(grey);
    return;
  }
  // A frame takes the left image's stamp (cam0 is the rig's reference camera).
  StereoFrame frame;
  frame.t_ns = camera == 0 ? t_ns : it->first;
  frame.left = camera == 0 ? std::move(grey) : std::move(it->second.images[0]);
  frame.right = camera == 1 ? std::move(grey) : std::move(it->second.images[1]);
  // Halves older than this frame can no longer make one.
  for (auto old = waiting_.begin(); old != it; old = waiting_.erase(old)) ++drops_.unpaired_images;
  waiting_.erase(it);
  if (frame.t_ns <= last_frame_ns_) {
    ++drops_.frames_out_of_order;
    return;
  }
  last_frame_ns_ = frame.t_ns;
  sink_.stereo(std::move(frame));
}

void LiveInput::scan(LidarScan scan) {
  if (scan.t_ns <= last_scan_ns_) {
    ++drops_.scans_out_of_order;
    return;
  }
  last_scan_ns_ = scan.t_ns;
  sink_.scan(std::move(scan));
}

}  // namespace vilslam
