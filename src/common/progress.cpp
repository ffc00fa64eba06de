#include "common/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace vilslam {
namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string minutes_seconds(double s) {
  const long total = std::lround(std::max(0.0, s));
  char text[32];
  std::snprintf(text, sizeof text, "%ld:%02ld", total / 60, total % 60);
  return text;
}

}  // namespace

Progress::Progress(std::string label, double total)
    : Progress(std::move(label), total, isatty(fileno(stderr)) ? stderr : nullptr, steady_seconds) {}

Progress::Progress(std::string label, double total, std::FILE* out, Clock clock)
    : label_(std::move(label)), total_(total), out_(out), clock_(std::move(clock)), start_s_(clock_()),
      last_draw_s_(start_s_ - redraw_interval_s) {}

Progress::~Progress() { finish(); }

std::string Progress::line(const std::string& label, double fraction, double elapsed_s) {
  fraction = std::clamp(fraction, 0.0, 1.0);
  char percent[16];
  std::snprintf(percent, sizeof percent, "%3d%%", static_cast<int>(std::floor(100.0 * fraction)));
  const std::string eta = fraction > 0.0 ? minutes_seconds(elapsed_s * (1.0 - fraction) / fraction) : "--";
  return label + " " + percent + " " + minutes_seconds(elapsed_s) + " elapsed, ETA " + eta;
}

void Progress::update(double done) {
  if (out_ == nullptr) return;
  const double now_s = clock_();
  if (now_s - last_draw_s_ < redraw_interval_s) return;
  last_draw_s_ = now_s;
  const double fraction = total_ > 0.0 ? done / total_ : 1.0;
  // \r and erase-to-end-of-line redraw the same terminal line.
  std::fprintf(out_, "\r%s\033[K", line(label_, fraction, now_s - start_s_).c_str());
  std::fflush(out_);
  drawn_ = true;
}

void Progress::finish() {
  if (out_ == nullptr || !drawn_) return;
  std::fprintf(out_, "\r\033[K");
  std::fflush(out_);
  drawn_ = false;
}

}  // namespace vilslam
