// KITTI odometry layout on a tiny synthetic folder (and the real KITTI 00 poses when present).
#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "io/dataset.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// KITTI odometry sequence 00 calibration (calib.txt of the benchmark).
const char* kCalib00 =
    "P0: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 0.000000000000e+00 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 0.000000000000e+00\n"
    "P1: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.861448000000e+02 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 0.000000000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 0.000000000000e+00\n"
    "P2: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 4.538225000000e+01 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 -1.130887000000e-01 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 3.779761000000e-03\n"
    "P3: 7.188560000000e+02 0.000000000000e+00 6.071928000000e+02 -3.372877000000e+02 0.000000000000e+00 "
    "7.188560000000e+02 1.852157000000e+02 2.369057000000e+00 0.000000000000e+00 0.000000000000e+00 "
    "1.000000000000e+00 4.915215000000e-03\n"
    "Tr: 4.276802385584e-04 -9.999672484946e-01 -8.084491683471e-03 -1.198459927713e-02 -7.210626507497e-03 "
    "8.081198471645e-03 -9.999413164504e-01 -5.403984729748e-02 9.999738645903e-01 4.859485810390e-04 "
    "-7.206933692422e-03 -2.921968648686e-01\n";

struct KittiFolder {
  fs::path base, seq;
  std::vector<std::vector<float>> scans;  // x y z r per point
  std::vector<cv::Mat> left;
};

// base/sequences/00/{calib.txt, times.txt, image_0, image_1, velodyne} and base/poses/00.txt (3 frames).
KittiFolder make_kitti_folder(const fs::path& base) {
  KittiFolder k;
  k.base = base;
  k.seq = base / "sequences" / "00";
  for (const char* sub : {"image_0", "image_1", "velodyne"}) fs::create_directories(k.seq / sub);
  fs::create_directories(base / "poses");
  std::ofstream(k.seq / "calib.txt") << kCalib00;
  std::ofstream(k.seq / "times.txt") << "0.000000e+00\n1.037359e-01\n2.073381e-01\n";
  std::ofstream(base / "poses" / "00.txt")
      << "1.000000e+00 0.000000e+00 0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00 "
         "0.000000e+00 0.000000e+00 0.000000e+00 1.000000e+00 0.000000e+00\n"
         "9.999978e-01 5.272628e-04 -2.066935e-03 -4.690294e-02 -5.296506e-04 9.999992e-01 -1.154865e-03 "
         "-2.839928e-02 2.066324e-03 1.155958e-03 9.999971e-01 8.586941e-01\n"
         "9.999910e-01 1.048972e-03 -4.131348e-03 -9.374345e-02 -1.058514e-03 9.999968e-01 -2.308104e-03 "
         "-5.676064e-02 4.128913e-03 2.312456e-03 9.999887e-01 1.716275e+00\n";
  cv::RNG rng(3);
  char name[32];
  for (int i = 0; i < 3; ++i) {
    cv::Mat l(30, 40, CV_8UC1), r(30, 40, CV_8UC1);
    rng.fill(l, cv::RNG::UNIFORM, 0, 256);
    rng.fill(r, cv::RNG::UNIFORM, 0, 256);
    std::snprintf(name, sizeof name, "%06d.png", i);
    cv::imwrite((k.seq / "image_0" / name).string(), l);
    cv::imwrite((k.seq / "image_1" / name).string(), r);
    k.left.push_back(l);
    std::vector<float> scan;
    for (int p = 0; p < 10 + i; ++p) {
      for (float v : {static_cast<float>(rng.uniform(-40.0, 40.0)), static_cast<float>(rng.uniform(-40.0, 40.0)),
                      static_cast<float>(rng.uniform(-2.0, 2.0)), static_cast<float>(rng.uniform(0.0, 1.0))}) {
        scan.push_back(v);
      }
    }
    std::snprintf(name, sizeof name, "%06d.bin", i);
    std::ofstream(k.seq / "velodyne" / name, std::ios::binary)
        .write(reinterpret_cast<const char*>(scan.data()), static_cast<std::streamsize>(scan.size() * sizeof(float)));
    k.scans.push_back(scan);
  }
  return k;
}

