// `vilslam report` pages in headless Chromium: the page of a real run (a room lap with loop closure and its
// map, measured against the model) renders every plot and the 3D view without a script error; a broken page
// is caught by the same check. With VILSLAM_REPORT_HTML set, a given page is checked and screenshotted
// (scripts/demo does this for the demo's report: docs/img/report.png).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "report/headless_chromium.h"
#include "report/synthetic_run.h"
#include "test_util.h"

namespace vilslam {
namespace {

namespace fs = std::filesystem;

constexpr const char* kWindow = "1400,3050";  // the page with every panel, whole

// The text of the page's #report-status element ("" when there is none).
std::string page_status(const std::string& dom) {
  const std::size_t element = dom.find("id=\"report-status\"");
  if (element == std::string::npos) return {};
  const std::size_t begin = dom.find('>', element) + 1;
  return dom.substr(begin, dom.find('<', begin) - begin);
}

// The page reported success in #report-status, and chromium logged no uncaught error. Returns the status text.
std::string expect_rendered(const test::BrowserPage& page) {
  EXPECT_EQ(page.exit_code, 0) << page.console;
  const std::string status = page_status(page.dom);
  EXPECT_EQ(status.rfind("report-status: ok: ", 0), 0u) << status << "\n" << page.console;
  EXPECT_EQ(page.console.find("Uncaught"), std::string::npos) << page.console;
  return status;
}

void expect_png(const fs::path& path) {
  const std::string png = test::read_file_bytes(path);
  EXPECT_EQ(png.substr(0, 8), "\x89PNG\r\n\x1a\n") << path;
  EXPECT_GT(png.size(), 50'000u) << path;  // a page of plots, not a blank window
}

// The camera of the room lap at half resolution and 10 Hz: the simulation takes a fifth of the default's time
// (9 s instead of 43 s on the loaded 2-core machine), and the lap still closes loops.
constexpr const char* kFastCamera =
    "camera:\n  rate_hz: 10.0\n  width_px: 376\n  height_px: 240\n  fx: 230.0\n  fy: 230.0\n  cx: 187.5\n  cy: 119.5\n";

// A one-lap room run (as tests/pipeline/test_loop_closure_run.cpp: loops need 4 s instead of 30 s of gap).
TEST(ReportBrowser, RunReportRendersEveryPlotAndTheMap) {
  VILSLAM_REQUIRE_CHROMIUM(chromium);
  const fs::path dir = test::temp_dir();
  const std::string data = (dir / "data").string(), run = (dir / "run").string();
  std::ofstream(dir / "fast_camera.yaml") << kFastCamera;
  ASSERT_EQ(test::run_cli("simulate room --length 8 --seed 2 --config " + (dir / "fast_camera.yaml").string() +
                          " --out " + data).exit_code, 0);
  std::ofstream(dir / "short_gap.yaml") << "loop_closure:\n  min_time_gap_s: 4.0\n";
  const test::CliResult r = test::run_cli("run --mode vil " + data + " --config " + (dir / "short_gap.yaml").string() +
                                          " --out " + run);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(test::run_cli("map " + data + " --poses " + run + "/lidar_final.tum --voxel 0.05 --out " +
                          (dir / "map.ply").string()).exit_code, 0);
  const fs::path html = dir / "report.html";
  const test::CliResult rep = test::run_cli("report " + run + " --gt " + data + " --map " + (dir / "map.ply").string() +
                                            " --model " + data + "/model.ply --out " + html.string());
  ASSERT_EQ(rep.exit_code, 0) << rep.output;
  const std::string page = test::read_file_bytes(html);
  EXPECT_NE(page.find("\"loops\": ["), std::string::npos);  // the lap's return closed a loop
  EXPECT_NE(page.find("\"value_name\": \"mre_m\""), std::string::npos);

  const fs::path screenshot = dir / "report.png";
  const std::string status = expect_rendered(test::open_in_chromium(chromium, html, dir / "browser", kWindow, screenshot));
  // 2 path views, 2 error plots (VIO and LiDAR against the ground truth), one histogram per timing series
  // (frontend, smoother, LiDAR mapping, key frame, loop detection, loop correction, the final solve), and the map.
  EXPECT_NE(status.find("ok: 11 plots, map of "), std::string::npos) << status;
  expect_png(screenshot);
}

// The check itself: a page whose data cannot be decoded reports the error instead of "ok".
TEST(ReportBrowser, ScriptErrorIsReported) {
  VILSLAM_REQUIRE_CHROMIUM(chromium);
  const fs::path dir = test::temp_dir();
  test::write_synthetic_run(dir / "run", dir / "gt.tum");
  const fs::path html = dir / "report.html";
  ASSERT_EQ(test::run_cli("report " + (dir / "run").string() + " --gt " + (dir / "gt.tum").string() + " --out " +
                          html.string()).exit_code, 0);
  std::string page = test::read_file_bytes(html);
  const std::size_t at = page.find("\"xyz\": \"");
  ASSERT_NE(at, std::string::npos);
  page.insert(at + 8, "#");  // not base64: atob throws
  std::ofstream(dir / "broken.html") << page;
  const test::BrowserPage broken = test::open_in_chromium(chromium, dir / "broken.html", dir / "broken", kWindow);
  const std::string status = page_status(broken.dom);
  EXPECT_EQ(status.rfind("report-status: error: ", 0), 0u) << status;
  EXPECT_NE(status.find("atob"), std::string::npos) << status;  // the error names what failed
  EXPECT_NE(broken.console.find("Uncaught"), std::string::npos) << broken.console;
}

// A given page (VILSLAM_REPORT_HTML), screenshotted to VILSLAM_REPORT_SCREENSHOT: scripts/demo.
TEST(ReportBrowser, GivenReportRenders) {
  const char* html = std::getenv("VILSLAM_REPORT_HTML");
  const char* screenshot = std::getenv("VILSLAM_REPORT_SCREENSHOT");
  if (html == nullptr || screenshot == nullptr) GTEST_SKIP() << "VILSLAM_REPORT_HTML and VILSLAM_REPORT_SCREENSHOT not set";
  VILSLAM_REQUIRE_CHROMIUM(chromium);
  const std::string status = expect_rendered(test::open_in_chromium(chromium, html, test::temp_dir(), kWindow, screenshot));
  std::printf("%s: %s\n", html, status.c_str());
  expect_png(screenshot);
}

}  // namespace
}  // namespace vilslam
