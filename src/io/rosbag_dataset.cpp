// A ROS1 bag as a dataset (docs/formats.md, "ROS1 bags"): IMU and ground truth are decoded up front,
// images and sweeps are indexed (header stamp, message ordinal) and decoded when the reader returns them.
// Times are the messages' header stamps; each stream's stamps must increase strictly.
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>

#include "common/error.h"
#include "io/calibration_io.h"
#include "io/dataset_index.h"
#include "io/euroc_tables.h"
#include "io/kalibr_calibration.h"
#include "io/ros_convert.h"
#include "io/ros_wire.h"
#include "io/message_log.h"
#include "io/ros2_messages.h"
#include "io/rosbag_topics.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

// The decoders of a log's serialization.
struct Decoders {
  RosImage (*image)(const std::vector<std::uint8_t>&);
  RosCompressedImage (*compressed_image)(const std::vector<std::uint8_t>&);
  RosImu (*imu)(const std::vector<std::uint8_t>&);
  RosPointCloud2 (*point_cloud2)(const std::vector<std::uint8_t>&);
  RosPoseStamped (*pose_stamped)(const std::vector<std::uint8_t>&);
};

const Decoders& decoders_of(const MessageLog& log) {
  static const Decoders ros1{decode_ros_image, decode_ros_compressed_image, decode_ros_imu, decode_ros_point_cloud2,
                             decode_ros_pose_stamped};
  static const Decoders cdr{decode_cdr_image, decode_cdr_compressed_image, decode_cdr_imu, decode_cdr_point_cloud2,
                            decode_cdr_pose_stamped};
  return log.wire() == BagWire::kCdr ? cdr : ros1;
}

// Runs f, turning a WireError about one message into an InputError naming the bag, topic and message.
template <typename F>
auto about_message(const std::string& bag, const std::string& topic, std::size_t ordinal, F f) {
  try {
    return f();
  } catch (const WireError& e) {
    throw InputError(bag, "topic " + topic + ", message " + std::to_string(ordinal) + ": " + e.what());
  }
}

void require_increasing(const std::string& bag, const std::string& topic, TimeNs previous, TimeNs t_ns,
                        std::size_t ordinal) {
  if (ordinal > 0 && t_ns <= previous) {
    throw InputError(bag, "topic " + topic + ", message " + std::to_string(ordinal) + ": header stamp " +
                              std::to_string(t_ns) + " ns not after the previous one's " + std::to_string(previous));
  }
}

std::string datatype_of(const MessageLog& bag, const std::string& topic) {
  for (const BagTopic& t : bag.topics()) {
    if (t.topic == topic) return t.datatype;
  }
  return {};
}

// The md5 of a topic's connection must be the one of the type vilslam decodes.
void require_md5(const MessageLog& bag, const std::string& topic, const RosMessageType& type) {
  for (const BagTopic& t : bag.topics()) {
    if (t.topic == topic && t.md5sum != type.md5sum && t.md5sum != "*") {
      throw InputError(bag.path(), "topic " + topic + ": " + t.datatype + " with definition MD5 " + t.md5sum +
                                       ", expected " + type.md5sum + " (another version of the message)");
    }
  }
}

const RosMessageType& image_type_of(const MessageLog& bag, const std::string& topic) {
  return datatype_of(bag, topic) == kRosImage.datatype ? kRosImage : kRosCompressedImage;
}

void check_image_size(const std::string& bag, const std::string& topic, int width, int height,
                      const CameraIntrinsics& cam) {
  if (width != cam.width_px || height != cam.height_px) {
    throw InputError(bag, "topic " + topic + ": image is " + std::to_string(width) + "x" + std::to_string(height) +
                              ", the calibration says " + std::to_string(cam.width_px) + "x" + std::to_string(cam.height_px));
  }
}

