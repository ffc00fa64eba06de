#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>

#include "common/error.h"
#include "io/trajectory_io.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// A random trajectory with strictly increasing nanosecond times and generic poses.
Trajectory random_trajectory(std::size_t n, TimeNs t0_ns, TimeNs step_ns, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Trajectory traj;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 t(100 * u(rng), 100 * u(rng), 10 * u(rng));
    const Vec3 phi(3 * u(rng), 3 * u(rng), 3 * u(rng));
    traj.push_back({t0_ns + static_cast<TimeNs>(i) * step_ns + static_cast<TimeNs>(i % 7), SE3(so3::exp_quat(phi), t)});
  }
  return traj;
}

void expect_same(const Trajectory& a, const Trajectory& b, double tol) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].t_ns, b[i].t_ns) << i;
    EXPECT_LT((a[i].T_W_B.translation() - b[i].T_W_B.translation()).norm(), tol) << i;
    EXPECT_LT((a[i].T_W_B.rotation() - b[i].T_W_B.rotation()).cwiseAbs().maxCoeff(), tol) << i;
  }
}


// Expects read_trajectory to throw an InputError naming the file and the given line.
void expect_input_error(const fs::path& path, TrajectoryFormat format, long line, const std::string& what) {
  try {
    read_trajectory(path.string(), format);
    FAIL() << "no error for " << what;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path.string()) << what;
    EXPECT_EQ(e.line(), line) << what << ": " << e.what();
  }
}

// Writes, detects and reads back a trajectory with 19-digit ns times: equal to the ns and 1e-9.
void expect_exact_round_trip(TrajectoryFormat format, const std::string& name, std::uint32_t seed) {
  const fs::path path = test::temp_dir() / name;
  const Trajectory traj = random_trajectory(200, 1403715529112143517, 5'000'001, seed);
  write_trajectory(path.string(), traj, format);
  EXPECT_EQ(detect_trajectory_format(path.string()), format);
  expect_same(traj, read_trajectory(path.string(), format), 1e-9);
}

TEST(TrajectoryIo, TumRoundTripIsExact) { expect_exact_round_trip(TrajectoryFormat::kTum, "a.txt", 1); }

TEST(TrajectoryIo, EurocRoundTripIsExact) { expect_exact_round_trip(TrajectoryFormat::kEuroc, "a.csv", 2); }

TEST(TrajectoryIo, KittiRoundTripWithIndexTimes) {
  const fs::path dir = test::temp_dir();
  Trajectory traj = random_trajectory(200, 0, kNsPerSecond, 3);
  for (std::size_t i = 0; i < traj.size(); ++i) traj[i].t_ns = static_cast<TimeNs>(i) * kNsPerSecond;
  write_trajectory((dir / "a.txt").string(), traj, TrajectoryFormat::kKitti);
  expect_same(traj, read_trajectory((dir / "a.txt").string(), TrajectoryFormat::kKitti), 1e-9);
  EXPECT_EQ(detect_trajectory_format((dir / "a.txt").string()), TrajectoryFormat::kKitti);
}

