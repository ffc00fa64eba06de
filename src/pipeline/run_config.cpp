#include "pipeline/run_config.h"

#include "common/yaml_config.h"
#include "vio/vio_config_yaml.h"

namespace vilslam {
namespace {

YamlFields run_yaml_fields(OfflineRunConfig& c) {
  return {yaml_section("frontend", frontend_yaml_fields(c.frontend)), yaml_section("vio", vio_yaml_fields(c.vio)),
          yaml_section("lidar_mapper", lidar::lidar_mapper_yaml_fields(c.lidar))};
}

}  // namespace

OfflineRunConfig load_run_config(const std::string& path) {
  OfflineRunConfig c;
  read_yaml_fields(load_yaml_file(path), path, "", run_yaml_fields(c));
  validate_frontend_config(c.frontend, path);
  validate_vio_config(c.vio, path);
  lidar::validate_lidar_config(c.lidar.lidar, path);
  return c;
}

std::string run_config_yaml(const OfflineRunConfig& config) {
  OfflineRunConfig copy = config;
  YAML::Emitter out;
  out << write_yaml_fields(run_yaml_fields(copy));
  return std::string(out.c_str()) + "\n";
}

}  // namespace vilslam