class BagPayloads : public PayloadStore {
 public:
  BagPayloads(std::unique_ptr<MessageLog> bag, BagTopics topics, RigCalibration calib)
      : bag_(std::move(bag)), topics_(std::move(topics)), calib_(std::move(calib)) {}

  StereoFrame stereo(std::size_t i) override {
    StereoFrame frame;
    frame.t_ns = stereo_ordinals[i].t_ns;
    frame.left = image(topics_.cam0, stereo_ordinals[i].left, calib_.cam0, left_bits);
    frame.right = image(topics_.cam1, stereo_ordinals[i].right, calib_.cam1, right_bits);
    return frame;
  }

  LidarScan scan(std::size_t i) override {
    const std::size_t ordinal = scan_ordinals[i];
    const auto bytes = bag_->message(topics_.lidar0, ordinal);
    return about_message(bag_->path(), topics_.lidar0, ordinal,
                         [&] { return scan_from_point_cloud2(decoders_of(*bag_).point_cloud2(bytes)); });
  }

  MessageLog& bag() { return *bag_; }

  // Entry i of the index's stereo (scans) list: the message ordinals on the cam0 and cam1 (lidar0) topics.
  struct StereoOrdinals {
    TimeNs t_ns;
    std::size_t left, right;
  };
  std::vector<StereoOrdinals> stereo_ordinals;
  std::vector<std::size_t> scan_ordinals;
  // Significant bits of each camera topic's 16-bit images (scale_bits of ImageTopicInfo).
  int left_bits = 16, right_bits = 16;

 private:
  cv::Mat image(const std::string& topic, std::size_t ordinal, const CameraIntrinsics& cam, int bits) {
    const auto bytes = bag_->message(topic, ordinal);
    const bool raw = datatype_of(*bag_, topic) == kRosImage.datatype;
    const cv::Mat grey = about_message(bag_->path(), topic, ordinal, [&] {
      return raw ? grey_from_ros_image(decoders_of(*bag_).image(bytes), bits)
                 : grey_from_ros_compressed_image(decoders_of(*bag_).compressed_image(bytes));
    });
    check_image_size(bag_->path(), topic, grey.cols, grey.rows, cam);
    return grey;
  }

  std::unique_ptr<MessageLog> bag_;
  BagTopics topics_;
  RigCalibration calib_;
};

// run1.bag, run1.db3 and the ROS 2 bag folder run1/ -> run1.rig.yaml beside them.
std::string default_calibration_path(const std::string& bag_path) {
  fs::path p = fs::path(bag_path).lexically_normal();
  if (p.filename().empty()) p = p.parent_path();
  return p.replace_extension(".rig.yaml").string();
}

// The calibration file's topics under the options' topics: a rig YAML's optional `ros_topics` map (role:
// topic), or the `rostopic` keys of Kalibr's files.
std::map<std::string, std::string> topic_choices(const std::string& calib_path, const KalibrFiles* kalibr,
                                                 const DatasetOptions& options) {
  std::map<std::string, std::string> topics = options.topics;
  if (kalibr) {
    for (const auto& [role, topic] : kalibr_topics(*kalibr)) topics.emplace(role, topic);  // an option given wins
    return topics;
  }
  const YAML::Node node = YAML::LoadFile(calib_path)["ros_topics"];
  if (!node) return topics;
  if (!node.IsMap()) throw InputError(calib_path, "ros_topics must be a map of role: topic");
  for (const auto& entry : node) {
    if (!entry.second.IsScalar()) throw InputError(calib_path, "ros_topics: " + entry.first.Scalar() + " is not a topic name");
    topics.emplace(entry.first.Scalar(), entry.second.Scalar());  // an option given wins
  }
  return topics;
}

std::vector<ImuSample> read_imu(const MessageLog& bag, const std::string& topic) {
  require_md5(bag, topic, kRosImu);
  std::vector<ImuSample> imu;
  bag.for_each(topic, [&](std::size_t k, const std::vector<std::uint8_t>& bytes) {
    const ImuSample s = about_message(bag.path(), topic, k, [&] { return imu_sample_from_ros(decoders_of(bag).imu(bytes)); });
    require_increasing(bag.path(), topic, imu.empty() ? 0 : imu.back().t_ns, s.t_ns, k);
    imu.push_back(s);
  });
  return imu;
}