TEST(TrajectoryIo, KittiTimesFile) {
  const fs::path dir = test::temp_dir();
  test::write_file_bytes(dir / "p.txt", "1 0 0 1 0 1 0 2 0 0 1 3\n1 0 0 4 0 1 0 5 0 0 1 6\n");
  test::write_file_bytes(dir / "t.txt", "0.5\n1.25e0\n");
  const Trajectory traj = read_trajectory((dir / "p.txt").string(), TrajectoryFormat::kKitti, (dir / "t.txt").string());
  ASSERT_EQ(traj.size(), 2u);
  EXPECT_EQ(traj[0].t_ns, 500'000'000);
  EXPECT_EQ(traj[1].t_ns, 1'250'000'000);
  EXPECT_EQ(traj[1].T_W_B.translation(), Vec3(4, 5, 6));
  test::write_file_bytes(dir / "t3.txt", "0.5\n1\n2\n");
  EXPECT_THROW(read_trajectory((dir / "p.txt").string(), TrajectoryFormat::kKitti, (dir / "t3.txt").string()),
               InputError);
}

TEST(TrajectoryIo, TumSecondsAreReadWithoutRoundingThroughDouble) {
  const fs::path dir = test::temp_dir();
  test::write_file_bytes(dir / "a.txt",
             "# t x y z qx qy qz qw\n1.403715529112143517e+09 0 0 0 0 0 0 1\n1403715529.2121431835 0 0 0 0 0 0 1\n");
  const Trajectory traj = read_trajectory((dir / "a.txt").string(), TrajectoryFormat::kTum);
  ASSERT_EQ(traj.size(), 2u);
  EXPECT_EQ(traj[0].t_ns, 1403715529112143517);
  EXPECT_EQ(traj[1].t_ns, 1403715529212143184);  // rounded half up at the ns digit
}

TEST(TrajectoryIo, EurocIgnoresExtraStateColumns) {
  const fs::path dir = test::temp_dir();
  test::write_file_bytes(dir / "a.csv",
             "#timestamp, p, q, v, b_w, b_a\n"
             "100,1,2,3,0.5,0.5,0.5,0.5,9,9,9,8,8,8,7,7,7\n200, 4, 5, 6, 1, 0, 0, 0\n");
  const Trajectory traj = read_trajectory((dir / "a.csv").string(), TrajectoryFormat::kEuroc);
  ASSERT_EQ(traj.size(), 2u);
  EXPECT_EQ(traj[0].t_ns, 100);
  EXPECT_EQ(traj[0].T_W_B.translation(), Vec3(1, 2, 3));
  EXPECT_NEAR(traj[0].T_W_B.quat().w(), 0.5, 1e-15);
  EXPECT_EQ(traj[1].T_W_B.translation(), Vec3(4, 5, 6));
}

TEST(TrajectoryIo, BadInputsNameFileAndLine) {
  const fs::path dir = test::temp_dir();
  const std::string ok = "# header\n1.0 0 0 0 0 0 0 1\n";
  const struct {
    const char* name;
    std::string text;
    long line;
  } cases[] = {
      {"columns", ok + "2.0 0 0 0 0 0 1\n", 3},
      {"non-numeric", ok + "2.0 0 abc 0 0 0 0 1\n", 3},
      {"nan", ok + "2.0 0 0 nan 0 0 0 1\n", 3},
      {"inf", ok + "2.0 0 0 0 0 0 0 inf\n", 3},
      {"bad time", ok + "2.0.1 0 0 0 0 0 0 1\n", 3},
      {"decreasing time", ok + "0.5 0 0 0 0 0 0 1\n", 3},
      {"non-unit quaternion", ok + "2.0 0 0 0 0 0 0 1.1\n", 3},
  };
  for (const auto& c : cases) {
    const fs::path path = dir / (std::string(c.name) + ".txt");
    test::write_file_bytes(path, c.text);
    expect_input_error(path, TrajectoryFormat::kTum, c.line, c.name);
  }
  test::write_file_bytes(dir / "k.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 2 0\n");
  expect_input_error(dir / "k.txt", TrajectoryFormat::kKitti, 2, "non-orthonormal rotation");
  test::write_file_bytes(dir / "e.csv", "#t\n100,1,2,3,1,0,0,0\n100x,1,2,3,1,0,0,0\n");
  expect_input_error(dir / "e.csv", TrajectoryFormat::kEuroc, 3, "bad ns timestamp");
  test::write_file_bytes(dir / "e2.csv", "100,1,2,3,1,0,0,0,5\n");
  expect_input_error(dir / "e2.csv", TrajectoryFormat::kEuroc, 1, "euroc column count");
  expect_input_error(dir / "missing.txt", TrajectoryFormat::kTum, 0, "missing file");
}

TEST(TrajectoryIo, WriteLeavesNoTemporaryFile) {
  const fs::path dir = test::temp_dir();
  write_trajectory((dir / "a.txt").string(), random_trajectory(5, 0, 1000, 4), TrajectoryFormat::kTum);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  EXPECT_THROW(write_trajectory((dir / "no_such_dir" / "a.txt").string(), {}, TrajectoryFormat::kTum), InputError);
}

TEST(TrajectoryIo, ReadsSharedKittiFiles) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "trajectories");
  const std::string times = dir + "/KITTI_00_gt_times.txt";
  for (const char* name : {"KITTI_00_gt.txt", "KITTI_00_ORB.txt", "KITTI_00_SPTAM.txt"}) {
    const std::string path = dir + "/" + name;
    EXPECT_EQ(detect_trajectory_format(path), TrajectoryFormat::kKitti) << name;
    const Trajectory traj = read_trajectory(path, TrajectoryFormat::kKitti, times);
    ASSERT_EQ(traj.size(), 4541u) << name;
    EXPECT_EQ(traj[1].t_ns, 103'735'900);
    EXPECT_EQ(traj.back().t_ns, 470'581'600'000);
    EXPECT_EQ(read_trajectory(path, TrajectoryFormat::kKitti).back().t_ns, 4540 * kNsPerSecond);
  }
  const Trajectory gt = read_trajectory(dir + "/KITTI_00_gt.txt", TrajectoryFormat::kKitti);
  EXPECT_NEAR(gt[1].T_W_B.translation().z(), 8.586941e-01, 1e-12);
}

