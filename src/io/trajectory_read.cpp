// Reading TUM, KITTI and EuRoC trajectory files with line-accurate InputErrors.
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "common/error.h"
#include "io/trajectory_io.h"

namespace vilslam {
namespace {

constexpr double kQuatNormTolerance = 1e-3;      // |q| must be 1 within this (files print 4+ decimals)
constexpr double kRotationOrthoTolerance = 1e-3;  // max |R^T R - I| and |det R - 1| for KITTI rows

struct Row {
  long line = 0;
  std::vector<std::string> tokens;
};

// Non-empty, non-comment rows of a file, split on whitespace (and commas when comma_separated).
std::vector<Row> read_rows(const std::string& path, bool comma_separated) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open file");
  std::vector<Row> rows;
  std::string text;
  long line = 0;
  while (std::getline(in, text)) {
    ++line;
    Row row{line, {}};
    std::string token;
    for (char c : text) {
      const bool space = c == ' ' || c == '\t' || c == '\r';
      if (comma_separated ? c == ',' : (space && !token.empty())) {
        row.tokens.push_back(token);
        token.clear();
      } else if (!space) {
        token.push_back(c);
      }
    }
    if (!token.empty() || (comma_separated && !row.tokens.empty())) row.tokens.push_back(token);
    if (row.tokens.empty() || row.tokens.front().front() == '#') continue;
    rows.push_back(std::move(row));
  }
  if (in.bad()) throw InputError(path, "read error");
  return rows;
}

double parse_double(const std::string& token, const std::string& path, long line) {
  if (token.empty()) throw InputError(path, "empty field", line);
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size()) throw InputError(path, "not a number: '" + token + "'", line);
  if (!std::isfinite(value) || errno == ERANGE) throw InputError(path, "non-finite value: '" + token + "'", line);
  return value;
}

// Decimal seconds ("1403715529.112143517", "1.4e9", "-0.5") to nanoseconds without going through a
// double, so that 19-digit timestamps survive exactly; rounds half away from zero at the ns digit.
TimeNs parse_seconds_ns(const std::string& token, const std::string& path, long line) {
  const auto bad = [&]() { return InputError(path, "not a time in seconds: '" + token + "'", line); };
  std::size_t i = 0;
  bool negative = false;
  if (i < token.size() && (token[i] == '+' || token[i] == '-')) negative = token[i++] == '-';
  std::string digits;
  long int_digits = 0;
  bool seen_dot = false;
  for (; i < token.size() && (std::isdigit(static_cast<unsigned char>(token[i])) || token[i] == '.'); ++i) {
    if (token[i] == '.') {
      if (seen_dot) throw bad();
      seen_dot = true;
    } else {
      digits.push_back(token[i]);
      if (!seen_dot) ++int_digits;
    }
  }
  if (digits.empty()) throw bad();
  if (i < token.size()) {
    if (token[i] != 'e' && token[i] != 'E') throw bad();
    const std::string exponent = token.substr(i + 1);
    char* end = nullptr;
    const long e = std::strtol(exponent.c_str(), &end, 10);
    if (exponent.empty() || end != exponent.c_str() + exponent.size() || std::labs(e) > 30) throw bad();
    int_digits += e;
  }
  const long ns_digits = int_digits + 9;  // digits of the result before the rounding position
  TimeNs ns = 0;
  for (long k = 0; k < ns_digits; ++k) {
    const int d = k >= 0 && k < static_cast<long>(digits.size()) ? digits[k] - '0' : 0;
    if (ns > (INT64_MAX - d) / 10) throw InputError(path, "time out of range: '" + token + "'", line);
    ns = ns * 10 + d;
  }
  if (ns_digits >= 0 && ns_digits < static_cast<long>(digits.size()) && digits[ns_digits] >= '5') ++ns;
  return negative ? -ns : ns;
}

TimeNs parse_int_ns(const std::string& token, const std::string& path, long line) {
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(token.c_str(), &end, 10);
  if (token.empty() || end != token.c_str() + token.size() || errno == ERANGE) {
    throw InputError(path, "not an integer timestamp in ns: '" + token + "'", line);
  }
  return static_cast<TimeNs>(value);
}