std::vector<GroundTruthState> read_poses(const MessageLog& bag, const std::string& topic) {
  require_md5(bag, topic, kRosPoseStamped);
  std::vector<GroundTruthState> gt;
  bag.for_each(topic, [&](std::size_t k, const std::vector<std::uint8_t>& bytes) {
    const RosPoseStamped m = about_message(bag.path(), topic, k, [&] { return decoders_of(bag).pose_stamped(bytes); });
    const auto& q = m.orientation_xyzw;
    const Quat quat(q[3], q[0], q[1], q[2]);
    if (!(quat.norm() > 0.5 && quat.norm() < 2)) {
      throw InputError(bag.path(), "topic " + topic + ", message " + std::to_string(k) + ": not a unit quaternion");
    }
    GroundTruthState s;
    s.t_ns = m.header.stamp_ns;
    s.T_W_I = SE3(quat.normalized(), Vec3(m.position[0], m.position[1], m.position[2]));
    require_increasing(bag.path(), topic, gt.empty() ? 0 : gt.back().t_ns, s.t_ns, k);
    gt.push_back(s);
  });
  return gt;
}

// What indexing learnt of a raw image topic: the first message's encoding and, for 16-bit images, the
// significant bits of the whole topic (one scale for every frame, so brightness does not flicker).
struct ImageTopicInfo {
  std::string encoding;  // empty for compressed images
  int bits = 0;          // 0: no 16-bit image
  // What `info` lists after the type: "mono8", or "mono16/12" for 16-bit images scaled from 12 bits.
  std::string listed() const { return bits > 0 ? " " + encoding + "/" + std::to_string(bits) : encoding.empty() ? "" : " " + encoding; }
  int scale_bits() const { return bits > 0 ? bits : 16; }
};

// Header stamps of an image topic (raw images are checked for encoding and size here).
std::vector<ImageRow> index_images(const MessageLog& bag, const std::string& topic, const CameraIntrinsics& cam,
                                   std::map<TimeNs, std::size_t>& ordinal_of, ImageTopicInfo& info) {
  const RosMessageType& type = image_type_of(bag, topic);
  require_md5(bag, topic, type);
  std::vector<ImageRow> rows;
  bag.for_each(topic, [&](std::size_t k, const std::vector<std::uint8_t>& bytes) {
    const TimeNs t_ns = about_message(bag.path(), topic, k, [&] {
      if (&type == &kRosCompressedImage) return decoders_of(bag).compressed_image(bytes).header.stamp_ns;
      const RosImage image = decoders_of(bag).image(bytes);
      check_ros_image(image);
      check_image_size(bag.path(), topic, static_cast<int>(image.width), static_cast<int>(image.height), cam);
      if (k == 0) info.encoding = image.encoding;
      info.bits = std::max(info.bits, ros_image_significant_bits(image));
      return image.header.stamp_ns;
    });
    require_increasing(bag.path(), topic, rows.empty() ? 0 : rows.back().t_ns, t_ns, k);
    rows.push_back({t_ns, bag.path() + ":" + topic + "@" + std::to_string(t_ns)});
    ordinal_of[t_ns] = k;
  });
  return rows;
}

}  // namespace

