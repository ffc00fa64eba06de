#include "io/euroc_tables.h"

#include <filesystem>

#include "common/error.h"
#include "common/log.h"
#include "io/csv.h"
#include "io/euroc_calibration.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

Vec3 vec3(const Table& table, const TableRow& row, std::size_t col) {
  return Vec3(table.number(row, col), table.number(row, col + 1), table.number(row, col + 2));
}

// A unit quaternion from four columns; a zero quaternion cannot be a rotation.
Quat quaternion(const Table& table, const TableRow& row, double w, double x, double y, double z) {
  const Quat q(w, x, y, z);
  if (q.norm() < 1e-6) throw InputError(table.path(), "quaternion has zero norm", row.line);
  return q.normalized();
}

}  // namespace

std::vector<ImuSample> read_imu_csv(const std::string& path) {
  const Table table(path, ',', 7);
  std::vector<ImuSample> imu;
  imu.reserve(table.rows().size());
  for (const TableRow& row : table.rows()) {
    ImuSample s;
    s.t_ns = table.time_ns(row, 0);
    s.gyro_rad_s = vec3(table, row, 1);
    s.accel_m_s2 = vec3(table, row, 4);
    imu.push_back(s);
  }
  table.require_increasing(times_of(imu));
  return imu;
}

std::vector<GroundTruthState> read_groundtruth_csv(const std::string& path, const SE3& T_S_I) {
  const Table table(path, ',', 17);
  std::vector<GroundTruthState> gt;
  gt.reserve(table.rows().size());
  for (const TableRow& row : table.rows()) {
    GroundTruthState s;
    s.t_ns = table.time_ns(row, 0);
    const Quat q_R_S = quaternion(table, row, table.number(row, 4), table.number(row, 5), table.number(row, 6),
                                  table.number(row, 7));
    s.T_W_I = SE3(q_R_S, vec3(table, row, 1)) * T_S_I;
    s.v_W_m_s = vec3(table, row, 8);
    s.bias_gyro_rad_s = vec3(table, row, 11);
    s.bias_accel_m_s2 = vec3(table, row, 14);
    gt.push_back(s);
  }
  table.require_increasing(times_of(gt));
  return gt;
}

std::vector<GroundTruthState> read_groundtruth_tum(const std::string& path, const SE3& T_S_I) {
  const Table table(path, ' ', 8);
  std::vector<GroundTruthState> gt;
  gt.reserve(table.rows().size());
  for (const TableRow& row : table.rows()) {
    GroundTruthState s;
    s.t_ns = table.seconds_as_ns(row, 0);
    const Quat q_W_S = quaternion(table, row, table.number(row, 7), table.number(row, 4), table.number(row, 5),
                                  table.number(row, 6));
    s.T_W_I = SE3(q_W_S, vec3(table, row, 1)) * T_S_I;
    gt.push_back(s);
  }
  table.require_increasing(times_of(gt));
  return gt;
}

std::vector<GroundTruthState> read_euroc_groundtruth(const std::string& mav0, const SE3& T_B_I) {
  const struct {
    const char* folder;
    const char* file;
    bool tum;
  } candidates[] = {{"state_groundtruth_estimate0", "data.csv", false},
                    {"gt0", "data.csv", false},
                    {"state_groundtruth_estimate0", "groundtruth.tum", true}};
  for (const auto& c : candidates) {
    const fs::path dir = fs::path(mav0) / c.folder;
    const fs::path file = dir / c.file;
    if (!fs::exists(file)) continue;
    const fs::path yaml = dir / "sensor.yaml";
    const SE3 T_B_S = fs::exists(yaml) ? read_euroc_T_BS(yaml.string()) : SE3::identity();
    const SE3 T_S_I = T_B_S.inverse() * T_B_I;
    return c.tum ? read_groundtruth_tum(file.string(), T_S_I) : read_groundtruth_csv(file.string(), T_S_I);
  }
  return {};
}

std::vector<ImageRow> read_camera_csv(const std::string& cam_dir, bool missing_is_error,
                                      std::vector<std::string>& problems) {
  const std::string csv = (fs::path(cam_dir) / "data.csv").string();
  const Table table(csv, ',', 2);
  std::vector<ImageRow> rows;
  std::vector<TimeNs> all_times;
  for (const TableRow& row : table.rows()) {
    const TimeNs t = table.time_ns(row, 0);
    all_times.push_back(t);
    const std::string image = (fs::path(cam_dir) / "data" / table.text(row, 1)).string();
    if (!fs::exists(image)) {
      if (missing_is_error) throw InputError(image, "image listed in " + csv + ":" + std::to_string(row.line) + " is missing");
      spdlog::warn("{}:{}: skipping row, image {} is missing", csv, row.line, image);
      problems.push_back(csv + ":" + std::to_string(row.line) + ": skipped row, missing image " + image);
      continue;
    }
    rows.push_back({t, image});
  }
  table.require_increasing(all_times);
  return rows;
}

std::vector<StereoEntry> pair_stereo(const std::vector<ImageRow>& left, const std::vector<ImageRow>& right,
                                     std::vector<std::string>& problems) {
  std::vector<StereoEntry> pairs;
  std::size_t i = 0, j = 0, left_only = 0, right_only = 0;
  while (i < left.size() || j < right.size()) {
    if (j == right.size() || (i < left.size() && left[i].t_ns < right[j].t_ns)) {
      ++left_only;
      ++i;
    } else if (i == left.size() || right[j].t_ns < left[i].t_ns) {
      ++right_only;
      ++j;
    } else {
      pairs.push_back({left[i].t_ns, left[i].path, right[j].path});
      ++i;
      ++j;
    }
  }
  if (left_only > 0) problems.push_back("cam0: " + std::to_string(left_only) + " images without a cam1 image at the same time");
  if (right_only > 0) problems.push_back("cam1: " + std::to_string(right_only) + " images without a cam0 image at the same time");
  return pairs;
}

}  // namespace vilslam
