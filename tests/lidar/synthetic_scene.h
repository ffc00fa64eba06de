#pragma once
// Test helper: a spinning 16-beam LiDAR ray-cast against a box-shaped room holding box obstacles, with
// every point measured from the sensor pose at its own instant (as a moving real sensor does).
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "common/lie.h"
#include "common/types.h"
#include "sim/lidar_beams.h"
#include "sim/rng.h"

namespace vilslam::test {

struct Box {
  Vec3 lo, hi;
};

struct Scene {
  Box room;                 // seen from inside
  std::vector<Box> blocks;  // seen from outside
};

// The default scene: a 24 x 16 x 5 m room with two blocks (convex vertical edges) off the centre.
inline Scene box_room() {
  return {{Vec3(-12, -8, -2), Vec3(12, 8, 3)},
          {{Vec3(3, 2, -2), Vec3(5, 4, 1)}, {Vec3(-6, -5, -2), Vec3(-4.5, -3, 2)}}};
}

// Slab intersection of the ray o + s d with a box: entry and exit parameters (entry > exit: miss).
inline std::pair<double, double> slab(const Box& b, const Vec3& o, const Vec3& d) {
  double enter = -std::numeric_limits<double>::infinity(), leave = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double s0 = (b.lo[k] - o[k]) / d[k], s1 = (b.hi[k] - o[k]) / d[k];
    enter = std::max(enter, std::min(s0, s1));
    leave = std::min(leave, std::max(s0, s1));
  }
  return {enter, leave};
}

inline double cast(const Scene& scene, const Vec3& o, const Vec3& d) {
  double range = slab(scene.room, o, d).second;
  for (const Box& b : scene.blocks) {
    const auto [enter, leave] = slab(b, o, d);
    if (enter <= leave && enter > 0.0) range = std::min(range, enter);
  }
  return range;
}

// |cos| of the incidence of direction d on the face of box b (seen from inside) that p lies on.
inline double cos_incidence_inside(const Box& b, const Vec3& p, const Vec3& d) {
  int face_axis = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    for (const double bound : {b.lo[axis], b.hi[axis]}) {
      if (std::abs(p[axis] - bound) < nearest) {
        nearest = std::abs(p[axis] - bound);
        face_axis = axis;
      }
    }
  }
  return std::abs(d[face_axis]);
}

// One sweep of a VLP-16-like sensor (16 rings, -15..15 deg, azimuth_step_deg) over duration_s from t_ns,
// with Gaussian range noise of range_noise_m (1 sigma), plus, with beam_divergence_rad, the spread of an
// oblique footprint on the room's faces, 0.5 r divergence tan(incidence) (the simulator's model, tan <= 10).
inline LidarScan sweep(const Scene& scene, const std::function<SE3(TimeNs)>& T_W_L, TimeNs t_ns,
                       double duration_s = 0.1, double azimuth_step_deg = 0.2, double range_noise_m = 0.0,
                       double beam_divergence_rad = 0.0) {
  sim::Rng rng(7);
  LidarScan scan;
  scan.t_ns = t_ns;
  const int columns = static_cast<int>(std::lround(360.0 / azimuth_step_deg));
  for (int c = 0; c < columns; ++c) {
    const double t_offset_s = duration_s * c / columns;
    const SE3 T = T_W_L(t_ns + s_to_ns(t_offset_s));
    const double azimuth = -M_PI + 2.0 * M_PI * c / columns;
    for (int ring = 0; ring < 16; ++ring) {
      const double elevation = (-15.0 + 2.0 * ring) * M_PI / 180.0;
      const Vec3 d_L(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                     std::sin(elevation));
      const Vec3 d_W = T.rotation() * d_L;
      const double true_range = cast(scene, T.translation(), d_W);
      const double cos_incidence = cos_incidence_inside(scene.room, T * (true_range * d_L), d_W);
      const double tan_incidence = std::min(10.0, std::sqrt(std::max(0.0, 1.0 - cos_incidence * cos_incidence)) /
                                                      std::max(cos_incidence, 1e-9));
      const double sigma_m = std::hypot(range_noise_m, 0.5 * true_range * beam_divergence_rad * tan_incidence);
      const double range = true_range + sigma_m * rng.gaussian();
      const Vec3 p_L = range * d_L;
      LidarPoint p;
      p.x = static_cast<float>(p_L.x());
      p.y = static_cast<float>(p_L.y());
      p.z = static_cast<float>(p_L.z());
      p.t_offset_s = static_cast<float>(t_offset_s);
      p.ring = static_cast<std::uint16_t>(ring);
      scan.points.push_back(p);
    }
  }
  return scan;
}

// Distance from p to the nearest of the 12 edges of box b, or of its 4 vertical (z) edges only.
inline double distance_to_box_edges(const Box& b, const Vec3& p, bool vertical_only = false) {
  double best = std::numeric_limits<double>::infinity();
  for (int axis = vertical_only ? 2 : 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const double along = std::clamp(p[axis], b.lo[axis], b.hi[axis]);
    for (double cu : {b.lo[u], b.hi[u]}) {
      for (double cv : {b.lo[v], b.hi[v]}) {
        Vec3 q;
        q[axis] = along;
        q[u] = cu;
        q[v] = cv;
        best = std::min(best, (p - q).norm());
      }
    }
  }
  return best;
}

inline double distance_to_scene_edges(const Scene& scene, const Vec3& p, bool vertical_only = false) {
  double best = distance_to_box_edges(scene.room, p, vertical_only);
  for (const Box& b : scene.blocks) best = std::min(best, distance_to_box_edges(b, p, vertical_only));
  return best;
}

// Moving at 3 m/s forward with a 60 deg/s yaw rate: 0.3 m and 6 deg over a 0.1 s sweep.
inline SE3 moving_pose(TimeNs t_ns) {
  const double t = ns_to_s(t_ns);
  return SE3(so3::exp(Vec3(0, 0, 60.0 * M_PI / 180.0 * t)), Vec3(3.0 * t - 1.0, 0.5, 0.2));
}

// One still sweep of the simulator's non-repetitive sensor (Mid-360 pattern) in the box room, with 2 cm
// range noise: no ring field, points in firing order.
inline LidarScan non_repetitive_sweep(const Scene& scene, const SE3& T_W_L) {
  const sim::LidarSimConfig config = sim::lidar_sensor("mid360");
  sim::Rng rng(3);
  LidarScan scan;
  scan.has_ring = false;
  for (int k = 0; k < sim::num_columns(config); ++k) {
    for (int head = 0; head < sim::beams_per_column(config); ++head) {
      const Vec3 d_L = sim::beam_direction_L(config, head, k);
      const double range = cast(scene, T_W_L.translation(), T_W_L.rotation() * d_L) + 0.02 * rng.gaussian();
      const Vec3 p_L = range * d_L;
      LidarPoint p;
      p.x = static_cast<float>(p_L.x());
      p.y = static_cast<float>(p_L.y());
      p.z = static_cast<float>(p_L.z());
      p.t_offset_s = static_cast<float>(ns_to_s(sim::column_offset_ns(config, k)));
      scan.points.push_back(p);
    }
  }
  return scan;
}

}  // namespace vilslam::test
