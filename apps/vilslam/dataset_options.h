#pragma once
// The options that say how to read a dataset given as a ROS1 bag (--calib, --topic ROLE=TOPIC), shared
// by the subcommands that open datasets.
#include <CLI/CLI.hpp>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "io/dataset.h"

namespace vilslam::cli {

struct DatasetOptionArgs {
  std::string calibration_path;
  std::vector<std::string> topics;  // "role=topic"
};

// Adds --calib and --topic to app; returns the arguments they fill.
std::shared_ptr<DatasetOptionArgs> add_dataset_options(CLI::App& app);
// "role=topic" pairs as a map; a pair without '=' is std::invalid_argument.
std::map<std::string, std::string> parse_topic_args(const std::vector<std::string>& args);
DatasetOptions dataset_options(const DatasetOptionArgs& args);

}  // namespace vilslam::cli
