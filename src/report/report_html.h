#pragma once
// The report page: one self-contained HTML file with the plotting libraries (Chart.js, three.js), the page's
// style and script, and the data inline; it opens offline (docs/report.md).
#include <string>

namespace vilslam::report {

// data_json: report_json's output. The page fills itself from it when opened.
std::string report_html(const std::string& data_json);

}  // namespace vilslam::report
