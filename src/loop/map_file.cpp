#include "loop/map_file.h"

#include <yaml-cpp/yaml.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "common/binary_io.h"
#include "common/error.h"
#include "common/json_writer.h"
#include "common/publish_dir.h"
#include "io/calibration_io.h"
#include "io/trajectory_io.h"

namespace vilslam::loop {
namespace {

namespace fs = std::filesystem;

constexpr char kFormat[] = "vilslam-map";
constexpr int kVersion = 1;
constexpr char kMagic[] = "VILSLAM_KEYFRAMES";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;
constexpr std::size_t kDescriptorBytes = 32;

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the file");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string hex(std::uint64_t v) {
  char buf[19];
  std::snprintf(buf, sizeof buf, "0x%016" PRIx64, v);
  return buf;
}

void put_pose(std::string& out, const SE3& T) {
  const Quat& q = T.quat();
  for (double v : {q.x(), q.y(), q.z(), q.w()}) put_binary(out, v);
  for (int i = 0; i < 3; ++i) put_binary(out, T.translation()[i]);
}

void put_features(std::string& out, const std::vector<lidar::FeaturePoint>& features) {
  put_binary(out, static_cast<std::uint32_t>(features.size()));
  for (const lidar::FeaturePoint& f : features) {
    for (int i = 0; i < 3; ++i) put_binary(out, f.p_L[i]);
    put_binary(out, f.t_offset_s);
    put_binary(out, f.smoothness);
  }
}

std::string key_frames_bytes(const std::vector<KeyFrame>& key_frames) {
  std::string out(kMagic, kMagicSize);
  put_binary(out, static_cast<std::uint32_t>(kVersion));
  put_binary(out, static_cast<std::uint64_t>(key_frames.size()));
  for (const KeyFrame& k : key_frames) {
    put_binary(out, static_cast<std::uint64_t>(k.pose_index));
    put_binary(out, k.scan_t_ns);
    put_binary(out, k.image.t_ns);
    put_binary(out, k.image.focal_px);
    put_pose(out, k.T_L_C0);
    const std::size_t rows = static_cast<std::size_t>(k.image.descriptors.rows);
    put_binary(out, static_cast<std::uint32_t>(rows));
    for (std::size_t r = 0; r < rows; ++r) {
      out.append(reinterpret_cast<const char*>(k.image.descriptors.ptr(static_cast<int>(r))), kDescriptorBytes);
      put_binary(out, k.image.left_norm[r].x());
      put_binary(out, k.image.left_norm[r].y());
      for (int i = 0; i < 3; ++i) put_binary(out, k.image.points_C0[r][i]);
    }
    put_binary(out, static_cast<std::uint32_t>(k.image.bow.size()));
    for (const auto& [word, weight] : k.image.bow) {
      put_binary(out, word);
      put_binary(out, weight);
    }
    put_binary(out, k.features_L.t_ns);
    put_features(out, k.features_L.edges);
    put_features(out, k.features_L.surfaces);
  }
  return out;
}

// A count read from the file, refused before anything is allocated when the bytes left cannot hold it.
std::size_t get_count(BinaryReader& in, std::size_t bytes_each, const char* what) {
  const std::uint32_t n = in.get<std::uint32_t>(what);
  if (static_cast<std::uint64_t>(n) * bytes_each > in.remaining()) {
    in.fail(std::string("truncated file: ") + std::to_string(n) + " " + what + " do not fit in the rest of it");
  }
  return n;
}

double get_finite(BinaryReader& in, const char* what) {
  const double v = in.get<double>(what);
  if (!std::isfinite(v)) in.fail(std::string("non-finite ") + what);
  return v;
}

SE3 get_pose(BinaryReader& in) {
  double q[4], t[3];
  for (double& v : q) v = get_finite(in, "T_L_C0");
  for (double& v : t) v = get_finite(in, "T_L_C0");
  const Quat quat(q[3], q[0], q[1], q[2]);
  if (std::abs(quat.norm() - 1.0) > 1e-6) in.fail("T_L_C0 has a quaternion that is not unit");
  return SE3(quat.normalized(), Vec3(t[0], t[1], t[2]));
}

std::vector<lidar::FeaturePoint> get_features(BinaryReader& in, const char* what) {
  std::vector<lidar::FeaturePoint> features(get_count(in, 3 * sizeof(double) + 2 * sizeof(float), what));
  for (lidar::FeaturePoint& f : features) {
    for (int i = 0; i < 3; ++i) f.p_L[i] = get_finite(in, what);
    f.t_offset_s = in.get<float>(what);
    f.smoothness = in.get<float>(what);
    if (!std::isfinite(f.t_offset_s) || !std::isfinite(f.smoothness)) in.fail(std::string("non-finite ") + what);
  }
  return features;
}

KeyFrame get_key_frame(BinaryReader& in) {
  KeyFrame k;
  k.pose_index = static_cast<std::size_t>(in.get<std::uint64_t>("pose index"));
  k.scan_t_ns = in.get<TimeNs>("scan time");
  k.image.t_ns = in.get<TimeNs>("image time");
  k.image.focal_px = get_finite(in, "focal length");
  if (!(k.image.focal_px > 0.0)) in.fail("non-positive focal length");
  k.T_L_C0 = get_pose(in);
  const std::size_t rows = get_count(in, kDescriptorBytes + 5 * sizeof(double), "descriptor rows");
  k.image.descriptors = cv::Mat(static_cast<int>(rows), static_cast<int>(kDescriptorBytes), CV_8U);
  k.image.left_norm.resize(rows);
  k.image.points_C0.resize(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    in.take(k.image.descriptors.ptr(static_cast<int>(r)), kDescriptorBytes, "descriptor rows");
    const double x = get_finite(in, "normalized coordinates"), y = get_finite(in, "normalized coordinates");
    k.image.left_norm[r] = Eigen::Vector2d(x, y);
    Vec3& p = k.image.points_C0[r];
    for (int i = 0; i < 3; ++i) p[i] = in.get<double>("3D points");
    if (!p.allFinite() && !p.array().isNaN().all()) in.fail("a 3D point is partly non-finite (unmatched rows are all NaN)");
  }
  const std::size_t words = get_count(in, sizeof(WordId) + sizeof(double), "BoW entries");
  for (std::size_t i = 0; i < words; ++i) {
    const WordId word = in.get<WordId>("BoW entries");
    const double weight = get_finite(in, "BoW weight");
    if (!k.image.bow.empty() && word <= k.image.bow.rbegin()->first) in.fail("BoW words not in increasing order");
    k.image.bow.emplace_hint(k.image.bow.end(), word, weight);
  }
  k.features_L.t_ns = in.get<TimeNs>("feature scan time");
  k.features_L.edges = get_features(in, "edge features");
  k.features_L.surfaces = get_features(in, "surface features");
  return k;
}

std::vector<KeyFrame> read_key_frames(const std::string& path, const Trajectory& poses) {
  const std::string bytes = read_bytes(path);
  BinaryReader in(path, bytes);
  std::string magic(kMagicSize, '\0');
  in.take(magic.data(), kMagicSize, "the magic string");
  if (magic != std::string(kMagic, kMagicSize)) in.fail("not a vilslam key frame file (bad magic string)");
  const auto version = in.get<std::uint32_t>("the version");
  if (version != kVersion) in.fail("key frame file version " + std::to_string(version) + ", this build reads " + std::to_string(kVersion));
  const auto count = in.get<std::uint64_t>("the key frame count");
  std::vector<KeyFrame> key_frames;
  for (std::uint64_t i = 0; i < count; ++i) {
    KeyFrame k = get_key_frame(in);
    k.id = key_frames.size();
    const std::string which = "key frame " + std::to_string(i);
    if (k.pose_index >= poses.size()) in.fail(which + ": pose index " + std::to_string(k.pose_index) + " beyond poses.tum");
    if (poses[k.pose_index].t_ns != k.scan_t_ns) in.fail(which + ": its time is not that of its pose in poses.tum");
    if (!key_frames.empty() && k.scan_t_ns <= key_frames.back().scan_t_ns) in.fail(which + ": not after the previous one");
    key_frames.push_back(std::move(k));
  }
  if (in.remaining() != 0) in.fail("trailing bytes after the last key frame");
  return key_frames;
}

double rotation_angle_rad(const SE3& a, const SE3& b) {
  return Eigen::AngleAxisd(a.rotation().transpose() * b.rotation()).angle();
}

bool same_camera(const CameraIntrinsics& a, const CameraIntrinsics& b) {
  return a.width_px == b.width_px && a.height_px == b.height_px && std::abs(a.fx - b.fx) <= 0.5 &&
         std::abs(a.fy - b.fy) <= 0.5 && std::abs(a.cx - b.cx) <= 0.5 && std::abs(a.cy - b.cy) <= 0.5;
}

bool same_extrinsic(const SE3& a, const SE3& b) {
  return (a.translation() - b.translation()).norm() <= 1e-3 && rotation_angle_rad(a, b) <= 0.1 * M_PI / 180.0;
}

}  // namespace

