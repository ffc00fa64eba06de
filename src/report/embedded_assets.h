#pragma once
// Text files compiled into the report module at build time (cmake/modules.cmake vilslam_embed_text).
#include <string_view>

namespace vilslam::embedded {

std::string_view chart_js();                 // Debian libjs-chart.js: chart.min.js
std::string_view three_js();                 // Debian libjs-three: three.min.js
std::string_view three_orbit_controls_js();  // Debian libjs-three: examples/js/controls/OrbitControls.js
std::string_view report_js();                // src/report/assets/report.js
std::string_view report_css();               // src/report/assets/report.css

}  // namespace vilslam::embedded
