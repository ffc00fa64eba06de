// The tilt error of eval/tilt_error.h and `vilslam eval --tilt --start-s --end-s`.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <tuple>

#include "eval/tilt_error.h"
#include "io/trajectory_io.h"
#include "cli_output.h"
#include "test_util.h"

namespace vilslam::eval {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// A route that rolls, pitches and yaws: the tilt error must not depend on where the body points.
Trajectory tilting_route(int n) {
  Trajectory gt;
  for (int i = 0; i < n; ++i) {
    const double s = 0.1 * i;
    const Mat3 R = so3::exp(Vec3(0, 0, 0.7 * s)) * so3::exp(Vec3(0.02 * std::sin(s), 0.03 * std::cos(2 * s), 0));
    gt.push_back({s_to_ns(1.0 + s), SE3(R, Vec3(s, 2 * std::sin(s), 0.1 * s * s))});
  }
  return gt;
}

TEST(TiltError, IsTheBodyTiltAndIgnoresYawAndPosition) {
  const Trajectory gt = tilting_route(60);
  // The estimate's world yawed 40 deg and shifted (a VIO's own heading), each body rolled 0.5 deg more.
  const SE3 T_est_gt(so3::exp(Vec3(0, 0, 40 * kDegToRad)), Vec3(3, -1, 0.2));
  Trajectory est;
  const SE3 roll(so3::exp(Vec3(0.5 * kDegToRad, 0, 0)), Vec3::Zero());
  for (const TimedPose& p : gt) est.push_back({p.t_ns, T_est_gt * p.T_W_B * roll});
  // (0.5 deg exactly for a horizontal x axis; the route's within 2 deg of it: 0.5 (1 - cos 2 deg) = 3e-4 deg less.)
  for (const double e : tilt_errors_deg(gt, est)) EXPECT_NEAR(e, 0.5, 1e-3);
  // A heading that drifts (each pose yawed about the world's vertical by its own angle) is no tilt.
  Trajectory yawed;
  for (const TimedPose& p : gt) {
    yawed.push_back({p.t_ns, SE3(so3::exp(Vec3(0, 0, 0.01 * ns_to_s(p.t_ns))), Vec3::Zero()) * p.T_W_B});
  }
  for (const double e : tilt_errors_deg(gt, yawed)) EXPECT_NEAR(e, 0.0, 1e-9);
  // A world tilted 0.2 deg about x: every body is 0.2 deg off, whatever its heading.
  Trajectory world_tilted;
  const SE3 world_roll(so3::exp(Vec3(0.2 * kDegToRad, 0, 0)), Vec3::Zero());
  for (const TimedPose& p : gt) world_tilted.push_back({p.t_ns, world_roll * p.T_W_B});
  for (const double e : tilt_errors_deg(gt, world_tilted)) EXPECT_NEAR(e, 0.2, 1e-9);
  EXPECT_THROW(tilt_errors_deg(gt, Trajectory(gt.begin(), gt.begin() + 5)), std::invalid_argument);
  EXPECT_THROW(tilt_errors_deg({}, {}), std::invalid_argument);
}

TEST(CmdEvalTilt, PrintsTheTiltOfTheWindowOnly) {
  const Trajectory gt = tilting_route(60);  // 1.0 .. 6.9 s
  Trajectory est;
  for (const TimedPose& p : gt) {
    const double roll_deg = p.t_ns < s_to_ns(4.0) ? 1.0 : 0.25;  // 1 deg for the first 3 s, then 0.25 deg
    est.push_back({p.t_ns, p.T_W_B * SE3(so3::exp(Vec3(roll_deg * kDegToRad, 0, 0)), Vec3::Zero())});
  }
  const auto dir = test::temp_dir();
  write_trajectory((dir / "gt.tum").string(), gt, TrajectoryFormat::kTum);
  write_trajectory((dir / "est.tum").string(), est, TrajectoryFormat::kTum);
  const std::string args =
      "eval --est " + (dir / "est.tum").string() + " --gt " + (dir / "gt.tum").string() + " --tilt";
  for (const auto& [window, mean_deg, count] :
       {std::tuple{"", 0.625, 60}, std::tuple{" --end-s 3", 1.0, 30}, std::tuple{" --start-s 3", 0.25, 30}}) {
    const auto json = dir / "tilt.json";
    const test::CliResult r = test::run_cli(args + window + " --json " + json.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("tilt [deg]"), std::string::npos) << r.output;
    const std::string doc = test::read_file_bytes(json);
    EXPECT_NEAR(test::json_number(doc, "tilt_deg", "mean"), mean_deg, 2e-3) << window;  // as above
    EXPECT_EQ(test::json_number(doc, "matched_poses", "matched_poses"), count) << window;
  }
  // Without --tilt no tilt row (the frames need not be gravity-aligned); a window that is not finite is refused.
  const test::CliResult plain =
      test::run_cli("eval --est " + (dir / "est.tum").string() + " --gt " + (dir / "gt.tum").string());
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_EQ(plain.output.find("tilt"), std::string::npos) << plain.output;
  const test::CliResult bad = test::run_cli(args + " --start-s nan");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--start-s must be finite"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace vilslam::eval