void require_columns(const Row& row, const std::string& path, const std::string& expected, bool ok) {
  if (!ok) {
    throw InputError(path, "expected " + expected + " columns, found " + std::to_string(row.tokens.size()), row.line);
  }
}

SE3 pose_from_quaternion(const Vec3& t, double w, double x, double y, double z, const std::string& path, long line) {
  const double norm = std::sqrt(w * w + x * x + y * y + z * z);
  if (std::abs(norm - 1.0) > kQuatNormTolerance) {
    throw InputError(path, "quaternion is not unit (|q| = " + std::to_string(norm) + ")", line);
  }
  return SE3(Quat(w, x, y, z), t);
}

void require_increasing(const Trajectory& traj, const std::string& path, long line) {
  if (traj.size() >= 2 && traj.back().t_ns <= traj[traj.size() - 2].t_ns) {
    throw InputError(path, "timestamp not strictly increasing", line);
  }
}

Trajectory read_tum(const std::string& path) {
  Trajectory traj;
  for (const Row& row : read_rows(path, false)) {
    require_columns(row, path, "8 (t x y z qx qy qz qw)", row.tokens.size() == 8);
    double v[8];
    for (int k = 1; k < 8; ++k) v[k] = parse_double(row.tokens[k], path, row.line);
    const TimeNs t_ns = parse_seconds_ns(row.tokens[0], path, row.line);
    traj.push_back({t_ns, pose_from_quaternion(Vec3(v[1], v[2], v[3]), v[7], v[4], v[5], v[6], path, row.line)});
    require_increasing(traj, path, row.line);
  }
  return traj;
}

Trajectory read_euroc(const std::string& path) {
  Trajectory traj;
  for (const Row& row : read_rows(path, true)) {
    const std::size_t n = row.tokens.size();
    require_columns(row, path, "8, 11, 14 or 17 (t, p, q_wxyz[, v, b_w, b_a])", n >= 8 && n <= 17 && (n - 8) % 3 == 0);
    double v[17];
    for (std::size_t k = 1; k < n; ++k) v[k] = parse_double(row.tokens[k], path, row.line);
    const TimeNs t_ns = parse_int_ns(row.tokens[0], path, row.line);
    traj.push_back({t_ns, pose_from_quaternion(Vec3(v[1], v[2], v[3]), v[4], v[5], v[6], v[7], path, row.line)});
    require_increasing(traj, path, row.line);
  }
  return traj;
}

std::vector<TimeNs> read_times(const std::string& path) {
  std::vector<TimeNs> times;
  for (const Row& row : read_rows(path, false)) {
    require_columns(row, path, "1 (t in seconds)", row.tokens.size() == 1);
    times.push_back(parse_seconds_ns(row.tokens[0], path, row.line));
    if (times.size() >= 2 && times.back() <= times[times.size() - 2]) {
      throw InputError(path, "timestamp not strictly increasing", row.line);
    }
  }
  return times;
}

Trajectory read_kitti(const std::string& path, const std::string& times_path) {
  const std::vector<Row> rows = read_rows(path, false);
  std::vector<TimeNs> times;
  if (!times_path.empty()) {
    times = read_times(times_path);
    if (times.size() != rows.size()) {
      throw InputError(times_path, std::to_string(times.size()) + " times for " + std::to_string(rows.size()) +
                                       " poses in " + path);
    }
  }
  Trajectory traj;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& row = rows[i];
    require_columns(row, path, "12 (3x4 row-major)", row.tokens.size() == 12);
    Mat3 R;
    Vec3 t;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) R(r, c) = parse_double(row.tokens[4 * r + c], path, row.line);
      t(r) = parse_double(row.tokens[4 * r + 3], path, row.line);
    }
    if (so3::orthonormality_error(R) > kRotationOrthoTolerance) {
      throw InputError(path, "rotation is not orthonormal", row.line);
    }
    const TimeNs t_ns = times.empty() ? static_cast<TimeNs>(i) * kNsPerSecond : times[i];
    traj.push_back({t_ns, SE3(R, t)});
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
