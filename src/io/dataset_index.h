#pragma once
// What every dataset reader builds up front: calibration, the small streams (IMU, ground truth) in
// memory, and an index of payload files (stereo images, scans) that are loaded only when returned.
// One reader class (open_indexed) serves every layout; the layouts differ only in how they index.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/dataset.h"

namespace vilslam {

struct StereoEntry {
  TimeNs t_ns = 0;
  std::string left_path;
  std::string right_path;
};

enum class ScanEncoding { kVilslam, kKitti };

struct ScanEntry {
  TimeNs t_ns = 0;
  std::string path;
  long num_points = -1;  // from the index file when it lists one, else -1
};

// Payloads kept inside one container file (a ROS bag) instead of a file each: entry i of the index's
// stereo (scans) list is loaded by stereo(i) (scan(i)). Entry paths then only describe the source.
class PayloadStore {
 public:
  virtual ~PayloadStore() = default;
  virtual StereoFrame stereo(std::size_t i) = 0;
  virtual LidarScan scan(std::size_t i) = 0;
};

struct DatasetIndex {
  DatasetSummary summary;  // format, path and problems found while indexing; the rest by finalize_summary
  RigCalibration calibration;
  bool has_cameras = false;
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> groundtruth;
  std::vector<StereoEntry> stereo;
  std::vector<ScanEntry> scans;
  ScanEncoding scan_encoding = ScanEncoding::kVilslam;
  std::string reference_model_path;
  std::shared_ptr<PayloadStore> store;  // null: payloads are the files the entries name
};

template <typename T>
std::vector<TimeNs> times_of(const std::vector<T>& items) {
  std::vector<TimeNs> t;
  t.reserve(items.size());
  for (const T& item : items) t.push_back(item.t_ns);
  return t;
}

// The layouts (each throws InputError naming the file at fault).
DatasetIndex index_euroc(const std::string& root);
DatasetIndex index_vilslam(const std::string& root);
DatasetIndex index_kitti(const std::string& root);
DatasetIndex index_rosbag(const std::string& bag_path, const DatasetOptions& options);
// Detects the layout of root and indexes it, summary finalized.
DatasetIndex index_dataset(const std::string& root, const DatasetOptions& options = {});

// Counts, time span, rates (from the median period) and gaps (> 1.5 nominal periods) into summary.
void finalize_summary(DatasetIndex& index);

// The reader over an index: merges the streams in time order and loads payloads lazily.
std::unique_ptr<DatasetReader> open_indexed(DatasetIndex index);

// Payload access shared by the reader and `vilslam info`.
StereoFrame load_stereo(const StereoEntry& entry);
LidarScan load_scan(const ScanEntry& entry, ScanEncoding encoding);
// Entry i of the index, from its store when it has one.
StereoFrame load_stereo(const DatasetIndex& index, std::size_t i);
LidarScan load_scan(const DatasetIndex& index, std::size_t i);
// (width, height) of a PNG from its header; InputError unless signature, IHDR and IEND are in place.
std::pair<int, int> png_size(const std::string& path);
// Cheap validation of every payload (PNG signature, IHDR and IEND, image size against the calibration;
// scan header against file size and the listed point count; a store's payloads were checked when it was
// indexed). deep: decode every payload instead.
// Throws InputError naming the first bad file.
void check_payloads(const DatasetIndex& index, bool deep);

}  // namespace vilslam
