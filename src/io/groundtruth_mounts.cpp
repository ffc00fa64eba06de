#include "io/groundtruth_mounts.h"

#include <filesystem>

#include "io/yaml_util.h"

namespace vilslam {

std::string groundtruth_mounts_yaml(const GroundTruthMounts& mounts) {
  std::string out = "# Where the sensors really are (ground truth; the estimator reads rig.yaml, the nominal mounts)\n";
  for (const auto& [key, T] : {std::pair<const char*, const SE3*>{"T_I_C0", &mounts.T_I_C0},
                               {"T_I_C1", &mounts.T_I_C1},
                               {"T_I_L", &mounts.T_I_L}}) {
    out += std::string(key) + ": " + yaml_list(transform_entries(*T)) + "\n";
  }
  return out;
}

std::optional<GroundTruthMounts> read_groundtruth_mounts(const std::string& dataset_path) {
  const std::filesystem::path file = std::filesystem::path(dataset_path) / kGroundTruthMountsFile;
  if (!std::filesystem::exists(file)) return std::nullopt;
  const YAML::Node root = load_yaml_file(file.string());
  return GroundTruthMounts{yaml_transform(root, "T_I_C0", file.string()), yaml_transform(root, "T_I_C1", file.string()),
                           yaml_transform(root, "T_I_L", file.string())};
}

}  // namespace vilslam
