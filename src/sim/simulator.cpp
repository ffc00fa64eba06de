#include "sim/simulator.h"

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include "common/error.h"
#include "common/json_writer.h"
#include "io/dataset_writer.h"
#include "io/euroc_tables.h"
#include "io/groundtruth_mounts.h"
#include "io/trajectory_io.h"
#include "sim/imu_alignment.h"
#include "sim/imu_stream_noise.h"
#include "sim/kitti_writer.h"
#include "sim/lidar_sim.h"
#include "sim/route.h"
#include "sim/scan_degeneracy.h"

namespace vilslam::sim {
namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

// SplitMix64 finalizer: independent, reproducible seeds for every frame, sweep and stream.
std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  std::uint64_t z = seed ^ (stream * 0x9E3779B97F4A7C15ULL) ^ (index * 0xBF58476D1CE4E5B9ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

struct FlownScene {
  World world;
  std::unique_ptr<BodyMotion> motion;
};

// A recorded ground truth cut to its first duration_s (0: whole), the room grown around what is flown.
FlownScene recorded_flight_scene(const SimConfig& config, const SimulateRequest& request) {
  Trajectory poses = read_trajectory(request.trajectory_path, TrajectoryFormat::kTum);
  if (request.duration_s > 0 && !poses.empty()) {
    const TimeNs end_ns = poses.front().t_ns + s_to_ns(request.duration_s);
    poses.erase(std::find_if(poses.begin(), poses.end(), [&](const TimedPose& p) { return p.t_ns > end_ns; }),
                poses.end());
  }
  if (poses.size() < 2)
    throw InputError(request.trajectory_path, "needs at least 2 poses" +
                                                  std::string(request.duration_s > 0 ? " within --duration" : ""));
  Eigen::AlignedBox3d flight_W;
  for (const TimedPose& pose : poses) flight_W.extend(pose.T_W_B.translation());
  FlownScene scene{World::generate(request.scenario, request.world_seed.value_or(request.seed), std::max(0.0, request.length_m),
                              flight_W),
              nullptr};
  scene.motion = std::make_unique<PoseSplineMotion>(poses, config.pose_spline);
  return scene;
}

constexpr double kMinRouteClearanceM = 0.3;  // a varied route's waypoints from any surface (the rig's size; in the message)

// A varied route (route.h) must keep clear of the world it was not built for.
void check_clearance(const World& world, const std::vector<Vec3>& route_W) {
  for (const Vec3& p_W : route_W) {
    if (world.distance_to_surface(p_W) < kMinRouteClearanceM) {
      throw InputError("--route-offset", "the shifted route passes within 0.3 m of a surface; choose a smaller offset");
    }
  }
}

// The world and the motion through it: a recorded ground truth, or the world's closed route flown at
// the configured speed (or at the speed that makes it last request.duration_s).
FlownScene make_scene(const SimConfig& config, const SimulateRequest& request) {
  if (!request.trajectory_path.empty()) return recorded_flight_scene(config, request);
  RouteMotionConfig motion_config = route_motion_config(config, request.scenario);
  motion_config.laps = request.laps;
  const double min_duration_s = motion_config.rest_start_s + motion_config.rest_end_s + motion_config.ramp_s;
  if (request.duration_s > 0 && request.duration_s <= min_duration_s)
    throw InputError("--duration", "must exceed the rests and speed ramps (" + std::to_string(min_duration_s) + " s)");
  double length_m = request.length_m;
  if (request.duration_s > 0 && length_m <= 0)
    length_m = motion_config.cruise_speed_m_s *
               (request.duration_s - motion_config.rest_start_s - motion_config.rest_end_s - motion_config.ramp_s);
  FlownScene scene{World::generate(request.scenario, request.world_seed.value_or(request.seed), std::max(0.0, length_m)),
              nullptr};
  const std::vector<Vec3> route_W = varied_route(scene.world.route_W(), request.route_start, request.route_offset_m);
  if (request.route_start != 0.0 || request.route_offset_m != 0.0) check_clearance(scene.world, route_W);
  if (request.duration_s > 0) {
    const RouteMotion probe(route_W, motion_config);
    motion_config.cruise_speed_m_s =
        RouteMotion::cruise_speed_for_duration(probe.length_m(), request.duration_s, motion_config);
  }
  scene.motion = std::make_unique<RouteMotion>(route_W, motion_config);
  return scene;
}

struct ImuStream {
  std::vector<ImuSample> samples;
  std::vector<GroundTruthState> groundtruth;
  TimeNs t0_ns = 0, t1_ns = 0;  // the sequence's time span
};

// Re-expresses a recorded motion as the pose of the real IMU (sim/imu_alignment.h) and logs the alignment.
void align_to_real_imu(FlownScene& scene, const std::vector<ImuSample>& samples) {
  const ImuAlignment a = align_imu_to_motion(*scene.motion, samples);
  const double body_deg = so3::log(a.R_B_I).norm() * 180.0 / kPi;
  const double tilt_deg = std::acos(std::clamp(-a.gravity_V_m_s2.normalized().z(), -1.0, 1.0)) * 180.0 / kPi;
  spdlog::info("real IMU vs ground truth: IMU axes {:.2f} deg from the body's{}, gravity {:.2f} deg from -z "
               "(|g| {:.3f} m/s^2), biases gyro [{:.4f} {:.4f} {:.4f}] rad/s accel [{:.3f} {:.3f} {:.3f}] m/s^2; "
               "RMS residual gyro {:.4f} -> {:.4f} rad/s, accel {:.3f} -> {:.3f} m/s^2",
               body_deg, a.rotation_estimated ? "" : " (not observable, kept)", tilt_deg, a.gravity_V_m_s2.norm(),
               a.gyro_bias_rad_s.x(), a.gyro_bias_rad_s.y(), a.gyro_bias_rad_s.z(), a.accel_bias_m_s2.x(),
               a.accel_bias_m_s2.y(), a.accel_bias_m_s2.z(), a.gyro_rms_identity_rad_s, a.gyro_rms_rad_s,
               a.accel_rms_identity_m_s2, a.accel_rms_m_s2);
  scene.motion = std::make_unique<ImuAlignedMotion>(std::move(scene.motion), a);
}

// The IMU and the ground truth at its timestamps: simulated, or a real stream restricted to the motion
// (which is then re-expressed as the real IMU's pose).
ImuStream make_imu(const SimConfig& config, const SimulateRequest& request, FlownScene& scene) {
  const BodyMotion& motion = *scene.motion;
  ImuStream out;
  // A preview of a route skips the initial rest: it starts at rest and sets off.
  TimeNs t0 = motion.start_ns(), t1 = motion.end_ns();
  if (request.preview) {
    if (request.trajectory_path.empty())
      t0 += s_to_ns(route_motion_config(config, request.scenario).rest_start_s);
    t1 = std::min(t1, t0 + s_to_ns(config.preview_duration_s));
  }
  if (request.imu_path.empty()) {
    ImuSimConfig imu = config.imu;
    imu.seed = mix_seed(request.seed, 3, 0);
    ImuSimulation sim = simulate_imu(motion, imu, t0, t1);
    const ImuNoise& sheet = config.imu.noise;
    const ImuNoise& truth = sim.errors.noise;
    spdlog::info("IMU against its data sheet (not in rig.yaml): noise x{:.2f} gyro, x{:.2f} accel, bias walks x{:.2f} "
                 "gyro, x{:.2f} accel; axis errors up to {:.2f} % scale, {:.2f} deg",
                 truth.gyro_noise_density / sheet.gyro_noise_density,
                 truth.accel_noise_density / sheet.accel_noise_density, truth.gyro_random_walk / sheet.gyro_random_walk,
                 truth.accel_random_walk / sheet.accel_random_walk, 100.0 * config.imu.errors.max_scale_error,
                 config.imu.errors.max_misalignment_deg);
    out.samples = std::move(sim.samples);
    out.groundtruth = std::move(sim.groundtruth);
  } else {
    std::vector<TimeNs> stamps;
    for (const ImuSample& s : read_imu_csv(request.imu_path)) {
      if (s.t_ns < t0 || s.t_ns > t1) continue;
      out.samples.push_back(s);
      stamps.push_back(s.t_ns);
    }
    if (stamps.size() < 10) throw InputError(request.imu_path, "fewer than 10 IMU samples within the trajectory's time range");
    align_to_real_imu(scene, out.samples);
    out.groundtruth = groundtruth_at(*scene.motion, stamps);
  }
  out.t0_ns = out.samples.front().t_ns;
  out.t1_ns = out.samples.back().t_ns;
  std::vector<ImuSample> kept;
  for (const ImuSample& s : out.samples)
    if (!in_fault(config.faults.imu_gaps, s.t_ns - out.t0_ns)) kept.push_back(s);
  out.samples = std::move(kept);
  return out;
}

// Stereo frames at the camera rate over [t0, t1], rendered in parallel batches and written in order.
void write_frames(const SimConfig& config, const SimulateRequest& request, const FlownScene& scene, const SensorMounts& mounts, const ImuStream& imu, DatasetWriter& writer, SequenceReport& report,
                  const std::function<void(double)>& progress) {
  const TimeNs period_ns = s_to_ns(1.0 / config.camera.rate_hz);
  const std::size_t count = static_cast<std::size_t>((imu.t1_ns - imu.t0_ns) / period_ns) + 1;
  const TimeNs offset_ns = mounts.camera_offset_ns;
  const SE3 T_I_C[2] = {mounts.T_I_C0, mounts.T_I_C1};
  const CameraIntrinsics* cams[2] = {&mounts.cam0, &mounts.cam1};  // the true lenses, not the written ones
  double corner_sum = 0;
  for (std::size_t first = 0; first < count; first += config.parallel_batch) {
    const std::size_t n = std::min<std::size_t>(config.parallel_batch, count - first);
    std::vector<StereoFrame> frames(n);
    std::vector<int> corners(n, 0);
    tbb::parallel_for(std::size_t(0), 2 * n, [&](std::size_t job) {
      const std::size_t k = first + job / 2;
      const int cam = static_cast<int>(job % 2);
      const TimeNs t_ns = imu.t0_ns + static_cast<TimeNs>(k) * period_ns;
      cv::Mat image;
      if (in_fault(config.faults.camera_blackouts, t_ns - imu.t0_ns)) {
        image = cv::Mat::zeros(cams[cam]->height_px, cams[cam]->width_px, CV_8UC1);
      } else {
        RenderOptions options = config.render;
        options.noise_seed = mix_seed(request.seed, 1 + cam, k);
        options.exposure_gain =
            1.0 + config.exposure_variation * std::sin(2 * kPi * ns_to_s(t_ns - imu.t0_ns) / config.exposure_period_s);
        if (in_fault(config.faults.exposure_jumps, t_ns - imu.t0_ns)) options.exposure_gain *= config.faults.exposure_jump_gain;
        const auto T_W_C = [&](TimeNs t) { return scene.motion->pose(t) * T_I_C[cam]; };
        image = render_image(scene.world, *cams[cam], T_W_C, t_ns, options);
      }
      StereoFrame& frame = frames[job / 2];
      if (cam == 1) {
        frame.right = image;
        return;
      }
      frame.t_ns = t_ns + offset_ns;
      frame.left = image;
      if (request.report) corners[job / 2] = count_corners(image);
    });
    for (std::size_t i = 0; i < n; ++i) {
      writer.add_stereo(frames[i]);
      corner_sum += corners[i];
    }
    progress(double(first + n) / count);
  }
  report.stereo_frames = count;
  report.mean_corners_per_frame = count > 0 ? corner_sum / count : 0;
}

// Sweeps whose whole period lies in [t0, t1], simulated in parallel batches, written in order to the
// dataset and to the KITTI copy.
void write_scans(const SimConfig& config, const SimulateRequest& request, const FlownScene& scene,
                 const SensorMounts& mounts, const ImuStream& imu, DatasetWriter& writer, KittiWriter& kitti,
                 SequenceReport& report, const std::function<void(double)>& progress) {
  const TimeNs period_ns = s_to_ns(1.0 / config.lidar.rate_hz);
  const std::size_t count = imu.t1_ns - imu.t0_ns >= period_ns
                                ? static_cast<std::size_t>((imu.t1_ns - imu.t0_ns - period_ns) / period_ns) + 1
                                : 0;
  const TimeNs offset_ns = mounts.lidar_offset_ns;
  const auto T_W_L = [&](TimeNs t) { return scene.motion->pose(t) * mounts.T_I_L; };
  double ratio_sum = 0;
  for (std::size_t first = 0; first < count; first += config.parallel_batch) {
    const std::size_t n = std::min<std::size_t>(config.parallel_batch, count - first);
    std::vector<LidarScan> scans(n);
    std::vector<char> dropped(n, 0);
    std::vector<double> ratios(n, 0.0);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
      const TimeNs t_ns = imu.t0_ns + static_cast<TimeNs>(first + i) * period_ns;
      dropped[i] = in_fault(config.faults.lidar_dropouts, t_ns - imu.t0_ns);
      if (dropped[i]) return;
      scans[i] = simulate_sweep(scene.world, config.lidar, t_ns, T_W_L, mix_seed(request.seed, 4, first + i));
      if (request.report) ratios[i] = analyze_scan_degeneracy(scene.world, config.lidar, T_W_L(t_ns)).min_max_ratio;
    });
    for (std::size_t i = 0; i < n; ++i) {
      if (dropped[i]) continue;
      ratio_sum += ratios[i];
      const SE3 pose = T_W_L(scans[i].t_ns);
      scans[i].t_ns += offset_ns;
      writer.add_lidar(scans[i]);
      kitti.add_scan(scans[i], pose);
      ++report.lidar_scans;
    }
    progress(double(first + n) / count);
  }
  report.mean_lidar_information_ratio = report.lidar_scans > 0 ? ratio_sum / report.lidar_scans : 0;
}