std::uint64_t vocabulary_identity(const std::string& vocabulary_path) {
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : read_bytes(vocabulary_path)) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

void save_map(const std::string& dir, const SavedMap& map) {
  for (const KeyFrame& k : map.key_frames) {
    if (k.pose_index >= map.poses.size()) throw std::invalid_argument("save_map: key frame pose index out of range");
  }
  const fs::path partial = dir + ".partial";
  fs::remove_all(partial);
  fs::create_directories(partial);
  YAML::Emitter yaml;
  yaml << YAML::BeginMap << YAML::Key << "format" << YAML::Value << kFormat << YAML::Key << "version" << YAML::Value
       << kVersion << YAML::Key << "vocabulary_fnv1a64" << YAML::Value << hex(map.vocabulary_id) << YAML::Key
       << "key_frames" << YAML::Value << map.key_frames.size() << YAML::Key << "poses" << YAML::Value
       << map.poses.size() << YAML::EndMap;
  write_file_atomic((partial / "map.yaml").string(), std::string(yaml.c_str()) + "\n");
  write_rig_yaml((partial / "rig.yaml").string(), map.rig);
  write_trajectory((partial / "poses.tum").string(), map.poses, TrajectoryFormat::kTum);
  write_file_atomic((partial / "key_frames.bin").string(), key_frames_bytes(map.key_frames));
  publish_directory(partial.string(), dir);
}

