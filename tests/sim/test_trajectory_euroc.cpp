#include <gtest/gtest.h>

#include <cmath>

#include "io/euroc_tables.h"
#include "sim/imu_sim.h"
#include "sim/trajectory.h"
#include "test_util.h"

namespace vilslam::sim {
namespace {

double rotation_angle(const SE3& a, const SE3& b) { return so3::log(a.quat().conjugate() * b.quat()).norm(); }

// The spline through EuRoC's real poses follows them (Vicon noise is a millimetre) and its IMU
// resembles the real one: the rig flies the real motion.
TEST(PoseSplineMotion, FollowsEurocGroundTruthAndItsImu) {
  VILSLAM_REQUIRE_SHARED_DATA(mav0, "euroc/V1_01_easy_micro/mav0");
  Trajectory gt;
  for (const GroundTruthState& s :
       read_groundtruth_tum(mav0 + "/state_groundtruth_estimate0/groundtruth.tum", SE3::identity()))
    gt.push_back({s.t_ns, s.T_W_I});
  gt.resize(std::min<std::size_t>(gt.size(), 6000));  // 30 s keeps the test fast
  const PoseSplineMotion motion(gt);
  double sq = 0, max_angle = 0;
  for (const TimedPose& p : gt) {
    const SE3 T = motion.pose(p.t_ns);
    sq += (T.translation() - p.T_W_B.translation()).squaredNorm();
    max_angle = std::max(max_angle, rotation_angle(T, p.T_W_B));
  }
  EXPECT_LT(std::sqrt(sq / gt.size()), 0.003);
  EXPECT_LT(max_angle, 0.5 * M_PI / 180);

  // Compare the derived gyro with the real one (minus a constant bias): the same motion.
  const std::vector<ImuSample> real = read_imu_csv(mav0 + "/imu0/data.csv");
  double err_sq = 0, real_sq = 0;
  Vec3 mean_diff = Vec3::Zero();
  std::vector<std::pair<Vec3, Vec3>> pairs;
  for (const ImuSample& s : real) {
    if (s.t_ns < motion.start_ns() || s.t_ns > motion.end_ns()) continue;
    pairs.emplace_back(ideal_imu(motion.state(s.t_ns)).gyro_rad_s, s.gyro_rad_s);
    mean_diff += s.gyro_rad_s - pairs.back().first;
  }
  ASSERT_GT(pairs.size(), 1000u);
  mean_diff /= static_cast<double>(pairs.size());
  for (const auto& [sim, meas] : pairs) {
    err_sq += (meas - mean_diff - sim).squaredNorm();
    real_sq += (meas - mean_diff).squaredNorm();
  }
  EXPECT_LT(std::sqrt(err_sq / real_sq), 0.3) << "relative gyro error";
}

}  // namespace
}  // namespace vilslam::sim
