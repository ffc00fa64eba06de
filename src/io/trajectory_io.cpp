// Trajectory format names, format detection and writing (atomically, through write_file_atomic).
#include "io/trajectory_io.h"

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/error.h"
#include "common/json_writer.h"
#include "io/csv.h"

namespace vilslam {
namespace {

// Shortest text that reads back to the same double.
std::string exact(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Seconds with exactly 9 decimals, formatted from the integer so no precision is lost.
std::string seconds_text(TimeNs t_ns) {
  const bool negative = t_ns < 0;
  const unsigned long long mag = negative ? 0ULL - static_cast<unsigned long long>(t_ns) : t_ns;
  char buf[40];
  std::snprintf(buf, sizeof buf, "%s%llu.%09llu", negative ? "-" : "", mag / 1000000000ULL, mag % 1000000000ULL);
  return buf;
}

void write_rows(std::ostream& out, const Trajectory& traj, TrajectoryFormat format) {
  switch (format) {
    case TrajectoryFormat::kTum:
      out << "# timestamp[s] tx ty tz qx qy qz qw\n";
      for (const TimedPose& p : traj) {
        const Vec3& t = p.T_W_B.translation();
        const Quat& q = p.T_W_B.quat();
        out << seconds_text(p.t_ns) << ' ' << exact(t.x()) << ' ' << exact(t.y()) << ' ' << exact(t.z()) << ' '
            << exact(q.x()) << ' ' << exact(q.y()) << ' ' << exact(q.z()) << ' ' << exact(q.w()) << '\n';
      }
      return;
    case TrajectoryFormat::kKitti:
      for (const TimedPose& p : traj) {
        const Mat4 T = p.T_W_B.matrix();
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 4; ++c) out << (r + c > 0 ? " " : "") << exact(T(r, c));
        }
        out << '\n';
      }
      return;
    case TrajectoryFormat::kEuroc:
      out << "#timestamp [ns],p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],q_RS_z []\n";
      for (const TimedPose& p : traj) {
        const Vec3& t = p.T_W_B.translation();
        const Quat& q = p.T_W_B.quat();
        out << p.t_ns << ',' << exact(t.x()) << ',' << exact(t.y()) << ',' << exact(t.z()) << ',' << exact(q.w())
            << ',' << exact(q.x()) << ',' << exact(q.y()) << ',' << exact(q.z()) << '\n';
      }
      return;
  }
}

}  // namespace

TrajectoryFormat parse_trajectory_format(const std::string& name) {
  if (name == "tum") return TrajectoryFormat::kTum;
  if (name == "kitti") return TrajectoryFormat::kKitti;
  if (name == "euroc") return TrajectoryFormat::kEuroc;
  throw std::invalid_argument("unknown trajectory format '" + name + "' (tum, kitti or euroc)");
}

TrajectoryFormat detect_trajectory_format(const std::string& path) {
  if (std::filesystem::path(path).extension() == ".csv") return TrajectoryFormat::kEuroc;
  const Table table(path, ' ', 1);
  if (table.rows().empty()) throw InputError(path, "no data rows to tell the trajectory format from");
  const TableRow& first = table.rows().front();
  if (first.fields.front().find(',') != std::string::npos) return TrajectoryFormat::kEuroc;
  if (first.fields.size() == 8) return TrajectoryFormat::kTum;
  if (first.fields.size() == 12) return TrajectoryFormat::kKitti;
  throw InputError(path, "cannot tell the trajectory format from " + std::to_string(first.fields.size()) + " columns",
                   first.line);
}

void write_trajectory(const std::string& path, const Trajectory& traj, TrajectoryFormat format) {
  std::ostringstream out;
  write_rows(out, traj, format);
  try {
    write_file_atomic(path, out.str());
  } catch (const std::runtime_error& e) {
    throw InputError(path, e.what());
  }
}

}  // namespace vilslam
