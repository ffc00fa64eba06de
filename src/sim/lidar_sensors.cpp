// The LiDAR models of the simulator, each following a real sensor's data sheet (docs/simulator.md).
#include <stdexcept>

#include "sim/lidar_sim.h"

namespace vilslam::sim {
namespace {

// 128 beams from -24.5 to +15 deg, dense around the horizon as on a Hesai Pandar128: 0.125 deg apart from
// -6 to +2 deg, 0.5 deg apart above and below.
std::vector<double> hesai128_elevations_deg() {
  std::vector<double> deg;
  for (int k = 37; k >= 1; --k) deg.push_back(-6.0 - 0.5 * k);
  for (int k = 0; k <= 64; ++k) deg.push_back(-6.0 + 0.125 * k);
  for (int k = 1; k <= 26; ++k) deg.push_back(2.0 + 0.5 * k);
  return deg;
}

}  // namespace

LidarSimConfig lidar_sensor(const std::string& name) {
  // VLP-16: 16 rings over +-15 deg, 0.2 deg at 10 Hz, +-3 cm typical accuracy, 100 m, 3 mrad beam
  // divergence; its data sheet gives no range per reflectivity, so 100 m is taken at 80 % (57 m at 10 %).
  LidarSimConfig c;
  c.sensor = name;
  c.returns.range_at_10pct_m = 57.0;
  c.returns.beam_divergence_rad = 0.003;
  c.returns.mixed_pixel_probability = 0.5;
  if (name == "vlp16") return c;
  if (name == "hesai128") {
    // Pandar128E3X data sheet: 0.2 deg azimuth at 10 Hz, 0.3-200 m, +-2 cm accuracy beyond 1 m.
    c.beam_elevations_deg = hesai128_elevations_deg();
    c.num_rings = static_cast<int>(c.beam_elevations_deg.size());
    c.min_elevation_deg = c.beam_elevations_deg.front();
    c.max_elevation_deg = c.beam_elevations_deg.back();
    c.min_range_m = 0.3;
    c.max_range_m = 200.0;
    c.returns.range_at_10pct_m = 200.0;  // the data sheet's range is given at 10 % reflectivity
    return c;
  }
  if (name == "mid360") {
    // Livox Mid-360 data sheet: 360 x 59 deg (-7 to +52 deg), 200,000 points/s, 10 Hz frames,
    // 0.1 m minimum range, 70 m at 80 % reflectivity, range error <= 2 cm (1 sigma at 10 m).
    c.pattern = LidarPattern::kNonRepetitive;
    c.num_rings = 0;
    c.min_elevation_deg = -7.0;
    c.max_elevation_deg = 52.0;
    c.min_range_m = 0.1;
    c.max_range_m = 70.0;
    c.returns.range_at_10pct_m = 40.0;
    return c;
  }
  throw std::invalid_argument("unknown LiDAR model '" + name + "' (vlp16, hesai128 or mid360)");
}

}  // namespace vilslam::sim
