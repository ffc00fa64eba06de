// Preintegration on real EuRoC V1_02_medium data: 1 s windows started from the ground-truth state
// predict the ground-truth pose 1 s later (body = IMU for V1_02, imu0 T_BS is the identity).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <variant>

#include "io/dataset.h"
#include "test_util.h"
#include "vio/imu_factor.h"

namespace vilslam {
namespace {

struct WindowErrors {
  std::vector<double> position_m;
  std::vector<double> rotation_deg;
};

NavState to_nav_state(const GroundTruthState& gt, bool with_biases) {
  NavState x;
  x.t_ns = gt.t_ns;
  x.R_W_I = gt.T_W_I.rotation();
  x.p_W_I = gt.T_W_I.translation();
  x.v_W_m_s = gt.v_W_m_s;
  if (with_biases) {
    x.bias_gyro_rad_s = gt.bias_gyro_rad_s;
    x.bias_accel_m_s2 = gt.bias_accel_m_s2;
  }
  return x;
}

WindowErrors evaluate(const std::vector<ImuSample>& imu, const std::vector<GroundTruthState>& gt, const ImuNoise& noise,
                      bool with_biases) {
  WindowErrors e;
  const Vec3 gravity(0, 0, -9.81);
  const TimeNs window_ns = kNsPerSecond;
  for (size_t i = 0; i < gt.size(); i += 4) {  // a window every 0.1 s
    const TimeNs t0 = gt[i].t_ns, t1 = t0 + window_ns;
    if (t0 < imu.front().t_ns || t1 > imu.back().t_ns) continue;
    const auto j = std::lower_bound(gt.begin(), gt.end(), t1,
                                    [](const GroundTruthState& g, TimeNs t) { return g.t_ns < t; });
    if (j == gt.end() || std::abs(j->t_ns - t1) > 2'000'000) continue;
    const NavState x0 = to_nav_state(gt[i], with_biases);
    Preintegration p(x0.bias_gyro_rad_s, x0.bias_accel_m_s2, noise);
    integrate_samples(imu, t0, j->t_ns, p);
    const NavState x1 = predict_state(p, x0, gravity);
    e.position_m.push_back((x1.p_W_I - j->T_W_I.translation()).norm());
    e.rotation_deg.push_back(so3::log(Mat3(x1.R_W_I.transpose() * j->T_W_I.rotation())).norm() * 180.0 / M_PI);
  }
  return e;
}

TEST(EurocPreintegration, OneSecondWindowsPredictGroundTruth) {
  VILSLAM_REQUIRE_SHARED_DATA(path, "euroc/V1_02_medium_imu");
  const std::unique_ptr<DatasetReader> reader = open_dataset(path);
  std::vector<ImuSample> imu;
  while (const std::optional<SensorEvent> ev = reader->next()) {
    if (const auto* s = std::get_if<ImuSample>(&ev->data)) imu.push_back(*s);
  }
  const std::vector<GroundTruthState>& gt = reader->groundtruth();
  ASSERT_GT(imu.size(), 7000u);
  ASSERT_GT(gt.size(), 1000u);

  const WindowErrors with = evaluate(imu, gt, reader->calibration().imu, true);
  const WindowErrors without = evaluate(imu, gt, reader->calibration().imu, false);
  ASSERT_GT(with.position_m.size(), 300u);
  const double pos_with = test::median(with.position_m), rot_with = test::median(with.rotation_deg);
  const double pos_without = test::median(without.position_m), rot_without = test::median(without.rotation_deg);
  std::printf("V1_02 1 s windows: %zu\n", with.position_m.size());
  std::printf("  ground-truth biases: median position error %.4f m, rotation error %.4f deg\n", pos_with, rot_with);
  std::printf("  zero biases:         median position error %.4f m, rotation error %.4f deg\n", pos_without,
              rot_without);
  EXPECT_LE(pos_with, 0.05);
  EXPECT_LE(rot_with, 0.3);
  EXPECT_GT(pos_without, 2.0 * pos_with);
  EXPECT_GT(rot_without, 2.0 * rot_with);
}

}  // namespace
}  // namespace vilslam