TEST(TrajectoryIo, ReadsSharedEurocAndTumFiles) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "trajectories");
  const Trajectory gt = read_trajectory(dir + "/V102_groundtruth.csv", detect_trajectory_format(dir + "/V102_groundtruth.csv"));
  ASSERT_EQ(gt.size(), 16702u);
  EXPECT_EQ(gt.front().t_ns, 1403715524907143168);
  EXPECT_NEAR(gt.front().T_W_B.quat().w(), 0.161996, 1e-6);
  EXPECT_NEAR(gt.front().T_W_B.translation().y(), 1.996773, 1e-12);
  const Trajectory fr1 = read_trajectory(dir + "/freiburg1_xyz-groundtruth.txt", TrajectoryFormat::kTum);
  EXPECT_EQ(fr1.size(), 3000u);
  EXPECT_EQ(read_trajectory(dir + "/freiburg1_xyz-rgbdslam.txt", TrajectoryFormat::kTum).size(), 788u);
  EXPECT_EQ(read_trajectory(dir + "/fr2_desk_ORB.txt", TrajectoryFormat::kTum).size(), 2893u);
}

// A row repeating the previous time is dropped (the first pose at that time stays); a time that goes
// back is still an error naming its line, also after a repeat.
TEST(TrajectoryIo, RepeatedTimeDropsTheRowDecreasingTimeIsAnError) {
  const fs::path dir = test::temp_dir();
  test::write_file_bytes(dir / "r.txt", "1.0 1 0 0 0 0 0 1\n2.0 2 0 0 0 0 0 1\n2.0 9 0 0 0 0 0 1\n3.0 3 0 0 0 0 0 1\n");
  const Trajectory traj = read_trajectory((dir / "r.txt").string(), TrajectoryFormat::kTum);
  ASSERT_EQ(traj.size(), 3u);
  EXPECT_EQ(traj[1].t_ns, 2 * kNsPerSecond);
  EXPECT_EQ(traj[1].T_W_B.translation().x(), 2.0);
  EXPECT_EQ(traj[2].T_W_B.translation().x(), 3.0);
  test::write_file_bytes(dir / "e.csv", "100,1,2,3,1,0,0,0\n100,4,5,6,1,0,0,0\n");
  ASSERT_EQ(read_trajectory((dir / "e.csv").string(), TrajectoryFormat::kEuroc).size(), 1u);
  test::write_file_bytes(dir / "d.txt", "1.0 1 0 0 0 0 0 1\n2.0 2 0 0 0 0 0 1\n2.0 9 0 0 0 0 0 1\n1.5 3 0 0 0 0 0 1\n");
  expect_input_error(dir / "d.txt", TrajectoryFormat::kTum, 4, "decreasing after a repeat");
}

// Two of the shared files repeat timestamps with a different pose (V102.txt lines 433, 684, 736, 788;
// fr2_desk ground truth line 10863); each loses exactly those rows, keeping the first pose at each time.
TEST(TrajectoryIo, SharedFilesWithRepeatedTimestampsLoseTheRepeatedRow) {
  VILSLAM_REQUIRE_SHARED_DATA(dir, "trajectories");
  const struct {
    const char* name;
    std::size_t rows;
    TimeNs repeated_ns;
    double first_x;  // the pose of the first row at the repeated time, the one kept
  } files[] = {{"V102.txt", 807 - 4, 1403715572'212143183, 1.16564},
               {"fr2_desk_groundtruth.txt", 20957 - 1, 1311868229'576000000, 1.4054}};
  for (const auto& f : files) {
    const Trajectory traj = read_trajectory(dir + "/" + f.name, TrajectoryFormat::kTum);
    for (std::size_t i = 1; i < traj.size(); ++i) ASSERT_GT(traj[i].t_ns, traj[i - 1].t_ns) << f.name << " " << i;
    EXPECT_EQ(traj.size(), f.rows) << f.name;
    const auto at = std::find_if(traj.begin(), traj.end(), [&](const TimedPose& p) { return p.t_ns == f.repeated_ns; });
    ASSERT_NE(at, traj.end());
    EXPECT_EQ(at->T_W_B.translation().x(), f.first_x) << f.name;
  }
}

}  // namespace
}  // namespace vilslam