DatasetIndex index_rosbag(const std::string& bag_path, const DatasetOptions& options) {
  DatasetIndex index;
  index.summary.format = is_ros2_bag(bag_path) ? "rosbag2" : "rosbag";
  index.summary.path = bag_path;
  const std::string calib_path =
      options.calibration_path.empty() ? default_calibration_path(bag_path) : options.calibration_path;
  if (!fs::exists(calib_path)) {
    throw InputError(bag_path, "no calibration: " + calib_path +
                                   " does not exist (give a rig YAML or a Kalibr camchain with --calib)");
  }
  std::optional<KalibrFiles> kalibr;
  if (is_kalibr_camchain(calib_path)) {
    // A bag carries no calibration to fall back on: the IMU noise must come from Kalibr's imu file too.
    kalibr = kalibr_files_beside(calib_path);
    if (kalibr->imu.empty()) {
      throw InputError(calib_path, "a Kalibr camchain for a bag needs Kalibr's IMU noise file beside it (imu.yaml, "
                                   "or imu-NAME.yaml for camchain-imucam-NAME.yaml)");
    }
    apply_kalibr_files(*kalibr, index.calibration);
    index.summary.calibration = "kalibr " + calib_path;
  } else {
    index.calibration = read_rig_yaml(calib_path);
  }

  std::unique_ptr<MessageLog> bag = open_message_log(bag_path);
  const BagTopics topics = choose_bag_topics(*bag, topic_choices(calib_path, kalibr ? &*kalibr : nullptr, options));
  auto& listed = index.summary.topics;
  index.imu = read_imu(*bag, topics.imu0);
  listed.push_back("imu0 " + topics.imu0 + " " + kRosImu.datatype);
  if (!topics.groundtruth.empty()) {
    index.groundtruth = read_poses(*bag, topics.groundtruth);
    listed.push_back("groundtruth " + topics.groundtruth + " " + kRosPoseStamped.datatype);
  }

  auto store = std::make_shared<BagPayloads>(std::move(bag), topics, index.calibration);
  const MessageLog& in = store->bag();
  if (!topics.cam0.empty()) {
    index.has_cameras = true;
    std::map<TimeNs, std::size_t> left_of, right_of;
    ImageTopicInfo left_info, right_info;
    const auto left = index_images(in, topics.cam0, index.calibration.cam0, left_of, left_info);
    const auto right = index_images(in, topics.cam1, index.calibration.cam1, right_of, right_info);
    index.stereo = pair_stereo(left, right, index.summary.problems);
    for (const StereoEntry& e : index.stereo) store->stereo_ordinals.push_back({e.t_ns, left_of.at(e.t_ns), right_of.at(e.t_ns)});
    store->left_bits = left_info.scale_bits();
    store->right_bits = right_info.scale_bits();
    listed.push_back("cam0 " + topics.cam0 + " " + datatype_of(in, topics.cam0) + left_info.listed());
    listed.push_back("cam1 " + topics.cam1 + " " + datatype_of(in, topics.cam1) + right_info.listed());
  }
  if (!topics.lidar0.empty()) {
    if (!index.calibration.has_lidar) {
      throw InputError(calib_path, "the bag has LiDAR topic " + topics.lidar0 + " but the calibration has no lidar section");
    }
    require_md5(in, topics.lidar0, kRosPointCloud2);
    std::string layout;
    in.for_each(topics.lidar0, [&](std::size_t k, const std::vector<std::uint8_t>& bytes) {
      const auto [scan, name] = about_message(bag_path, topics.lidar0, k, [&] {
        const RosPointCloud2 cloud = decoders_of(in).point_cloud2(bytes);
        return std::make_pair(scan_from_point_cloud2(cloud), point_cloud2_layout(cloud));
      });
      if (k == 0) layout = name;
      require_increasing(bag_path, topics.lidar0, index.scans.empty() ? 0 : index.scans.back().t_ns, scan.t_ns, k);
      index.scans.push_back({scan.t_ns, bag_path + ":" + topics.lidar0 + "@" + std::to_string(scan.t_ns),
                             static_cast<long>(scan.points.size())});
      store->scan_ordinals.push_back(k);
    });
    listed.push_back("lidar0 " + topics.lidar0 + " " + kRosPointCloud2.datatype + " " + layout);
  }
  index.store = store;
  return index;
}

}  // namespace vilslam
