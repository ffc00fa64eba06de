// vilslam_ros_node: the live system on a ROS1 robot, a thin wrapper over vilslam::System (docs/pipeline.md,
// "The ROS1 node"). It subscribes to the rig's streams, pushes them through LiveInput (stereo pairing, each
// stream in time order) into the System in real-time mode (the overload policy on), and publishes each
// output the moment its module produces it. When LiDAR mapping is lost (vil with loop closure) it resets the whole
// state as `vilslam run` does and the new System re-localizes in the map of the one before (docs/pipeline.md,
// "Resets after a lost map"). On shutdown (Ctrl-C) it finishes the run and, with --out, writes the outputs
// `vilslam run` writes.
//
//   vilslam_ros_node --rig RIG.yaml [--config RUN.yaml] [--mode vil|vio|lidar-only] [--out DIR]
//                    [imu0:=/imu/data cam0:=/left/image_raw cam1:=/right/image_raw lidar0:=/velodyne_points]
//
// Subscribed (relative names, remap them): imu0 (sensor_msgs/Imu), cam0 and cam1 (sensor_msgs/Image mono8,
// rgb8 or bgr8, or CompressedImage), lidar0 (sensor_msgs/PointCloud2: Velodyne, Ouster, Hesai or Livox layout).
// Published (in the node's namespace, ~): odometry (nav_msgs/Odometry of I in W at the IMU rate), camera_state
// (nav_msgs/Odometry of each optimized stereo-frame state), lidar_pose (geometry_msgs/PoseStamped of L in W,
// the mapper's), path (nav_msgs/Path of the loop-corrected LiDAR poses), sparse_map (sensor_msgs/PointCloud2
// of each mapped sweep's edge and planar features in W), and /tf (world -> imu at the IMU rate).
#include <CLI/CLI.hpp>
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_msgs/TFMessage.h>
#include <topic_tools/shape_shifter.h>

#include <atomic>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/error.h"
#include "io/calibration_io.h"
#include "io/ros_convert.h"
#include "io/ros_wire.h"
#include "pipeline/live_input.h"
#include "pipeline/run_config.h"
#include "pipeline/run_outputs.h"
#include "pipeline/run_segments.h"
#include "pipeline/system.h"

namespace vilslam {
namespace {

constexpr const char* kWorldFrame = "world";
constexpr const char* kImuFrame = "imu";

ros::Time stamp(TimeNs t_ns) { return ros::Time().fromNSec(static_cast<std::uint64_t>(t_ns)); }

geometry_msgs::Pose pose_msg(const SE3& T) {
  geometry_msgs::Pose p;
  p.position.x = T.translation().x();
  p.position.y = T.translation().y();
  p.position.z = T.translation().z();
  const Quat q = T.quat();
  p.orientation.x = q.x();
  p.orientation.y = q.y();
  p.orientation.z = q.z();
  p.orientation.w = q.w();
  return p;
}

nav_msgs::Odometry odometry_msg(const TimedPose& pose) {
  nav_msgs::Odometry m;
  m.header.stamp = stamp(pose.t_ns);
  m.header.frame_id = kWorldFrame;
  m.child_frame_id = kImuFrame;
  m.pose.pose = pose_msg(pose.T_W_B);
  return m;
}

// The odometry's pose as the TF of its child frame.
tf2_msgs::TFMessage tf_msg(const nav_msgs::Odometry& odometry) {
  geometry_msgs::TransformStamped t;
  t.header = odometry.header;
  t.child_frame_id = odometry.child_frame_id;
  const geometry_msgs::Point& position = odometry.pose.pose.position;
  t.transform.translation.x = position.x;
  t.transform.translation.y = position.y;
  t.transform.translation.z = position.z;
  t.transform.rotation = odometry.pose.pose.orientation;
  tf2_msgs::TFMessage tf;
  tf.transforms.push_back(t);
  return tf;
}

geometry_msgs::PoseStamped pose_stamped_msg(TimeNs t_ns, const SE3& T) {
  geometry_msgs::PoseStamped m;
  m.header.stamp = stamp(t_ns);
  m.header.frame_id = kWorldFrame;
  m.pose = pose_msg(T);
  return m;
}

// A message's wire bytes, for the decoders the bag reader uses (io/ros_messages.h).
std::vector<std::uint8_t> wire_bytes(const topic_tools::ShapeShifter& message) {
  std::vector<std::uint8_t> bytes(message.size());
  ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  message.write(stream);
  return bytes;
}

class Node {
 public:
  Node(ros::NodeHandle& nh, ros::NodeHandle& private_nh, const RigCalibration& calib, const OfflineRunConfig& config,
       int image_bits)
      : image_bits_(image_bits),
        odometry_(private_nh.advertise<nav_msgs::Odometry>("odometry", 400)),
        camera_state_(private_nh.advertise<nav_msgs::Odometry>("camera_state", 20)),
        lidar_pose_(private_nh.advertise<geometry_msgs::PoseStamped>("lidar_pose", 20)),
        path_pub_(private_nh.advertise<nav_msgs::Path>("path", 2)),
        sparse_map_(private_nh.advertise<sensor_msgs::PointCloud2>("sparse_map", 4)),
        tf_(nh.advertise<tf2_msgs::TFMessage>("/tf", 400)),
        calib_(calib), config_(config),
        reset_on_lost_(resets_on_lidar_lost(config)),
        system_(std::make_unique<System>(calib, config, callbacks())),
        input_(LiveInputConfig{}, LiveInputSink{[this](const ImuSample& s) {
                                                  system_->push_imu(s);
                                                  pushed(s.t_ns);
                                                },
                                                [this](StereoFrame f) {
                                                  const TimeNs t_ns = f.t_ns;
                                                  system_->push_stereo(std::move(f));
                                                  pushed(t_ns);
                                                },
                                                [this](LidarScan s) {
                                                  const TimeNs t_ns = s.t_ns;
                                                  system_->push_scan(std::move(s));
                                                  pushed(t_ns);
                                                }}) {
    path_.header.frame_id = kWorldFrame;
    const bool with_vio = config.mode != RunMode::kLidarOnly;
    if (with_vio) {
      subscriptions_.push_back(nh.subscribe<topic_tools::ShapeShifter>("imu0", 2000, &Node::imu, this));
      subscriptions_.push_back(nh.subscribe<topic_tools::ShapeShifter>(
          "cam0", 10, [this](const topic_tools::ShapeShifter::ConstPtr& m) { image(0, *m); }));
      subscriptions_.push_back(nh.subscribe<topic_tools::ShapeShifter>(
          "cam1", 10, [this](const topic_tools::ShapeShifter::ConstPtr& m) { image(1, *m); }));
    }
    if (config.mode != RunMode::kVio) {
      subscriptions_.push_back(nh.subscribe<topic_tools::ShapeShifter>("lidar0", 4, &Node::scan, this));
    }
  }

