#pragma once
// One YAML for every module of `vilslam run` (docs/pipeline.md): optional top-level sections
// `frontend:` (frontend_yaml_fields), `vio:` (vio_yaml_fields), `lidar_mapper:`
// (lidar_mapper_yaml_fields) and `loop_closure:` (loop_closure_yaml_fields plus `vocabulary` and `graph`). A missing section or key keeps the default; config/run_default.yaml lists
// every key with its default.
#include <string>

#include "pipeline/offline_runner.h"

namespace vilslam {

// The modules' configs from the file; mode stays the default (it is chosen on the command line).
// Throws InputError naming the file and the key on a missing or malformed file, an unknown section or
// key, a value of the wrong type, a non-finite number or a value out of its range.
OfflineRunConfig load_run_config(const std::string& path);

// The three sections with every key's value (the effective config of a run); load_run_config reads it
// back to the same config.
std::string run_config_yaml(const OfflineRunConfig& config);

}  // namespace vilslam
