// Reading loops.csv (see loop_constraints_io.h) with line-accurate InputErrors (rows parsed by io/csv.h).
#include "loop/loop_constraints_io.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.h"
#include "io/csv.h"

namespace vilslam::loop {
namespace {

constexpr std::size_t kPoseFields = 9;
constexpr std::size_t kFieldsWithSigmas = 11;
constexpr double kQuatNormTolerance = 1e-3;  // same tolerance as the trajectory readers

std::size_t index_of_time(const Table& table, const TableRow& row, std::size_t col, const Trajectory& poses) {
  const TimeNs t_ns = table.time_ns(row, col);
  const auto it = std::lower_bound(poses.begin(), poses.end(), t_ns,
                                   [](const TimedPose& p, TimeNs t) { return p.t_ns < t; });
  if (it == poses.end() || it->t_ns != t_ns) {
    throw InputError(table.path(), "time " + std::to_string(t_ns) + " ns is not a pose time of the trajectory",
                     row.line);
  }
  return static_cast<std::size_t>(it - poses.begin());
}

SE3 pose_of(const Table& table, const TableRow& row) {
  const Vec3 t(table.number(row, 2), table.number(row, 3), table.number(row, 4));
  const Quat q(table.number(row, 8), table.number(row, 5), table.number(row, 6), table.number(row, 7));
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > kQuatNormTolerance) {
    throw InputError(table.path(), "quaternion is not unit (|q| = " + std::to_string(norm) + ")", row.line);
  }
  return SE3(q, t);
}

Mat6 information_of(const Table& table, const TableRow& row, const LoopSigmas& defaults) {
  if (row.fields.size() != kPoseFields && row.fields.size() != kFieldsWithSigmas) {
    throw InputError(table.path(), "expected 9 or 11 fields, got " + std::to_string(row.fields.size()), row.line);
  }
  LoopSigmas s = defaults;
  if (row.fields.size() == kFieldsWithSigmas) {
    s.sigma_m = table.number(row, 9);
    s.sigma_rad = table.number(row, 10);
    if (!(s.sigma_m > 0.0) || !(s.sigma_rad > 0.0)) throw InputError(table.path(), "sigmas must be positive", row.line);
  }
  return information_from_sigmas(s.sigma_m, s.sigma_rad);
}

}  // namespace

std::vector<RelativePoseConstraint> read_loop_constraints(const std::string& path, const Trajectory& poses,
                                                          const LoopSigmas& defaults) {
  const Table table(path, ',', kPoseFields);
  std::vector<RelativePoseConstraint> constraints;
  for (const TableRow& row : table.rows()) {
    RelativePoseConstraint c;
    c.from_index = index_of_time(table, row, 0, poses);
    c.to_index = index_of_time(table, row, 1, poses);
    if (c.from_index == c.to_index) throw InputError(path, "from and to times are equal", row.line);
    c.T_from_to = pose_of(table, row);
    c.information = information_of(table, row, defaults);
    c.kind = ConstraintKind::kLoop;
    constraints.push_back(c);
  }
  return constraints;
}

}  // namespace vilslam::loop
