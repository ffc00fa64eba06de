#pragma once
// Loop key frames straight from the simulator: a stereo pair rendered and a LiDAR sweep ray cast at one
// static body pose of a simulated world (a static sweep needs no dewarping), with the simulator's rig,
// the frontend's default settings and the shipped vocabulary.
#include <memory>
#include <string>

#include "frontend/camera_model.h"
#include "lidar/features.h"
#include "loop/key_frame.h"
#include "sim/camera_render.h"
#include "sim/lidar_sim.h"
#include "sim/sim_config.h"
#include "sim/trajectory.h"
#include "sim/world.h"

namespace vilslam::test {

inline std::string shipped_vocabulary_path() {
  return std::string(VILSLAM_SOURCE_DIR) + "/config/vocabulary/orb_k10_l4.voc";
}

struct SimLoopScene {
  SimLoopScene(sim::Scenario scenario, std::uint64_t seed)
      : world(sim::World::generate(scenario, seed)),
        calib(sim::rig_calibration(sim::SimConfig{})),
        rig(make_stereo_rig(calib)),
        motion(world.route_W(), sim::route_motion_config(sim::SimConfig{}, scenario)),
        vocabulary(std::make_shared<Vocabulary>(Vocabulary::load(shipped_vocabulary_path()))) {}

  sim::World world;
  RigCalibration calib;
  StereoRig rig;
  sim::RouteMotion motion;
  std::shared_ptr<const Vocabulary> vocabulary;
  sim::LidarSimConfig lidar;  // ideal returns unless a test sets a sensor's (sim::lidar_sensor)

  SE3 T_W_L(const SE3& T_W_I) const { return T_W_I * calib.T_I_L; }

  // The key frame of body pose T_W_I: images at t_ns, the sweep ending at t_ns. depth_left_m receives the
  // left image's rendered depth when given.
  loop::KeyFrame key_frame(const SE3& T_W_I, TimeNs t_ns, std::size_t pose_index, std::uint64_t noise_seed,
                           cv::Mat* depth_left_m = nullptr) const {
    sim::RenderOptions render;
    render.noise_seed = noise_seed;
    const auto fixed = [](const SE3& T) { return [T](TimeNs) { return T; }; };
    StereoFrame frame;
    frame.t_ns = t_ns;
    frame.left = sim::render_image(world, calib.cam0, fixed(T_W_I * calib.T_I_C0), t_ns, render, depth_left_m);
    render.noise_seed = noise_seed + 1;
    frame.right = sim::render_image(world, calib.cam1, fixed(T_W_I * calib.T_I_C1), t_ns, render);
    const TimeNs sweep_ns = static_cast<TimeNs>(1e9 / lidar.rate_hz);
    const LidarScan scan = sim::simulate_sweep(world, lidar, t_ns - sweep_ns, fixed(T_W_L(T_W_I)), noise_seed + 2);
    loop::KeyFrame k;
    k.pose_index = pose_index;
    k.scan_t_ns = t_ns;
    k.image = loop::make_key_image(frame, rig, FrontendConfig{}, *vocabulary);
    k.T_L_C0 = calib.T_I_L.inverse() * calib.T_I_C0;
    k.features_L = lidar::extract_features(scan, lidar::RingConfig{}, lidar::FeatureConfig{});
    return k;
  }
};

}  // namespace vilslam::test
