#pragma once
// A small synthetic dataset for the io tests: known values written with DatasetWriter.
#include <opencv2/core.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "common/calibration.h"
#include "io/dataset_writer.h"

namespace vilslam::test {

inline RigCalibration synthetic_calibration() {
  RigCalibration c;
  for (CameraIntrinsics* cam : {&c.cam0, &c.cam1}) {
    cam->width_px = 64;
    cam->height_px = 48;
    cam->fx = 50.5;
    cam->fy = 51.25;
    cam->cx = 31.7;
    cam->cy = 23.9;
    cam->distortion = DistortionModel::kRadTan;
    cam->distortion_coeffs = {-0.28, 0.07, 1.9e-4, -3.5e-5};
    cam->rate_hz = 20;
  }
  c.cam1.distortion = DistortionModel::kEquidistant;
  c.cam1.distortion_coeffs = {0.01, -0.002, 3e-4, -1e-5};
  c.T_I_C0 = SE3(so3::exp(Vec3(0.1, -1.5, 0.02)), Vec3(-0.02, -0.06, 0.01));
  c.T_I_C1 = c.T_I_C0 * SE3(so3::exp(Vec3(0.001, 0.002, -0.003)), Vec3(0.11, 0.001, -0.002));
  c.has_lidar = true;
  c.T_I_L = SE3(so3::exp(Vec3(0.0, 0.0, 3.1)), Vec3(0.05, 0.0, 0.12));
  c.lidar.num_rings = 16;
  c.lidar.rate_hz = 10;
  c.lidar.min_range_m = 0.4;
  c.lidar.max_range_m = 80;
  c.imu.gyro_noise_density = 1.7e-4;
  c.imu.rate_hz = 200;
  c.cam_time_offset_ns = -1234;
  c.lidar_time_offset_ns = 567;
  return c;
}

struct SyntheticData {
  RigCalibration calib = synthetic_calibration();
  std::vector<ImuSample> imu;
  std::vector<StereoFrame> stereo;
  std::vector<LidarScan> scans;
  std::vector<GroundTruthState> groundtruth;
  PointCloud model;
};

// 0.5 s at 200 Hz IMU, 20 Hz stereo, 10 Hz LiDAR, 100 Hz ground truth, starting at t0.
inline SyntheticData make_synthetic_data() {
  SyntheticData d;
  cv::RNG rng(7);
  const TimeNs t0 = 1'600'000'000'000'000'000;
  for (int i = 0; i < 100; ++i) {
    ImuSample s;
    s.t_ns = t0 + i * 5'000'000;
    s.gyro_rad_s = Vec3(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.1 / 3.0);
    s.accel_m_s2 = Vec3(rng.uniform(-1.0, 1.0), 9.80665, 1e-7 * i);
    d.imu.push_back(s);
  }
  for (int i = 0; i < 10; ++i) {
    StereoFrame f;
    f.t_ns = t0 + i * 50'000'000 + 1;
    f.left.create(48, 64, CV_8UC1);
    f.right.create(48, 64, CV_8UC1);
    rng.fill(f.left, cv::RNG::UNIFORM, 0, 256);
    rng.fill(f.right, cv::RNG::UNIFORM, 0, 256);
    d.stereo.push_back(f);
  }
  for (int i = 0; i < 5; ++i) {
    LidarScan scan;
    scan.t_ns = t0 + i * 100'000'000 + 2;
    scan.has_ring = i != 3;
    for (int k = 0; k < 50 + i; ++k) {
      LidarPoint p;
      p.x = static_cast<float>(rng.uniform(-50.0, 50.0));
      p.y = static_cast<float>(rng.uniform(-50.0, 50.0));
      p.z = static_cast<float>(rng.uniform(-2.0, 5.0));
      p.intensity = static_cast<float>(rng.uniform(0.0, 255.0));
      p.t_offset_s = 0.1f * static_cast<float>(k) / 60.0f;
      p.ring = static_cast<std::uint16_t>(k % 16);
      scan.points.push_back(p);
    }
    d.scans.push_back(scan);
  }
  for (int i = 0; i < 50; ++i) {
    GroundTruthState g;
    g.t_ns = t0 + i * 10'000'000 + 3;
    g.T_W_I = SE3(so3::exp(Vec3(0.01 * i, -0.3, 2.0)), Vec3(i * 0.1, -2.0, 1.0 / 3.0));
    g.v_W_m_s = Vec3(1.0, 0.5, -0.25 * i);
    g.bias_gyro_rad_s = Vec3(1e-3, -2e-3, 3e-3);
    g.bias_accel_m_s2 = Vec3(0.1, 0.2, -0.3);
    d.groundtruth.push_back(g);
  }
  for (int i = 0; i < 20; ++i) {
    d.model.points.emplace_back(static_cast<float>(i), 0.5f * static_cast<float>(i), -1.0f);
    d.model.intensity.push_back(static_cast<float>(i) * 2.0f);
  }
  return d;
}

inline void write_synthetic_dataset(const std::string& root, const SyntheticData& d) {
  DatasetWriter w(root, d.calib);
  for (const auto& s : d.imu) w.add_imu(s);
  for (const auto& f : d.stereo) w.add_stereo(f);
  for (const auto& s : d.scans) w.add_lidar(s);
  for (const auto& g : d.groundtruth) w.add_groundtruth(g);
  w.set_reference_model(d.model);
  w.finish();
}

}  // namespace vilslam::test
