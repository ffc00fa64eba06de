#include "report/report_html.h"

#include <string_view>

#include "report/embedded_assets.h"

namespace vilslam::report {
namespace {

// Text inside <script> ends at the first "</script": "</" in the data becomes "<\/" (the same string in
// JSON). The embedded scripts are checked at build time instead (cmake/embed_text.cmake).
std::string escape_script_end(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    out += json[i];
    if (json[i] == '<' && i + 1 < json.size() && json[i + 1] == '/') out += '\\';
  }
  return out;
}

void append_script(std::string& html, std::string_view code) {
  html += "<script>\n";
  html += code;
  html += "\n</script>\n";
}

}  // namespace

std::string report_html(const std::string& data_json) {
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>vilslam report</title>\n<style>\n";
  html += embedded::report_css();
  html += "</style>\n";
  // Errors of any later script are caught from here on and shown in #report-status (the browser test reads it).
  append_script(html,
                "window.reportErrors = [];\n"
                "window.addEventListener('error', function (e) {\n"
                "  window.reportErrors.push(String(e.message || e.type));\n"
                "  var s = document.getElementById('report-status');\n"
                "  if (s) { s.textContent = 'report-status: error: ' + window.reportErrors.join('; '); s.className = 'error'; }\n"
                "});");
  append_script(html, embedded::chart_js());
  append_script(html, embedded::three_js());
  append_script(html, embedded::three_orbit_controls_js());
  html += "</head>\n<body>\n<div id=\"report\"></div>\n<p id=\"report-status\" class=\"pending\">report-status: pending</p>\n";
  html += "<script type=\"application/json\" id=\"report-data\">\n";
  html += escape_script_end(data_json);
  html += "</script>\n";
  append_script(html, embedded::report_js());
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace vilslam::report
