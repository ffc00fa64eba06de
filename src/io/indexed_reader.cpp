// The one DatasetReader implementation: time-merges the index's streams, loads payloads on demand.
#include "io/dataset_index.h"
#include "io/event_merge.h"

namespace vilslam {
namespace {

// Stream ids in tie order: IMU, ground truth, stereo, LiDAR (dataset.h).
enum Stream : std::size_t { kImu, kGroundTruth, kStereo, kLidar };

class IndexedReader : public DatasetReader {
 public:
  explicit IndexedReader(DatasetIndex index) : index_(std::move(index)) {
    merge_.add_stream(times_of(index_.imu));
    merge_.add_stream(times_of(index_.groundtruth));
    merge_.add_stream(times_of(index_.stereo));
    merge_.add_stream(times_of(index_.scans));
  }

  std::optional<SensorEvent> next() override {
    const auto item = merge_.next();
    if (!item) return std::nullopt;
    const auto [stream, i] = *item;
    SensorEvent event;
    switch (stream) {
      case kImu: event.data = index_.imu[i]; break;
      case kGroundTruth: event.data = index_.groundtruth[i]; break;
      case kStereo: event.data = load_stereo(index_, i); break;
      default: event.data = load_scan(index_, i); break;
    }
    event.t_ns = std::visit([](const auto& d) { return d.t_ns; }, event.data);
    return event;
  }

  void rewind() override { merge_.rewind(); }
  const RigCalibration& calibration() const override { return index_.calibration; }
  const DatasetSummary& summary() const override { return index_.summary; }
  const std::vector<GroundTruthState>& groundtruth() const override { return index_.groundtruth; }
  std::string reference_model_path() const override { return index_.reference_model_path; }

 private:
  DatasetIndex index_;
  EventMerge merge_;
};

}  // namespace

std::unique_ptr<DatasetReader> open_indexed(DatasetIndex index) {
  return std::make_unique<IndexedReader>(std::move(index));
}

}  // namespace vilslam
