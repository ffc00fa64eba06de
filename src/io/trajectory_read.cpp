// Reading TUM, KITTI and EuRoC trajectory files with line-accurate InputErrors (rows parsed by io/csv.h).
#include <cmath>
#include <string>
#include <vector>

#include "common/error.h"
#include "io/csv.h"
#include "io/trajectory_io.h"

namespace vilslam {
namespace {

constexpr double kQuatNormTolerance = 1e-3;      // |q| must be 1 within this (files print 4+ decimals)
constexpr double kRotationOrthoTolerance = 1e-3;  // max |R^T R - I| and |det R - 1| for KITTI rows

void require_columns(const Table& table, const TableRow& row, const std::string& expected, bool ok) {
  if (!ok) {
    throw InputError(table.path(), "expected " + expected + " columns, found " + std::to_string(row.fields.size()),
                     row.line);
  }
}

Vec3 vec3(const Table& table, const TableRow& row, std::size_t col) {
  return Vec3(table.number(row, col), table.number(row, col + 1), table.number(row, col + 2));
}

// Translation from columns p_col..p_col+2, quaternion w from w_col and x, y, z from xyz_col..xyz_col+2.
SE3 pose_from_columns(const Table& table, const TableRow& row, std::size_t p_col, std::size_t w_col, std::size_t xyz_col) {
  const double w = table.number(row, w_col);
  const Vec3 xyz = vec3(table, row, xyz_col);
  const double norm = std::sqrt(w * w + xyz.squaredNorm());
  if (std::abs(norm - 1.0) > kQuatNormTolerance) {
    throw InputError(table.path(), "quaternion is not unit (|q| = " + std::to_string(norm) + ")", row.line);
  }
  return SE3(Quat(w, xyz.x(), xyz.y(), xyz.z()), vec3(table, row, p_col));
}

std::vector<TimeNs> times_of(const Trajectory& traj) {
  std::vector<TimeNs> times;
  for (const TimedPose& p : traj) times.push_back(p.t_ns);
  return times;
}

// The poses of rows with a new time (Table::rows_without_repeated_times): benchmark files repeat a stamp.
Trajectory without_repeated_times(const Table& table, const Trajectory& traj) {
  Trajectory kept;
  for (std::size_t i : table.rows_without_repeated_times(times_of(traj))) kept.push_back(traj[i]);
  return kept;
}

Trajectory read_tum(const std::string& path) {
  const Table table(path, ' ', 8);
  Trajectory traj;
  for (const TableRow& row : table.rows()) {
    require_columns(table, row, "8 (t x y z qx qy qz qw)", row.fields.size() == 8);
    traj.push_back({table.seconds_as_ns(row, 0), pose_from_columns(table, row, 1, 7, 4)});
  }
  return without_repeated_times(table, traj);
}

Trajectory read_euroc(const std::string& path) {
  const Table table(path, ',', 8);
  Trajectory traj;
  for (const TableRow& row : table.rows()) {
    const std::size_t n = row.fields.size();
    require_columns(table, row, "8, 11, 14 or 17 (t, p, q_wxyz[, v, b_w, b_a])", n <= 17 && (n - 8) % 3 == 0);
    for (std::size_t col = 8; col < n; ++col) table.number(row, col);  // extra state columns must be numbers too
    traj.push_back({table.time_ns(row, 0), pose_from_columns(table, row, 1, 4, 5)});
  }
  return without_repeated_times(table, traj);
}

std::vector<TimeNs> read_times(const std::string& path) {
  const Table table(path, ' ', 1);
  std::vector<TimeNs> times;
  for (const TableRow& row : table.rows()) {
    require_columns(table, row, "1 (t in seconds)", row.fields.size() == 1);
    times.push_back(table.seconds_as_ns(row, 0));
  }
  table.require_increasing(times);
  return times;
}

Trajectory read_kitti(const std::string& path, const std::string& times_path) {
  const Table table(path, ' ', 12);
  std::vector<TimeNs> times;
  if (!times_path.empty()) {
    times = read_times(times_path);
    if (times.size() != table.rows().size()) {
      throw InputError(times_path, std::to_string(times.size()) + " times for " +
                                       std::to_string(table.rows().size()) + " poses in " + path);
    }
  }
  Trajectory traj;
  for (std::size_t i = 0; i < table.rows().size(); ++i) {
    const TableRow& row = table.rows()[i];
    require_columns(table, row, "12 (3x4 row-major)", row.fields.size() == 12);
    Mat3 R;
    Vec3 t;
    for (std::size_t r = 0; r < 3; ++r) {
      for (std::size_t c = 0; c < 3; ++c) R(r, c) = table.number(row, 4 * r + c);
      t(r) = table.number(row, 4 * r + 3);
    }
    if (so3::orthonormality_error(R) > kRotationOrthoTolerance) {
      throw InputError(path, "rotation is not orthonormal", row.line);
    }
    traj.push_back({times.empty() ? static_cast<TimeNs>(i) * kNsPerSecond : times[i], SE3(R, t)});
  }
  return traj;
}

}  // namespace

Trajectory read_trajectory(const std::string& path, TrajectoryFormat format, const std::string& times_path) {
  switch (format) {
    case TrajectoryFormat::kTum:
      return read_tum(path);
    case TrajectoryFormat::kKitti:
      return read_kitti(path, times_path);
    case TrajectoryFormat::kEuroc:
      return read_euroc(path);
  }
  throw std::invalid_argument("unknown trajectory format");
}

}  // namespace vilslam
