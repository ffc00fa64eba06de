#include "map/map_builder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "common/error.h"
#include "io/dataset_index.h"
#include "lidar/azimuth_times.h"
#include "lidar/dewarp.h"
#include "lidar/sensor_traits.h"

namespace vilslam::map {

namespace {

void check_config(const MapBuilderConfig& c) {
  if (!(c.min_range_m >= 0.0) || !(c.max_range_m > c.min_range_m)) {
    throw std::invalid_argument("range filter needs 0 <= min_range_m < max_range_m");
  }
  if (!(c.max_pose_gap_s > 0.0)) throw std::invalid_argument("max_pose_gap_s must be positive");
  const lidar::MixedPixelConfig& m = c.mixed_pixels;
  if (!(m.min_gap_ratio > 0.0) || !(m.max_step_ratio >= 1.0) || m.direction_neighbours < 2 ||
      !(m.max_neighbour_angle_deg > 0.0 && m.max_neighbour_angle_deg < 90.0) ||
      !(m.max_incidence_deg > 0.0 && m.max_incidence_deg < 90.0)) {
    throw std::invalid_argument("mixed pixels need min_gap_ratio > 0, max_step_ratio >= 1, direction_neighbours >= 2 "
                                "and max_neighbour_angle_deg and max_incidence_deg in (0, 90)");
  }
  if (c.window_start_ns >= c.window_end_ns) throw std::invalid_argument("time window is empty (start >= end)");
}

void check_poses(const Trajectory& T_W_L) {
  for (std::size_t i = 1; i < T_W_L.size(); ++i) {
    if (T_W_L[i].t_ns <= T_W_L[i - 1].t_ns) {
      throw std::invalid_argument("pose times must increase strictly (pose " + std::to_string(i + 1) + ")");
    }
  }
}

// First pose at or after t_ns.
Trajectory::const_iterator pose_at_or_after(const Trajectory& T_W_L, TimeNs t_ns) {
  return std::lower_bound(T_W_L.begin(), T_W_L.end(), t_ns, [](const TimedPose& p, TimeNs t) { return p.t_ns < t; });
}

// True when poses bracket every instant of [start_t_ns, end_t_ns] with no gap above max_gap_ns.
bool covers(const Trajectory& T_W_L, TimeNs start_t_ns, TimeNs end_t_ns, TimeNs max_gap_ns) {
  if (T_W_L.empty() || start_t_ns < T_W_L.front().t_ns || end_t_ns > T_W_L.back().t_ns) return false;
  auto first = pose_at_or_after(T_W_L, start_t_ns);
  if (first != T_W_L.begin() && first->t_ns != start_t_ns) --first;
  const auto last = pose_at_or_after(T_W_L, end_t_ns);
  for (auto it = first; it != last; ++it) {
    if ((it + 1)->t_ns - it->t_ns > max_gap_ns) return false;
  }
  return true;
}

// Pose at t_ns interpolated between its neighbours (t_ns within the trajectory's span).
SE3 interpolated(const Trajectory& T_W_L, TimeNs t_ns) {
  const auto after = pose_at_or_after(T_W_L, t_ns);
  if (after == T_W_L.end()) return T_W_L.back().T_W_B;
  if (after == T_W_L.begin() || after->t_ns == t_ns) return after->T_W_B;
  const TimedPose& before = *(after - 1);
  const double alpha = static_cast<double>(t_ns - before.t_ns) / static_cast<double>(after->t_ns - before.t_ns);
  return interpolate(before.T_W_B, after->T_W_B, alpha);
}

std::string span_text(const Trajectory& T_W_L) {
  if (T_W_L.empty()) return {};
  char buf[96];
  std::snprintf(buf, sizeof buf, " (%.3f s to %.3f s)", ns_to_s(T_W_L.front().t_ns), ns_to_s(T_W_L.back().t_ns));
  return buf;
}

// The sweep's points in W that pass the range filter (range of the raw return) and are no mixed pixels.
std::vector<Eigen::Vector3f> sweep_in_world(const LidarScan& raw, const Trajectory& T_W_L,
                                            const MapBuilderConfig& config, MapBuildStats& stats) {
  // Dewarping uses only the motion relative to the sweep's end, so any continuous trajectory serves.
  const Trajectory& motion = config.motion.empty() ? T_W_L : config.motion;
  const auto motion_at = [&motion](TimeNs t_ns) { return interpolated(motion, t_ns); };
  const LidarScan end_frame = config.dewarp ? lidar::dewarp(raw, motion_at) : raw;
  const SE3 T_W_end = interpolated(T_W_L, raw.end_t_ns());
  const std::vector<bool> mixed =
      config.drop_mixed_pixels ? lidar::mixed_pixels(raw, config.mixed_pixels) : std::vector<bool>(raw.points.size());
  std::vector<Eigen::Vector3f> points_W;
  points_W.reserve(raw.points.size());
  for (std::size_t i = 0; i < raw.points.size(); ++i) {
    const LidarPoint& r = raw.points[i];
    const double range_m = std::sqrt(double(r.x) * r.x + double(r.y) * r.y + double(r.z) * r.z);
    if (range_m < config.min_range_m || range_m > config.max_range_m) {
      ++stats.points_out_of_range;
      continue;
    }
    if (mixed[i]) {
      ++stats.points_mixed;
      continue;
    }
    const LidarPoint& p = end_frame.points[i];
    points_W.push_back((T_W_end * Vec3(p.x, p.y, p.z)).cast<float>());
  }
  return points_W;
}

}  // namespace

MapBuildResult build_dense_map(const std::string& dataset_path, const Trajectory& T_W_L, const MapBuilderConfig& config,
                               const std::function<void(double)>& progress) {
  check_config(config);
  check_poses(T_W_L);
  check_poses(config.motion);
  MapBuildResult result{DenseMap(config.voxel_size_m), {}};
  // The index, not the event stream: only the scans are loaded, never the images.
  const DatasetIndex index = index_dataset(dataset_path);
  if (index.scans.empty()) throw InputError(dataset_path, "dataset has no LiDAR scans");
  const TimeNs offset_ns = index.calibration.lidar_time_offset_ns;
  const TimeNs max_gap_ns = s_to_ns(config.max_pose_gap_s);
  const lidar::SensorTraits traits = lidar::first_sweep_traits(index);  // as the run read them (lidar_feeder.h)
  for (std::size_t i = 0; i < index.scans.size(); ++i) {
    if (progress) progress(double(i) / index.scans.size());
    const ScanEntry& entry = index.scans[i];
    // The sweep start is checked before loading; the end is known only from the points.
    const TimeNs start_t_ns = entry.t_ns + offset_ns;
    if (!covers(T_W_L, start_t_ns, start_t_ns, max_gap_ns)) {
      ++result.stats.sweeps_skipped;
      continue;
    }
    LidarScan scan = load_scan(index, i);
    scan.t_ns += offset_ns;
    if (config.dewarp && config.azimuth_times && traits.read()) {
      lidar::fill_missing_point_times(scan, traits, index.calibration.lidar.rate_hz);  // as the run did
    }
    if (scan.points.empty() || !covers(T_W_L, scan.t_ns, scan.end_t_ns(), max_gap_ns) ||
        (!config.motion.empty() && !covers(config.motion, scan.t_ns, scan.end_t_ns(), max_gap_ns))) {
      ++result.stats.sweeps_skipped;
      continue;
    }
    if (scan.end_t_ns() < config.window_start_ns || scan.end_t_ns() >= config.window_end_ns) {
      ++result.stats.sweeps_outside_window;
      continue;
    }
    const std::vector<Eigen::Vector3f> points_W = sweep_in_world(scan, T_W_L, config, result.stats);
    result.stats.points_inserted += result.map.insert(points_W);
    ++result.stats.sweeps_used;
  }
  if (result.stats.sweeps_used == 0) {
    throw InputError(dataset_path, "no LiDAR sweep lies within the time span of the " + std::to_string(T_W_L.size()) +
                                       " poses" + span_text(T_W_L) +
                                       (result.stats.sweeps_outside_window > 0 ? " and ends within the time window" : ""));
  }
  return result;
}

}  // namespace vilslam::map