TEST(KittiReader, ReadsCalibrationFramesScansAndPoses) {
  const KittiFolder k = make_kitti_folder(test::temp_dir());
  const auto reader = open_dataset(k.seq.string() + "/");
  const DatasetSummary& s = reader->summary();
  EXPECT_EQ(s.format, "kitti");
  EXPECT_EQ(s.stereo_frames, 3u);
  EXPECT_EQ(s.lidar_scans, 3u);
  EXPECT_EQ(s.imu_samples, 0u);
  EXPECT_EQ(s.groundtruth_poses, 3u);

  const RigCalibration& c = reader->calibration();
  EXPECT_EQ(c.cam0.fx, 718.856);
  EXPECT_EQ(c.cam1.cy, 185.2157);
  EXPECT_EQ(c.cam0.width_px, 40);
  EXPECT_EQ(c.cam1.height_px, 30);
  EXPECT_EQ(c.cam0.distortion, DistortionModel::kNone);
  EXPECT_LT((c.T_I_C0.matrix() - Mat4::Identity()).norm(), 1e-15);
  // cam1 sits baseline = 386.1448 / 718.856 m to the right of cam0 (+x of the camera frame).
  EXPECT_NEAR(c.T_C0_C1().translation().x(), 386.1448 / 718.856, 1e-12);
  EXPECT_NEAR(c.T_C0_C1().translation().tail<2>().norm(), 0.0, 1e-15);
  EXPECT_TRUE(c.has_lidar);
  EXPECT_NEAR(c.T_I_L.translation().z(), -2.921968648686e-01, 1e-15);
  // Tr's printed rotation is orthonormal to ~1e-8 only; the reader keeps the nearest rotation.
  EXPECT_NEAR(c.T_I_L.rotation()(0, 1), -9.999672484946e-01, 1e-7);
  EXPECT_NEAR(c.cam0.rate_hz, 2.0 / 0.2073381, 1e-9);

  std::size_t frames = 0, scans = 0;
  while (auto e = reader->next()) {
    if (const auto* f = std::get_if<StereoFrame>(&e->data)) {
      EXPECT_EQ(cv::norm(f->left, k.left[frames], cv::NORM_INF), 0.0);
      ++frames;
    } else if (const auto* scan = std::get_if<LidarScan>(&e->data)) {
      const auto& raw = k.scans[scans];
      EXPECT_FALSE(scan->has_ring);
      ASSERT_EQ(scan->points.size() * 4, raw.size());
      for (std::size_t p = 0; p < scan->points.size(); ++p) {
        EXPECT_EQ(scan->points[p].x, raw[4 * p]);
        EXPECT_EQ(scan->points[p].z, raw[4 * p + 2]);
        EXPECT_EQ(scan->points[p].intensity, raw[4 * p + 3]);
        EXPECT_EQ(scan->points[p].t_offset_s, 0.0f);
      }
      EXPECT_EQ(scan->t_ns, (std::vector<TimeNs>{0, 103735900, 207338100}[scans]));
      ++scans;
    }
  }
  EXPECT_EQ(frames, 3u);
  EXPECT_EQ(scans, 3u);
  const auto& gt = reader->groundtruth();
  EXPECT_EQ(gt[1].t_ns, 103735900);
  EXPECT_EQ(gt[2].t_ns, 207338100);
  EXPECT_NEAR(gt[2].T_W_I.translation().z(), 1.716275, 1e-12);
}

TEST(KittiReader, PosesFileNextToTheSequenceWinsAndMustMatchTimes) {
  const KittiFolder k = make_kitti_folder(test::temp_dir());
  std::ofstream(k.seq / "poses.txt") << "1 0 0 0 0 1 0 0 0 0 1 0\n";
  try {
    open_dataset(k.seq.string());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (k.seq / "poses.txt").string());
  }
}

TEST(KittiReader, MissingScanIsSkippedAndListed) {
  const KittiFolder k = make_kitti_folder(test::temp_dir());
  fs::remove(k.seq / "velodyne" / "000001.bin");
  const auto reader = open_dataset(k.seq.string());
  EXPECT_EQ(reader->summary().lidar_scans, 2u);
  EXPECT_EQ(reader->summary().stereo_frames, 3u);
  ASSERT_FALSE(reader->summary().problems.empty());
  EXPECT_NE(reader->summary().problems[0].find("000001.bin"), std::string::npos);
}

TEST(KittiReader, RealSequence00PosesPassTheRotationCheck) {
  VILSLAM_REQUIRE_SHARED_DATA(poses, "trajectories/KITTI_00_gt.txt");
  VILSLAM_REQUIRE_SHARED_DATA(times, "trajectories/KITTI_00_gt_times.txt");
  const fs::path seq = test::temp_dir() / "00";
  fs::create_directories(seq);
  std::ofstream(seq / "calib.txt") << kCalib00;
  fs::copy_file(times, seq / "times.txt");
  fs::copy_file(poses, seq / "poses.txt");
  const auto reader = open_dataset(seq.string());
  ASSERT_EQ(reader->groundtruth().size(), 4541u);
  EXPECT_EQ(reader->summary().stereo_frames, 0u);
  EXPECT_EQ(reader->summary().end_t_ns, 470581600000);  // last line of the times file: 4.705816e+02
  EXPECT_NEAR(reader->groundtruth().back().T_W_I.translation().z(), 96.96153, 1e-12);
}

}  // namespace
}  // namespace vilslam
