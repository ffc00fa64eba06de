#pragma once
// How much of a run each module covered (issue 60, common/coverage.h): the fraction of the data's time span with a
// published pose, and the fraction with a pose made while the module was tracking.
#include <optional>
#include <vector>

#include "common/coverage.h"
#include "pipeline/run_types.h"

namespace vilslam {

struct RunCoverage {
  std::optional<Coverage> vio;    // camera-rate states (vio_status.csv): tracking = "tracking"
  std::optional<Coverage> lidar;  // mapped sweeps (lidar_status.csv): tracking = registered, not after a gap or re-anchored
};

// Of the run's modules that ran, over its data span (r.data_s).
RunCoverage run_coverage(const OfflineRunResult& r);

}  // namespace vilslam