  // After ros::spin: roscpp is shutting down, so what the modules still produce is kept for --out, not published.
  OfflineRunResult finish() {
    subscriptions_.clear();
    publishing_ = false;
    return segments_ ? segments_->finish(finish_system()) : finish_system();
  }
  void print_summary(const OfflineRunResult& result) const {
    const LiveInputDrops& d = input_.drops();
    std::printf("vilslam node: %zu stereo frame states, %zu sweeps mapped; dropped by the overload policy %zu frames, "
                "%zu sweeps; out of order %zu IMU samples, %zu frames, %zu sweeps; unpaired images %zu; bad messages "
                "%zu\n",
                result.camera_states.size(), result.lidar.size(), dropped_frames_, dropped_sweeps_,
                d.imu_out_of_order, d.frames_out_of_order, d.scans_out_of_order, d.unpaired_images, bad_messages_);
  }

 private:
  // After each push (the spinner's thread): a LiDAR mapping lost resets the whole state at the pushed stamp.
  void pushed(TimeNs t_ns) {
    if (!segments_) segments_.emplace(calib_, config_, t_ns);
    if (!reset_on_lost_ || !system_->lidar_lost()) return;
    const loop::SavedMap& map = segments_->reset(finish_system(), t_ns);
    system_ = std::make_unique<System>(calib_, segments_->restart_config(), callbacks(), map);
    ROS_WARN("vilslam: LiDAR mapping was lost; the whole state was reset and re-localizes in the map so far");
  }

  // The current System's outputs, its drops counted with the earlier ones'.
  OfflineRunResult finish_system() {
    dropped_frames_ += system_->dropped_frames();
    dropped_sweeps_ += system_->dropped_sweeps();
    return system_->finish();
  }

  SystemCallbacks callbacks() {
    SystemCallbacks cb;
    cb.imu_pose = [this](const TimedPose& p) {
      if (!publishing_) return;
      const nav_msgs::Odometry m = odometry_msg(p);
      odometry_.publish(m);
      tf_.publish(tf_msg(m));
    };
    cb.camera_state = [this](const TimedPose& p) {
      if (publishing_) camera_state_.publish(odometry_msg(p));
    };
    cb.lidar_pose = [this](const lidar::LidarMappingResult& r) {
      if (publishing_) lidar_pose_.publish(pose_stamped_msg(r.t_ns, r.T_W_L));
    };
    cb.lidar_global_pose = [this](const TimedPose& p) {
      if (!publishing_) return;
      path_.poses.push_back(pose_stamped_msg(p.t_ns, p.T_W_B));
      path_.header.stamp = stamp(p.t_ns);
      path_pub_.publish(path_);
    };
    cb.lidar_features = [this](const TimedPose& T_W_L, const lidar::FeatureScan& features) {
      if (publishing_) sparse_map_.publish(features_msg(T_W_L, features));
    };
    return cb;
  }

