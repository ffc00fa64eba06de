#pragma once
// The real-time mode of `vilslam run --realtime SPEED`: the dataset's events are released on the wall clock at
// their sensor times (SPEED times faster), as a live robot's drivers would deliver them, and the run measures
// how long after its measurement each output is published. When a module falls behind, the overload policy
// (docs/pipeline.md, "Real-time mode") drops new stereo pairs and sweeps, never IMU samples.
#include <atomic>
#include <chrono>
#include <cstddef>

#include "common/time.h"

namespace vilslam {

struct RealtimeConfig {
  double speed = 0.0;                  // > 0: real-time mode at this speed; 0: offline, as fast as possible
  std::size_t max_frames_waiting = 3;  // a stereo pair arriving while this many wait for the smoother is dropped
  std::size_t max_sweeps_waiting = 2;  // a sweep arriving while this many wait to be mapped is dropped
  // Messages each module's queue holds before the reader would wait (offline: 256, stage.h). At 3x the LiDAR side gets
  // 600 pose updates a second; a loop correction with its map rebuild must not stall the reader behind them.
  std::size_t queue_capacity = 16384;
};

// Maps sensor time to wall time from the first event on: wall(t) = start + (t - t_first) / speed.
class SensorClock {
 public:
  using Clock = std::chrono::steady_clock;

  // Throws std::invalid_argument unless speed > 0. The clock starts now.
  SensorClock(TimeNs first_t_ns, double speed);
  // The first event is due now.
  void restart() { start_ = Clock::now(); }

  // Sleeps until the sensor instant t_ns is due; returns how late it already was, in ms (0 when on time).
  double wait_until(TimeNs t_ns) const;
  // Wall time since the sensor instant t_ns was due, in ms: an output's latency when t_ns is its measurement's time.
  double since_ms(TimeNs t_ns) const;

 private:
  Clock::time_point due(TimeNs t_ns) const;

  TimeNs first_t_ns_;
  double speed_;
  Clock::time_point start_;
};

// The overload policy for one kind of arrival (stereo pairs or sweeps): admitted while fewer than max_waiting
// of them wait in the pipeline. admit() runs on the reader's thread, done() on the module's that handled them.
class ArrivalGate {
 public:
  explicit ArrivalGate(std::size_t max_waiting) : max_waiting_(max_waiting) {}

  // false (and one more dropped) when max_waiting already wait.
  bool admit() {
    if (waiting_ >= max_waiting_) {
      ++dropped_;
      return false;
    }
    ++waiting_;
    return true;
  }
  void done(std::size_t count = 1) { waiting_ -= count; }
  std::size_t dropped() const { return dropped_; }

 private:
  std::size_t max_waiting_;
  std::atomic<std::size_t> waiting_{0};
  std::size_t dropped_ = 0;  // the reader's thread only
};

// Stereo pairs and sweeps in the pipeline: released by the reader, not yet handled by the smoother (pairs) or
// the mapper (sweeps).
struct PipelineLoad {
  explicit PipelineLoad(const RealtimeConfig& config)
      : frames(config.max_frames_waiting), sweeps(config.max_sweeps_waiting) {}
  ArrivalGate frames;
  ArrivalGate sweeps;
};

}  // namespace vilslam
