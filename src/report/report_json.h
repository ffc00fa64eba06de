#pragma once
// The report's data as the JSON the page's script reads (src/report/assets/report.js): keys in a fixed
// order and big arrays as base64 float32 (report/base64.h), so the same inputs give the same bytes.
#include <string>

#include "report/report_data.h"

namespace vilslam::report {

std::string report_json(const ReportData& data, const ReportOptions& options);

}  // namespace vilslam::report
