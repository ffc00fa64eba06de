#include "pipeline/run_status.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "lidar/mapping_status.h"

namespace vilslam {

std::string vio_status_csv(const std::vector<VioStatusRecord>& states) {
  std::ostringstream out;
  out << std::setprecision(17) << "t_ns,status,frame_matches,landmarks,imu_gap_s\n";
  for (const VioStatusRecord& s : states) {
    out << s.t_ns << ',' << vio_status_name(s) << ',' << s.frame_matches << ',' << s.landmarks << ','
        << s.imu_gap_s << '\n';
  }
  return out.str();
}

namespace {

// Pointers to the mapped and the rejected sweeps, in time order (a segment's sweeps after a reset come later).
std::vector<const lidar::LidarMappingResult*> in_time_order(const std::vector<lidar::LidarMappingResult>& sweeps,
                                                            const std::vector<lidar::LidarMappingResult>& rejected) {
  std::vector<const lidar::LidarMappingResult*> all;
  for (const auto& m : sweeps) all.push_back(&m);
  for (const auto& m : rejected) all.push_back(&m);
  std::stable_sort(all.begin(), all.end(), [](const auto* a, const auto* b) { return a->t_ns < b->t_ns; });
  return all;
}

void add_record(std::vector<StatusStretch>& stretches, const std::string& module, const std::string& status,
                TimeNs t_ns, double gap_s, double join_s) {
  for (auto it = stretches.rbegin(); it != stretches.rend() && it->module == module; ++it) {
    if (it->status != status) continue;
    if (ns_to_s(t_ns - it->end_t_ns) < join_s) {
      it->end_t_ns = t_ns;
      ++it->count;
      it->gap_s += gap_s;
      return;
    }
    break;
  }
  stretches.push_back({module, status, t_ns, t_ns, 1, gap_s});
}

}  // namespace

std::string lidar_status_csv(const std::vector<lidar::LidarMappingResult>& sweeps,
                             const std::vector<lidar::LidarMappingResult>& rejected) {
  std::ostringstream out;
  out << std::setprecision(17) << "t_ns,status,gap_s,vio_prior,converged,correction_m,correction_deg,degenerate\n";
  for (const lidar::LidarMappingResult* sweep : in_time_order(sweeps, rejected)) {
    const lidar::LidarMappingResult& m = *sweep;
    out << m.t_ns << ',' << lidar::mapping_status_name(lidar::mapping_status(m)) << ',' << m.gap_s << ','
        << (m.vio_prior ? 1 : 0) << ',' << (m.converged ? 1 : 0) << ',' << m.correction_m << ',' << m.correction_deg
        << ',' << (m.degenerate ? 1 : 0) << '\n';
  }
  return out.str();
}

std::vector<StatusStretch> status_stretches(const OfflineRunResult& run, double join_s) {
  std::vector<StatusStretch> stretches;
  for (const VioStatusRecord& s : run.vio_status) {
    if (s.status == VioStatus::kTracking) continue;
    add_record(stretches, "vio", vio_status_name(s), s.t_ns, s.imu_gap_s, join_s);
  }
  for (const lidar::LidarMappingResult* m : in_time_order(run.lidar, run.lidar_rejected)) {
    const lidar::MappingStatus status = lidar::mapping_status(*m);
    if (status == lidar::MappingStatus::kOk || status == lidar::MappingStatus::kDegenerate) continue;
    add_record(stretches, "lidar", lidar::mapping_status_name(status), m->t_ns, m->gap_s, join_s);
  }
  return stretches;
}

}  // namespace vilslam