  static sensor_msgs::PointCloud2 features_msg(const TimedPose& T_W_L, const lidar::FeatureScan& features) {
    sensor_msgs::PointCloud2 cloud;
    cloud.header.stamp = stamp(T_W_L.t_ns);
    cloud.header.frame_id = kWorldFrame;
    sensor_msgs::PointCloud2Modifier modifier(cloud);
    modifier.setPointCloud2FieldsByString(1, "xyz");
    modifier.resize(features.edges.size() + features.surfaces.size());
    sensor_msgs::PointCloud2Iterator<float> x(cloud, "x"), y(cloud, "y"), z(cloud, "z");
    for (const auto* points : {&features.edges, &features.surfaces}) {
      for (const lidar::FeaturePoint& p : *points) {
        const Vec3 p_W = T_W_L.T_W_B * p.p_L;
        *x = static_cast<float>(p_W.x());
        *y = static_cast<float>(p_W.y());
        *z = static_cast<float>(p_W.z());
        ++x, ++y, ++z;
      }
    }
    return cloud;
  }

  // A message that cannot be used is reported (throttled) and skipped; the node keeps running.
  template <class F>
  void guarded(const std::string& topic, F&& convert_and_push) {
    try {
      convert_and_push();
    } catch (const std::exception& e) {
      ++bad_messages_;
      ROS_ERROR_THROTTLE(1.0, "vilslam: skipping a message on %s: %s", topic.c_str(), e.what());
    }
  }

  void imu(const topic_tools::ShapeShifter::ConstPtr& m) {
    guarded("imu0", [&] { input_.imu(imu_sample_from_ros(decode_ros_imu(wire_bytes(*m)))); });
  }

  void image(int camera, const topic_tools::ShapeShifter& m) {
    guarded(camera == 0 ? "cam0" : "cam1", [&] {
      const std::vector<std::uint8_t> bytes = wire_bytes(m);
      if (m.getDataType() == kRosCompressedImage.datatype) {
        const RosCompressedImage image = decode_ros_compressed_image(bytes);
        input_.image(camera, image.header.stamp_ns, grey_from_ros_compressed_image(image));
      } else {
        const RosImage image = decode_ros_image(bytes);
        input_.image(camera, image.header.stamp_ns, grey_from_ros_image(image, image_bits_));
      }
    });
  }

  void scan(const topic_tools::ShapeShifter::ConstPtr& m) {
    guarded("lidar0", [&] { input_.scan(scan_from_point_cloud2(decode_ros_point_cloud2(wire_bytes(*m)))); });
  }

  int image_bits_;  // significant bits of 16-bit images (--image-bits)
  ros::Publisher odometry_, camera_state_, lidar_pose_, path_pub_, sparse_map_, tf_;
  nav_msgs::Path path_;  // the LiDAR thread's only
  std::atomic<bool> publishing_{true};
  RigCalibration calib_;
  OfflineRunConfig config_;
  bool reset_on_lost_;
  std::optional<RunSegments> segments_;  // from the first push on
  std::unique_ptr<System> system_;
  std::size_t dropped_frames_ = 0, dropped_sweeps_ = 0;  // by the Systems finished so far
  LiveInput input_;  // the spinner's thread only
  std::vector<ros::Subscriber> subscriptions_;
  std::size_t bad_messages_ = 0;
};

int run(int argc, char** argv) {
  ros::init(argc, argv, "vilslam");  // takes the remappings (name:=topic) out of argv
  CLI::App app("vilslam's live ROS1 node (docs/pipeline.md, \"The ROS1 node\")");
  std::string rig_path, config_path, mode = "vil", out_dir;
  app.add_option("--rig", rig_path, "Rig calibration YAML (docs/formats.md; `export-bag` writes one beside its bag)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--config", config_path, "Run YAML (config/run_default.yaml); default: built-in")->check(CLI::ExistingFile);
  app.add_option("--mode", mode, "Pipeline mode")->check(CLI::IsMember({"vio", "vil", "lidar-only"}))->capture_default_str();
  app.add_option("--out", out_dir, "On shutdown, write the run's outputs here as `vilslam run` does");
  int image_bits = 16;
  app.add_option("--image-bits", image_bits,
                 "Significant bits of 16-bit images (mono16, 16UC1, bayer_*16): 2^bits - 1 becomes white")
      ->check(CLI::Range(8, 16))
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    OfflineRunConfig config = config_path.empty() ? OfflineRunConfig{} : load_run_config(config_path);
    config.mode = parse_run_mode(mode);
    config.realtime.speed = 1.0;  // live: the overload policy of pipeline/realtime.h
    ros::NodeHandle nh, private_nh("~");
    if (config.time_offset.enabled) {  // estimated from a recording before the run starts: not possible live
      ROS_WARN("vilslam: time_offset.enabled is for recorded runs; live, the rig's cam_time_offset_ns is used");
      config.time_offset.enabled = false;
    }
    Node node(nh, private_nh, read_rig_yaml(rig_path), config, image_bits);
    ROS_INFO("vilslam: running (mode %s)", mode.c_str());
    ros::spin();  // until Ctrl-C or rosnode kill
    const OfflineRunResult result = node.finish();
    node.print_summary(result);
    if (!out_dir.empty()) {
      write_run_outputs(out_dir, config, result);
      std::printf("wrote %s\n", out_dir.c_str());
    }
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}

}  // namespace
}  // namespace vilslam

int main(int argc, char** argv) { return vilslam::run(argc, argv); }
