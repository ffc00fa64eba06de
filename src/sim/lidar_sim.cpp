#include "sim/lidar_sim.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "sim/lidar_beams.h"
#include "sim/rng.h"

namespace vilslam::sim {
namespace {

constexpr float kMaxIntensity = 255.0f;

struct Slot {
  bool valid = false;
  LidarPoint point;
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
  std::vector<Slot> slots(static_cast<std::size_t>(columns) * beams);
  tbb::parallel_for(tbb::blocked_range<int>(0, columns, 32), [&](const tbb::blocked_range<int>& range) {
    for (int k = range.begin(); k < range.end(); ++k) {
      const SE3& T = poses[k];
      const float t_offset_s = static_cast<float>(ns_to_s(column_offset_ns(config, k)));
      for (int beam = 0; beam < beams; ++beam) {
        const Vec3 dir_L = beam_direction_L(config, beam, k, t_start_ns);
        const Vec3 dir_W = T.quat() * dir_L;
        const auto hit = world.raycast(T.translation(), dir_W, config.max_range_m);
        if (!hit) continue;
        const std::size_t index = static_cast<std::size_t>(k) * beams + beam;
        // The range noise of a beam is a pure function of (noise_seed, beam index).
        const double range = hit->range_m + config.range_noise_sigma_m * rng_for(noise_seed, index).gaussian();
        if (range < config.min_range_m || range > config.max_range_m) continue;
        // Lambertian return: reflectivity times the cosine of the incidence angle.
        const double cos_incidence = std::abs(hit->normal_W.dot(dir_W));
        const Vec3 p_L = range * dir_L;
        Slot& slot = slots[index];
        slot.valid = true;
        slot.point.x = static_cast<float>(p_L.x());
        slot.point.y = static_cast<float>(p_L.y());
        slot.point.z = static_cast<float>(p_L.z());
        slot.point.intensity = std::clamp(kMaxIntensity * hit->reflectivity * static_cast<float>(cos_incidence), 0.0f,
                                          kMaxIntensity);
        slot.point.t_offset_s = t_offset_s;
        slot.point.ring = spinning ? static_cast<std::uint16_t>(beam) : 0;
      }
    }
  });
  LidarScan scan;
  scan.t_ns = t_start_ns;
  scan.has_ring = spinning;
  for (const Slot& slot : slots) {
    if (slot.valid) scan.points.push_back(slot.point);
  }
  return scan;
}

}  // namespace vilslam::sim
