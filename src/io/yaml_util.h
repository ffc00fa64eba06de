#pragma once
// yaml-cpp helpers shared by the calibration readers (loading files: common/yaml_config.h load_yaml_file):
// typed required fields and 4x4 rigid transforms, every failure an InputError naming the file.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "common/lie.h"
#include "common/yaml_config.h"  // load_yaml_file

namespace vilslam {

// Largest orthonormality_error accepted for a rotation read from a file. Printed rotations are far
// better (EuRoC T_BS 6e-13, KITTI Tr 9e-8, KITTI 00 poses 2e-7: docs/formats.md); 1e-5 still rejects
// any edited entry.
constexpr double kRotationTolerance = 1e-5;

// root[key] must be a map; otherwise InputError(file, "missing section '<key>'").
YAML::Node yaml_section(const YAML::Node& root, const std::string& key, const std::string& file);
// node[key] must exist and convert; otherwise InputError(file, "<key>: ...").
double yaml_double(const YAML::Node& node, const std::string& key, const std::string& file);
int yaml_int(const YAML::Node& node, const std::string& key, const std::string& file);
std::string yaml_string(const YAML::Node& node, const std::string& key, const std::string& file);
std::vector<double> yaml_doubles(const YAML::Node& node, const std::string& key, const std::string& file,
                                 std::size_t expected_size);

// A 4x4 rigid transform stored as EuRoC {rows: 4, cols: 4, data: [16]}, a nested 4x4 list (Kalibr)
// or a flat list of 16 numbers (row-major). The last row must be 0 0 0 1, the rotation orthonormal
// within kRotationTolerance.
SE3 yaml_transform(const YAML::Node& node, const std::string& key, const std::string& file);

// Writing: shortest decimal that reads back to the same double ("%.17g"), and "[a, b, c]".
std::string yaml_number(double v);
std::string yaml_list(const std::vector<double>& values);
// Row-major entries of T as a list of 16 numbers.
std::vector<double> transform_entries(const SE3& T);

// Checks a rotation read from a file (InputError naming file and what).
void require_rotation(const Mat3& R, const std::string& what, const std::string& file);

}  // namespace vilslam
