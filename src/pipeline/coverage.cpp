#include "pipeline/coverage.h"

#include "lidar/mapping_status.h"

namespace vilslam {

RunCoverage run_coverage(const OfflineRunResult& r) {
  RunCoverage c;
  std::vector<TimeNs> t_ns;
  std::vector<bool> tracking;
  for (const VioStatusRecord& s : r.vio_status) {
    if (s.loss != VioLoss::kNone) continue;  // a loss event, not a state
    t_ns.push_back(s.t_ns);
    tracking.push_back(s.status == VioStatus::kTracking);
  }
  if (!t_ns.empty()) c.vio = coverage_of(t_ns, tracking, r.data_s);
  t_ns.clear();
  tracking.clear();
  for (const lidar::LidarMappingResult& m : r.lidar) {
    t_ns.push_back(m.t_ns);
    const lidar::MappingStatus status = lidar::mapping_status(m);
    // Continuous with the poses before (a registration at its iteration limit still follows the motion).
    tracking.push_back(status != lidar::MappingStatus::kAfterGap && status != lidar::MappingStatus::kReanchored);
  }
  if (!t_ns.empty()) c.lidar = coverage_of(t_ns, tracking, r.data_s);
  return c;
}

}  // namespace vilslam
