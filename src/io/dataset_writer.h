#pragma once
// Writes a dataset in the project's own folder format (docs/formats.md), streaming: payloads go to disk
// as they are added. Everything is written under "<root>.partial" and renamed to <root> by finish(), so
// an interrupted run never leaves a half-written dataset at <root>.
#include <fstream>
#include <memory>
#include <string>

#include "common/calibration.h"
#include "common/types.h"
#include "io/cloud_io.h"

namespace vilslam {

class DatasetWriter {
 public:
  // Throws InputError when <root> exists and overwrite is false, or a folder cannot be created.
  DatasetWriter(const std::string& root, const RigCalibration& calib, bool overwrite = false);
  ~DatasetWriter();  // without finish(): removes the partial folder
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;

  void add_imu(const ImuSample& sample);
  void add_stereo(const StereoFrame& frame);  // 8-bit grey PNGs
  void add_lidar(const LidarScan& scan);
  void add_groundtruth(const GroundTruthState& state);
  void set_reference_model(const PointCloud& model);
  // The folder being written (<root>.partial), moved into place by finish(): callers put side outputs
  // there so that they appear together with the dataset or not at all.
  std::string staging_path() const;
  // Writes the indexes and calibration files and moves the folder into place.
  void finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vilslam
