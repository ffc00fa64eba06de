// DatasetSummary from an index: counts, time span, rates and gaps.
#include <algorithm>
#include <cstdio>
#include <limits>

#include "io/dataset_index.h"

namespace vilslam {
namespace {

constexpr double kGapPeriods = 1.5;     // a step longer than this many nominal periods is a gap
constexpr std::size_t kMaxGapsListed = 10;

// Median step between consecutive times (0 with fewer than two).
TimeNs median_period_ns(const std::vector<TimeNs>& t) {
  if (t.size() < 2) return 0;
  std::vector<TimeNs> dt(t.size() - 1);
  for (std::size_t i = 1; i < t.size(); ++i) dt[i - 1] = t[i] - t[i - 1];
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  return dt[dt.size() / 2];
}

// Rate from the median period; lists gaps (> 1.5 nominal periods) as problems. The nominal rate is the
// calibration's when it has one, else the measured one.
double rate_and_gaps(const std::string& stream, const std::vector<TimeNs>& t, double nominal_rate_hz,
                     std::vector<std::string>& problems) {
  const TimeNs median = median_period_ns(t);
  if (median <= 0) return 0;
  const double rate_hz = 1e9 / static_cast<double>(median);
  const double period_ns = 1e9 / (nominal_rate_hz > 0 ? nominal_rate_hz : rate_hz);
  std::size_t gaps = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double dt = static_cast<double>(t[i] - t[i - 1]);
    if (dt <= kGapPeriods * period_ns) continue;
    if (++gaps <= kMaxGapsListed) {
      char msg[200];
      std::snprintf(msg, sizeof msg, "%s: gap of %.3f s (%.1f periods) after t_ns=%lld", stream.c_str(), dt * 1e-9,
                    dt / period_ns, static_cast<long long>(t[i - 1]));
      problems.emplace_back(msg);
    }
  }
  if (gaps > kMaxGapsListed) {
    problems.push_back(stream + ": " + std::to_string(gaps - kMaxGapsListed) + " more gaps not listed");
  }
  return rate_hz;
}

}  // namespace

void finalize_summary(DatasetIndex& index) {
  DatasetSummary& s = index.summary;
  s.stereo_frames = index.stereo.size();
  s.imu_samples = index.imu.size();
  s.lidar_scans = index.scans.size();
  s.groundtruth_poses = index.groundtruth.size();
  const std::vector<std::vector<TimeNs>> streams = {times_of(index.imu), times_of(index.groundtruth),
                                                    times_of(index.stereo), times_of(index.scans)};
  TimeNs start = std::numeric_limits<TimeNs>::max();
  TimeNs end = std::numeric_limits<TimeNs>::min();
  for (const auto& t : streams) {
    if (t.empty()) continue;
    start = std::min(start, t.front());
    end = std::max(end, t.back());
  }
  s.start_t_ns = start <= end ? start : 0;
  s.end_t_ns = start <= end ? end : 0;
  const RigCalibration& c = index.calibration;
  s.imu_rate_hz = rate_and_gaps("imu0", streams[0], c.imu.rate_hz, s.problems);
  s.camera_rate_hz = rate_and_gaps("stereo", streams[2], c.cam0.rate_hz, s.problems);
  s.lidar_rate_hz = rate_and_gaps("lidar0", streams[3], c.has_lidar ? c.lidar.rate_hz : 0.0, s.problems);
}

}  // namespace vilslam
