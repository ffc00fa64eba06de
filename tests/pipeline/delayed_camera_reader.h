#pragma once
// A dataset with every stereo pair stamped delay_ns late (as a camera driver with an unknown latency): the
// calibration's t_imu = t_cam + offset then needs offset = -delay_ns.
#include <memory>
#include <utility>
#include <variant>

#include "io/dataset.h"

namespace vilslam::test {

class DelayedCameraReader : public DatasetReader {
 public:
  DelayedCameraReader(std::unique_ptr<DatasetReader> inner, TimeNs delay_ns)
      : inner_(std::move(inner)), delay_ns_(delay_ns) {}
  std::optional<SensorEvent> next() override {
    std::optional<SensorEvent> event = inner_->next();
    if (event && std::holds_alternative<StereoFrame>(event->data)) {
      event->t_ns += delay_ns_;
      std::get<StereoFrame>(event->data).t_ns += delay_ns_;
    }
    return event;
  }
  void rewind() override { inner_->rewind(); }
  const RigCalibration& calibration() const override { return inner_->calibration(); }
  const DatasetSummary& summary() const override { return inner_->summary(); }
  const std::vector<GroundTruthState>& groundtruth() const override { return inner_->groundtruth(); }

 private:
  std::unique_ptr<DatasetReader> inner_;
  TimeNs delay_ns_;
};

}  // namespace vilslam::test
