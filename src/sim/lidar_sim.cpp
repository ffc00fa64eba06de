#include "sim/lidar_sim.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "sim/lidar_beams.h"

namespace vilslam::sim {
namespace {

constexpr float kMaxIntensity = 255.0f;

// A beam's hit before the sensor's return model: range 0 when the ray hit nothing.
struct Hit {
  Vec3 dir_L = Vec3::Zero();
  double range_m = 0;
  float reflectivity = 0;
  float cos_incidence = 0;
};

}  // namespace

LidarScan simulate_sweep(const World& world, const LidarSimConfig& config, TimeNs t_start_ns,
                         const std::function<SE3(TimeNs)>& T_W_L, std::uint64_t noise_seed) {
  check_lidar_config(config);
  const int columns = num_columns(config), beams = beams_per_column(config);
  const bool spinning = config.pattern == LidarPattern::kSpinning;
  // Poses are evaluated serially (the caller's pose function need not be thread-safe); rays in parallel.
  std::vector<SE3> poses(columns);
  for (int k = 0; k < columns; ++k) poses[k] = T_W_L(t_start_ns + column_offset_ns(config, k));
  const std::size_t count = static_cast<std::size_t>(columns) * beams;
  std::vector<Hit> hits(count);
  tbb::parallel_for(tbb::blocked_range<int>(0, columns, 32), [&](const tbb::blocked_range<int>& range) {
    for (int k = range.begin(); k < range.end(); ++k) {
      for (int beam = 0; beam < beams; ++beam) {
        const Vec3 dir_L = beam_direction_L(config, beam, k, t_start_ns);
        const Vec3 dir_W = poses[k].quat() * dir_L;
        const auto hit = world.raycast(poses[k].translation(), dir_W, config.max_range_m);
        if (!hit) continue;
        Hit& h = hits[static_cast<std::size_t>(k) * beams + beam];
        h.dir_L = dir_L;
        h.range_m = hit->range_m;
        h.reflectivity = hit->reflectivity;
        h.cos_incidence = static_cast<float>(std::abs(hit->normal_W.dot(dir_W)));
      }
    }
  });
  // The return model compares each beam with its next firing (the next column), so it runs once every
  // hit is known.
  std::vector<std::optional<LidarPoint>> points(count);
  tbb::parallel_for(tbb::blocked_range<int>(0, columns, 32), [&](const tbb::blocked_range<int>& range) {
    for (int k = range.begin(); k < range.end(); ++k) {
      const float t_offset_s = static_cast<float>(ns_to_s(column_offset_ns(config, k)));
      for (int beam = 0; beam < beams; ++beam) {
        const std::size_t index = static_cast<std::size_t>(k) * beams + beam;
        const Hit& h = hits[index];
        if (h.range_m <= 0) continue;
        const double neighbour_m = k + 1 < columns ? hits[index + beams].range_m : 0.0;
        const double range = returned_range_m(config.returns, config.range_noise_sigma_m, h.range_m, neighbour_m,
                                              h.reflectivity, h.cos_incidence, noise_seed, index);
        if (range < config.min_range_m || range > config.max_range_m) continue;
        const Vec3 p_L = range * h.dir_L;
        LidarPoint& point = points[index].emplace();
        point.x = static_cast<float>(p_L.x());
        point.y = static_cast<float>(p_L.y());
        point.z = static_cast<float>(p_L.z());
        // Lambertian return: reflectivity times the cosine of the incidence angle.
        point.intensity = std::clamp(kMaxIntensity * h.reflectivity * h.cos_incidence, 0.0f, kMaxIntensity);
        point.t_offset_s = t_offset_s;
        point.ring = spinning ? static_cast<std::uint16_t>(beam) : 0;
      }
    }
  });
  LidarScan scan;
  scan.t_ns = t_start_ns;
  scan.has_ring = spinning;
  for (const std::optional<LidarPoint>& point : points) {
    if (point) scan.points.push_back(*point);
  }
  return scan;
}

}  // namespace vilslam::sim
