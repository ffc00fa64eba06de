#pragma once
// A one-line progress report with an ETA for long commands: redrawn in place on a terminal (stderr is a
// TTY), silent otherwise so that logs and captured output stay clean.
#include <cstdio>
#include <functional>
#include <string>

namespace vilslam {

class Progress {
 public:
  using Clock = std::function<double()>;  // seconds, monotonic

  // Reports to stderr when it is a terminal, else nowhere.
  Progress(std::string label, double total);
  // Reports to out (nullptr: nowhere) with the given clock; for tests and callers that choose the stream.
  Progress(std::string label, double total, std::FILE* out, Clock clock);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // done of total; redraws at most every redraw_interval_s. Values outside [0, total] are clamped.
  void update(double done);
  // Clears the line (called by the destructor too).
  void finish();

  // "LABEL  45% 0:12 elapsed, ETA 0:15" (ETA from the mean rate so far; "ETA --" before any progress).
  static std::string line(const std::string& label, double fraction, double elapsed_s);

  static constexpr double redraw_interval_s = 0.25;

 private:
  std::string label_;
  double total_;
  std::FILE* out_;
  Clock clock_;
  double start_s_;
  double last_draw_s_;
  bool drawn_ = false;
};

}  // namespace vilslam
