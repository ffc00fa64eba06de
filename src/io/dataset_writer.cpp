#include "io/dataset_writer.h"

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "common/error.h"
#include "common/json_writer.h"
#include "common/publish_dir.h"
#include "io/calibration_io.h"
#include "io/euroc_calibration.h"
#include "io/scan_file.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string vec_fields(const Vec3& v) { return num(v.x()) + "," + num(v.y()) + "," + num(v.z()); }

void open_csv(std::ofstream& f, const fs::path& path, const char* header) {
  f.open(path, std::ios::trunc);
  if (!f) throw InputError(path.string(), "cannot create file");
  f << header << "\n";
}

void require_after(TimeNs t_ns, TimeNs& last_t_ns, const char* stream) {
  if (t_ns <= last_t_ns) {
    throw std::invalid_argument(std::string("DatasetWriter: ") + stream + " timestamps must increase strictly (" +
                                std::to_string(t_ns) + " after " + std::to_string(last_t_ns) + ")");
  }
  last_t_ns = t_ns;
}

}  // namespace

struct DatasetWriter::Impl {
  fs::path root;
  fs::path partial;
  fs::path mav0;
  RigCalibration calib;
  bool overwrite = false;
  bool finished = false;
  std::ofstream imu_csv, cam_csv[2], gt_csv, lidar_csv;
  TimeNs last_imu = INT64_MIN, last_stereo = INT64_MIN, last_lidar = INT64_MIN, last_gt = INT64_MIN;

  void write_image(int cam, TimeNs t_ns, const cv::Mat& image) {
    if (image.empty() || image.type() != CV_8UC1) throw std::invalid_argument("DatasetWriter: images must be 8-bit grey");
    const std::string name = std::to_string(t_ns) + ".png";
    const fs::path path = mav0 / ("cam" + std::to_string(cam)) / "data" / name;
    if (!cv::imwrite(path.string(), image)) throw std::runtime_error("cannot write " + path.string());
    cam_csv[cam] << t_ns << "," << name << "\n";
  }
};

DatasetWriter::DatasetWriter(const std::string& root, const RigCalibration& calib, bool overwrite)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.root = fs::path(root);
  if (!m.root.has_filename()) m.root = m.root.parent_path();  // "dir/" names dir
  m.partial = m.root;
  m.partial += ".partial";
  m.mav0 = m.partial / "mav0";
  m.calib = calib;
  m.overwrite = overwrite;
  validate_calibration(calib, root + " (calibration given to DatasetWriter)");
  if (fs::exists(m.root) && !overwrite) throw InputError(root, "already exists (pass overwrite to replace it)");
  std::error_code ec;
  fs::remove_all(m.partial, ec);
  for (const char* dir : {"cam0/data", "cam1/data", "imu0", "state_groundtruth_estimate0"}) {
    fs::create_directories(m.mav0 / dir, ec);
    if (ec) throw InputError((m.mav0 / dir).string(), "cannot create folder: " + ec.message());
  }
  open_csv(m.imu_csv, m.mav0 / "imu0" / "data.csv",
           "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
           "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]");
  for (int cam = 0; cam < 2; ++cam) {
    open_csv(m.cam_csv[cam], m.mav0 / ("cam" + std::to_string(cam)) / "data.csv", "#timestamp [ns],filename");
  }
  open_csv(m.gt_csv, m.mav0 / "state_groundtruth_estimate0" / "data.csv",
           "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], "
           "v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], "
           "b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]");
  if (calib.has_lidar) {
    fs::create_directories(m.mav0 / "lidar0" / "data", ec);
    if (ec) throw InputError((m.mav0 / "lidar0").string(), "cannot create folder: " + ec.message());
    open_csv(m.lidar_csv, m.mav0 / "lidar0" / "data.csv", "#timestamp [ns],filename,num_points");
  }
}

DatasetWriter::~DatasetWriter() {
  if (impl_ && !impl_->finished) {
    std::error_code ec;
    fs::remove_all(impl_->partial, ec);
  }
}

void DatasetWriter::add_imu(const ImuSample& s) {
  require_after(s.t_ns, impl_->last_imu, "IMU");
  impl_->imu_csv << s.t_ns << "," << vec_fields(s.gyro_rad_s) << "," << vec_fields(s.accel_m_s2) << "\n";
}

void DatasetWriter::add_stereo(const StereoFrame& frame) {
  require_after(frame.t_ns, impl_->last_stereo, "stereo");
  impl_->write_image(0, frame.t_ns, frame.left);
  impl_->write_image(1, frame.t_ns, frame.right);
}

void DatasetWriter::add_lidar(const LidarScan& scan) {
  if (!impl_->calib.has_lidar) throw std::invalid_argument("DatasetWriter: the calibration has no LiDAR");
  require_after(scan.t_ns, impl_->last_lidar, "LiDAR");
  const std::string name = std::to_string(scan.t_ns) + ".bin";
  write_scan_file((impl_->mav0 / "lidar0" / "data" / name).string(), scan);
  impl_->lidar_csv << scan.t_ns << "," << name << "," << scan.points.size() << "\n";
}

void DatasetWriter::add_groundtruth(const GroundTruthState& s) {
  require_after(s.t_ns, impl_->last_gt, "ground truth");
  const Quat& q = s.T_W_I.quat();
  impl_->gt_csv << s.t_ns << "," << vec_fields(s.T_W_I.translation()) << "," << num(q.w()) << "," << num(q.x()) << ","
                << num(q.y()) << "," << num(q.z()) << "," << vec_fields(s.v_W_m_s) << ","
                << vec_fields(s.bias_gyro_rad_s) << "," << vec_fields(s.bias_accel_m_s2) << "\n";
}

void DatasetWriter::set_reference_model(const PointCloud& model) {
  write_cloud((impl_->partial / "model.ply").string(), model);
}

std::string DatasetWriter::staging_path() const { return impl_->partial.string(); }

void DatasetWriter::finish() {
  Impl& m = *impl_;
  if (m.finished) return;
  for (std::ofstream* f : {&m.imu_csv, &m.cam_csv[0], &m.cam_csv[1], &m.gt_csv, &m.lidar_csv}) {
    if (!f->is_open()) continue;
    f->close();
    if (!*f) throw std::runtime_error("cannot write the index files under " + m.partial.string());
  }
  const RigCalibration& c = m.calib;
  // The body frame of the sensor.yaml files is I: T_BS = T_I_S.
  write_file_atomic((m.mav0 / "cam0" / "sensor.yaml").string(), euroc_camera_yaml_text(c.cam0, c.T_I_C0, "cam0"));
  write_file_atomic((m.mav0 / "cam1" / "sensor.yaml").string(), euroc_camera_yaml_text(c.cam1, c.T_I_C1, "cam1"));
  write_file_atomic((m.mav0 / "imu0" / "sensor.yaml").string(), euroc_imu_yaml_text(c.imu));
  if (c.has_lidar) {
    write_file_atomic((m.mav0 / "lidar0" / "sensor.yaml").string(), euroc_lidar_yaml_text(c.lidar, c.T_I_L));
  }
  write_rig_yaml((m.partial / "rig.yaml").string(), c);
  publish_directory(m.partial.string(), m.root.string());
  m.finished = true;
}

}  // namespace vilslam
