#pragma once
// Opening a page in headless Chromium (Debian `chromium`, scripts/setup) for the report's browser test: the
// DOM after the page's scripts ran, its console log, and a screenshot.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "test_util.h"

namespace vilslam::test {

// The chromium executable, or "" when it is not installed.
inline std::string find_chromium() {
  for (const char* path : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (std::filesystem::exists(path)) return path;
  }
  return {};
}

// Binds var to the chromium executable; without it the test fails under CI and skips elsewhere.
#define VILSLAM_REQUIRE_CHROMIUM(var)                                                         \
  const std::string var = ::vilslam::test::find_chromium();                                   \
  if (var.empty()) {                                                                          \
    if (::vilslam::test::under_ci()) FAIL() << "chromium is not installed (scripts/setup)";  \
    GTEST_SKIP() << "chromium is not installed (scripts/setup installs it)";                 \
  }

struct BrowserPage {
  int exit_code = -1;
  std::string dom;      // --dump-dom: the document after its scripts ran
  std::string console;  // chromium's log (stderr), with the page's console messages and uncaught errors
};

// Software WebGL (SwiftShader) stands in for the GPU that headless machines lack. The page builds itself
// in one synchronous script, so the DOM and the screenshot, taken after the load event, show it complete.
inline std::string chromium_command(const std::string& chromium, const std::filesystem::path& profile,
                                    const std::string& window_size, const std::string& action) {
  return chromium + " --headless=new --no-sandbox --disable-gpu --use-angle=swiftshader --enable-unsafe-swiftshader" +
         " --disable-dev-shm-usage --no-first-run --hide-scrollbars --user-data-dir=" + profile.string() +
         " --enable-logging=stderr --v=0 --window-size=" + window_size + " " + action;
}

// Opens html_path once and returns its DOM and log; with a screenshot path, also writes a PNG of the window
// (window_size "W,H" pixels).
inline BrowserPage open_in_chromium(const std::string& chromium, const std::filesystem::path& html_path,
                                    const std::filesystem::path& work_dir, const std::string& window_size,
                                    const std::filesystem::path& screenshot = {}) {
  std::filesystem::create_directories(work_dir);
  const std::string url = "file://" + std::filesystem::absolute(html_path).string();
  const std::filesystem::path dom = work_dir / "dom.html", log = work_dir / "chromium.log";
  const std::string shot = screenshot.empty() ? "" : "--screenshot=" + std::filesystem::absolute(screenshot).string() + " ";
  const std::string command = chromium_command(chromium, work_dir / "profile", window_size, shot + "--dump-dom " + url) +
                              " > " + dom.string() + " 2> " + log.string();
  const int status = std::system(command.c_str());
  BrowserPage page;
  page.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  page.dom = read_file_bytes(dom);
  page.console = read_file_bytes(log);
  return page;
}

}  // namespace vilslam::test