SavedMap load_map(const std::string& dir) {
  if (!fs::is_directory(dir)) throw InputError(dir, "not a map folder");
  const std::string yaml_path = (fs::path(dir) / "map.yaml").string();
  if (!fs::exists(yaml_path)) throw InputError(yaml_path, "missing: not a vilslam map folder");
  SavedMap map;
  std::size_t key_frames = 0, poses = 0;
  try {
    const YAML::Node y = YAML::LoadFile(yaml_path);
    if (!y.IsMap() || y["format"].as<std::string>("") != kFormat) throw InputError(yaml_path, "not a vilslam map (format)");
    const int version = y["version"].as<int>(-1);
    if (version != kVersion) {
      throw InputError(yaml_path, "map version " + std::to_string(version) + ", this build reads " + std::to_string(kVersion));
    }
    map.vocabulary_id = std::stoull(y["vocabulary_fnv1a64"].as<std::string>(), nullptr, 16);
    key_frames = y["key_frames"].as<std::size_t>();
    poses = y["poses"].as<std::size_t>();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(yaml_path, std::string("malformed: ") + e.what());
  }
  map.rig = read_rig_yaml((fs::path(dir) / "rig.yaml").string());
  const std::string poses_path = (fs::path(dir) / "poses.tum").string();
  map.poses = read_trajectory(poses_path, TrajectoryFormat::kTum);
  if (map.poses.size() != poses) throw InputError(poses_path, "holds " + std::to_string(map.poses.size()) + " poses, map.yaml says " + std::to_string(poses));
  const std::string kf_path = (fs::path(dir) / "key_frames.bin").string();
  map.key_frames = read_key_frames(kf_path, map.poses);
  if (map.key_frames.size() != key_frames) {
    throw InputError(kf_path, "holds " + std::to_string(map.key_frames.size()) + " key frames, map.yaml says " + std::to_string(key_frames));
  }
  return map;
}

void check_map_fits(const SavedMap& map, const std::string& dir, std::uint64_t vocabulary_id, const RigCalibration& rig) {
  if (map.vocabulary_id != vocabulary_id) {
    throw InputError((fs::path(dir) / "map.yaml").string(),
                     "built with another vocabulary (" + hex(map.vocabulary_id) + ", this run uses " + hex(vocabulary_id) + ")");
  }
  const std::string rig_path = (fs::path(dir) / "rig.yaml").string();
  if (!same_camera(map.rig.cam0, rig.cam0) || !same_camera(map.rig.cam1, rig.cam1)) {
    throw InputError(rig_path, "the map's cameras are not this rig's (image size, or intrinsics more than 0.5 px apart)");
  }
  if (!same_extrinsic(map.rig.T_I_C0, rig.T_I_C0) || !same_extrinsic(map.rig.T_I_C1, rig.T_I_C1)) {
    throw InputError(rig_path, "the map's camera extrinsics are more than 1 mm or 0.1 deg from this rig's");
  }
  if (map.rig.has_lidar != rig.has_lidar || (rig.has_lidar && !same_extrinsic(map.rig.T_I_L, rig.T_I_L))) {
    throw InputError(rig_path, "the map's LiDAR is not this rig's (missing on one, or 1 mm / 0.1 deg apart)");
  }
}

}  // namespace vilslam::loop
