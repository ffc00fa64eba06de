// Reading and writing loops.csv (see loop_constraints_io.h) with line-accurate InputErrors (rows parsed
// by io/csv.h).
#include "loop/loop_constraints_io.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "common/error.h"
#include "io/csv.h"

namespace vilslam::loop {
namespace {

constexpr std::size_t kPoseFields = 9;
constexpr std::size_t kFieldsWithSigmas = 11;
constexpr std::size_t kEpnpFields = 7;
constexpr std::size_t kScoreFields = 9;
constexpr std::size_t kLongFields = kFieldsWithSigmas + kEpnpFields + kScoreFields;
constexpr double kQuatNormTolerance = 1e-3;  // same tolerance as the trajectory readers

// tx ty tz qx qy qz qw starting at column first.
SE3 pose_at_column(const Table& table, const TableRow& row, std::size_t first) {
  const Vec3 t(table.number(row, first), table.number(row, first + 1), table.number(row, first + 2));
  const Quat q(table.number(row, first + 6), table.number(row, first + 3), table.number(row, first + 4),
               table.number(row, first + 5));
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > kQuatNormTolerance) {
    throw InputError(table.path(), "quaternion is not unit (|q| = " + std::to_string(norm) + ")", row.line);
  }
  return SE3(q, t);
}

LoopRow parse_row(const Table& table, const TableRow& row) {
  const std::size_t n = row.fields.size();
  if (n != kPoseFields && n != kFieldsWithSigmas && n != kLongFields) {
    throw InputError(table.path(), "expected 9, 11 or 27 fields, got " + std::to_string(n), row.line);
  }
  LoopRow r;
  r.line = row.line;
  r.from_t_ns = table.time_ns(row, 0);
  r.to_t_ns = table.time_ns(row, 1);
  if (r.from_t_ns == r.to_t_ns) throw InputError(table.path(), "from and to times are equal", row.line);
  r.T_from_to = pose_at_column(table, row, 2);
  if (n >= kFieldsWithSigmas) {
    r.sigmas = LoopSigmas{table.number(row, 9), table.number(row, 10)};
    if (!(r.sigmas->sigma_m > 0.0) || !(r.sigmas->sigma_rad > 0.0)) {
      throw InputError(table.path(), "sigmas must be positive", row.line);
    }
  }
  if (n == kLongFields) {
    r.T_from_to_epnp = pose_at_column(table, row, kFieldsWithSigmas);
    std::size_t c = kFieldsWithSigmas + kEpnpFields;
    LoopScores s;
    for (double* v : {&s.bow_score, &s.descriptor_matches, &s.pnp_inliers, &s.icp_rms_m, &s.icp_inlier_fraction,
                      &s.icp_min_eigenvalue_per_match, &s.epnp_icp_translation_m, &s.epnp_icp_rotation_rad,
                      &s.odometry_disagreement_m}) {
      *v = table.number(row, c++);
    }
    r.scores = s;
  }
  return r;
}

std::size_t index_of_time(const std::string& path, long line, TimeNs t_ns, const Trajectory& poses) {
  const auto it = std::lower_bound(poses.begin(), poses.end(), t_ns,
                                   [](const TimedPose& p, TimeNs t) { return p.t_ns < t; });
  if (it == poses.end() || it->t_ns != t_ns) {
    throw InputError(path, "time " + std::to_string(t_ns) + " ns is not a pose time of the trajectory", line);
  }
  return static_cast<std::size_t>(it - poses.begin());
}

void write_pose(std::ostream& out, const SE3& T) {
  const Vec3& t = T.translation();
  const Quat& q = T.quat();
  out << ',' << t.x() << ',' << t.y() << ',' << t.z() << ',' << q.x() << ',' << q.y() << ',' << q.z() << ','
      << q.w();
}

void write_scores(std::ostream& out, const LoopCandidateRecord& r) {
  out << ',' << r.bow_score << ',' << r.descriptor_matches << ',' << r.pnp_inliers << ',' << r.icp_rms_m << ','
      << r.icp_inlier_fraction << ',' << r.icp_min_eigenvalue_per_match << ',' << r.epnp_icp_translation_m << ','
      << r.epnp_icp_rotation_rad << ',' << r.odometry_disagreement_m;
}

constexpr const char* kScoreHeader =
    "bow_score,descriptor_matches,pnp_inliers,icp_rms_m,icp_inlier_fraction,icp_min_eigenvalue_per_match,"
    "epnp_icp_translation_m,epnp_icp_rotation_rad,odometry_disagreement_m";

}  // namespace

std::vector<LoopRow> read_loop_rows(const std::string& path) {
  const Table table(path, ',', kPoseFields);
  std::vector<LoopRow> rows;
  for (const TableRow& row : table.rows()) rows.push_back(parse_row(table, row));
  return rows;
}

std::vector<RelativePoseConstraint> read_loop_constraints(const std::string& path, const Trajectory& poses,
                                                          const LoopSigmas& defaults) {
  std::vector<RelativePoseConstraint> constraints;
  for (const LoopRow& row : read_loop_rows(path)) {
    RelativePoseConstraint c;
    c.from_index = index_of_time(path, row.line, row.from_t_ns, poses);
    c.to_index = index_of_time(path, row.line, row.to_t_ns, poses);
    c.T_from_to = row.T_from_to;
    const LoopSigmas s = row.sigmas.value_or(defaults);
    c.information = information_from_sigmas(s.sigma_m, s.sigma_rad);
    c.kind = ConstraintKind::kLoop;
    constraints.push_back(c);
  }
  return constraints;
}

std::string loops_csv(const std::vector<LoopCandidateRecord>& records) {
  std::ostringstream out;
  out << std::setprecision(17)
      << "# from_t_ns,to_t_ns,tx,ty,tz,qx,qy,qz,qw,sigma_m,sigma_rad,epnp_tx,epnp_ty,epnp_tz,epnp_qx,epnp_qy,epnp_qz,"
         "epnp_qw,"
      << kScoreHeader << '\n';
  for (const LoopCandidateRecord& r : records) {
    if (!r.accepted()) continue;
    // The graph uses the full information; the sigma columns give its diagonal's standard deviations.
    out << r.candidate_t_ns << ',' << r.query_t_ns;
    write_pose(out, r.T_Lu_Lv);
    out << ',' << 1.0 / std::sqrt(r.information(0, 0)) << ',' << 1.0 / std::sqrt(r.information(3, 3));
    write_pose(out, r.T_Lu_Lv_epnp);
    write_scores(out, r);
    out << '\n';
  }
  return out.str();
}

std::string loop_candidates_csv(const std::vector<LoopCandidateRecord>& records) {
  std::ostringstream out;
  out << std::setprecision(17) << "# query_t_ns,candidate_t_ns,query_key_frame,candidate_key_frame," << kScoreHeader
      << ",icp_matched_fraction,stage\n";
  for (const LoopCandidateRecord& r : records) {
    out << r.query_t_ns << ',' << r.candidate_t_ns << ',' << r.query_key_frame << ',' << r.candidate_key_frame;
    write_scores(out, r);
    out << ',' << r.icp_matched_fraction << ',' << (r.accepted() ? "accepted" : r.rejected_by) << '\n';
  }
  return out.str();
}

}  // namespace vilslam::loop