// A TUM copy of the ground truth for trajectory tools, written next to the temporary KITTI folder.
void write_tum_copy(const std::vector<GroundTruthState>& states, const fs::path& path) {
  Trajectory poses;
  poses.reserve(states.size());
  for (const GroundTruthState& g : states) poses.push_back({g.t_ns, g.T_W_I});
  write_trajectory(path.string(), poses, TrajectoryFormat::kTum);
}

}  // namespace

SequenceReport simulate(const SimConfig& configured, const SimulateRequest& request) {
  const SimConfig config = configured.sensor_realism ? configured : ideal_sensors(configured);
  FlownScene scene = make_scene(config, request);
  RigCalibration calib = rig_calibration(config);
  // The sensors render and scan from their true mounts; the calibration written is the nominal one.
  const SensorMounts mounts = true_mounts(calib, config.calibration_errors, mix_seed(request.seed, 5, 0));
  const ImuStream imu = make_imu(config, request, scene);
  if (!request.imu_path.empty()) {
    // The estimator's calibration comes from the config and the written IMU stream, never the ground truth.
    calib.imu = noise_from_stream(imu.samples, calib.imu);
    spdlog::info("real IMU noise written to rig.yaml (Allan deviation at the sample interval): gyro {:.3g} "
                 "rad/s/sqrt(Hz), accel {:.3g} m/s^2/sqrt(Hz)",
                 calib.imu.gyro_noise_density, calib.imu.accel_noise_density);
  }

  SequenceReport report;
  report.scenario = scenario_name(request.scenario);
  report.duration_s = ns_to_s(imu.t1_ns - imu.t0_ns);
  report.length_m = path_length_m(imu.groundtruth);

  // The KITTI copy and the TUM ground truth are written inside the dataset's staging folder, so the
  // writer's one rename publishes them with it (a killed run leaves no dataset without them).
  DatasetWriter writer(request.out_dir, calib, request.overwrite);
  const fs::path staging = writer.staging_path();
  KittiWriter kitti((staging / "kitti").string(), calib);

  for (const ImuSample& s : imu.samples) writer.add_imu(s);
  for (const GroundTruthState& g : imu.groundtruth) writer.add_groundtruth(g);
  report.imu_samples = imu.samples.size();
  report.groundtruth_states = imu.groundtruth.size();
  spdlog::info("simulate {}: {:.1f} m in {:.1f} s, {} IMU samples", report.scenario, report.length_m, report.duration_s,
           report.imu_samples);

  // Progress: images, then sweeps, each weighted by its share of the sensor rates.
  const double image_share = config.camera.rate_hz / (config.camera.rate_hz + config.lidar.rate_hz);
  const auto stage_progress = [&request](double offset, double share) {
    return std::function<void(double)>([&request, offset, share](double fraction) {
      if (request.progress) request.progress(offset + share * fraction);
    });
  };
  write_frames(config, request, scene, mounts, imu, writer, report, stage_progress(0.0, image_share));
  write_scans(config, request, scene, mounts, imu, writer, kitti, report, stage_progress(image_share, 1.0 - image_share));
  kitti.finish();
  write_tum_copy(imu.groundtruth, staging / "groundtruth.tum");
  if (config.sensor_realism) {
    write_file_atomic((staging / kGroundTruthMountsFile).string(),
                      groundtruth_mounts_yaml({mounts.T_I_C0, mounts.T_I_C1, mounts.T_I_L}));
  }
  const double spacing_m = request.preview ? std::max(config.model_spacing_m, 0.2) : config.model_spacing_m;
  writer.set_reference_model(scene.world.sample_surfaces(spacing_m));
  writer.finish();
  return report;
}

}  // namespace vilslam::sim
