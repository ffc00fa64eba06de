// The smallest robot program on vilslam: sensor data pushed into vilslam::System as drivers would deliver it
// (here read from a dataset folder), outputs taken from the callbacks.
//   vilslam_consumer DATASET
#include <cstdio>
#include <exception>
#include <stdexcept>

#include "io/dataset.h"
#include "pipeline/system.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: vilslam_consumer DATASET\n");
    return 2;
  }
  try {
    const auto reader = vilslam::open_dataset(argv[1]);
    std::size_t imu_poses = 0, states = 0, sweeps = 0, loops = 0;
    vilslam::SystemCallbacks out;
    out.imu_pose = [&](const vilslam::TimedPose&) { ++imu_poses; };
    out.camera_state = [&](const vilslam::TimedPose&) { ++states; };
    out.lidar_pose = [&](const vilslam::lidar::LidarMappingResult&) { ++sweeps; };
    out.loop_candidate = [&](const vilslam::loop::LoopCandidateRecord& r) {
      if (r.accepted()) std::printf("loop %.3f s -> %.3f s\n", r.candidate_t_ns * 1e-9, r.query_t_ns * 1e-9);
      loops += r.accepted();
    };
    vilslam::OfflineRunConfig config;
    config.mode = vilslam::RunMode::kVil;
    config.loop.min_time_gap_s = 4.0;
    vilslam::System system(reader->calibration(), config, out);
    while (auto event = reader->next()) {
      if (auto* imu = std::get_if<vilslam::ImuSample>(&event->data)) system.push_imu(*imu);
      if (auto* pair = std::get_if<vilslam::StereoFrame>(&event->data)) system.push_stereo(std::move(*pair));
      if (auto* sweep = std::get_if<vilslam::LidarScan>(&event->data)) system.push_scan(std::move(*sweep));
    }
    const vilslam::OfflineRunResult result = system.finish();
    if (result.lidar.empty()) throw std::runtime_error("no LiDAR pose");
    const vilslam::SE3& last = result.lidar.back().T_W_L;
    std::printf("imu poses %zu, camera states %zu, lidar poses %zu, loops %zu, last lidar position %.3f %.3f %.3f\n",
                imu_poses, states, sweeps, loops, last.translation().x(), last.translation().y(),
                last.translation().z());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vilslam_consumer: %s\n", e.what());
    return 1;
  }
  return 0;
}
