#include "io/yaml_util.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/error.h"

namespace vilslam {
namespace {

YAML::Node field(const YAML::Node& node, const std::string& key, const std::string& file) {
  if (!node.IsMap() || !node[key]) throw InputError(file, "missing field '" + key + "'");
  return node[key];
}

std::vector<double> flatten_matrix(const YAML::Node& m, const std::string& key, const std::string& file) {
  std::vector<double> values;
  try {
    if (m.IsMap()) {
      if (yaml_int(m, "rows", file) != 4 || yaml_int(m, "cols", file) != 4) {
        throw InputError(file, key + ": expected a 4x4 matrix");
      }
      return yaml_doubles(m, "data", file, 16);
    }
    if (!m.IsSequence()) throw InputError(file, key + ": expected a 4x4 matrix");
    for (const auto& item : m) {
      if (item.IsSequence()) {
        if (item.size() != 4) throw InputError(file, key + ": expected rows of 4 numbers");
        for (const auto& v : item) values.push_back(v.as<double>());
      } else {
        values.push_back(item.as<double>());
      }
    }
  } catch (const YAML::Exception&) {
    throw InputError(file, key + ": matrix entries must be numbers");
  }
  if (values.size() != 16) throw InputError(file, key + ": expected 16 numbers, got " + std::to_string(values.size()));
  return values;
}

}  // namespace

YAML::Node yaml_section(const YAML::Node& root, const std::string& key, const std::string& file) {
  if (!root.IsMap() || !root[key] || !root[key].IsMap()) throw InputError(file, "missing section '" + key + "'");
  return root[key];
}

double yaml_double(const YAML::Node& node, const std::string& key, const std::string& file) {
  double v = 0;
  try {
    v = field(node, key, file).as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(file, key + ": expected a number");
  }
  if (!std::isfinite(v)) throw InputError(file, key + ": not finite");
  return v;
}

int yaml_int(const YAML::Node& node, const std::string& key, const std::string& file) {
  try {
    return field(node, key, file).as<int>();
  } catch (const YAML::Exception&) {
    throw InputError(file, key + ": expected an integer");
  }
}

std::string yaml_string(const YAML::Node& node, const std::string& key, const std::string& file) {
  try {
    return field(node, key, file).as<std::string>();
  } catch (const YAML::Exception&) {
    throw InputError(file, key + ": expected a string");
  }
}

std::vector<double> yaml_doubles(const YAML::Node& node, const std::string& key, const std::string& file,
                                 std::size_t expected_size) {
  std::vector<double> values;
  try {
    values = field(node, key, file).as<std::vector<double>>();
  } catch (const YAML::Exception&) {
    throw InputError(file, key + ": expected a list of numbers");
  }
  if (values.size() != expected_size) {
    throw InputError(file, key + ": expected " + std::to_string(expected_size) + " numbers, got " +
                               std::to_string(values.size()));
  }
  for (double v : values) {
    if (!std::isfinite(v)) throw InputError(file, key + ": not finite");
  }
  return values;
}

std::string yaml_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string yaml_list(const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + yaml_number(values[i]);
  return out + "]";
}

std::vector<double> transform_entries(const SE3& T) {
  const Mat4 M = T.matrix();
  std::vector<double> v;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) v.push_back(M(r, c));
  }
  return v;
}

void require_rotation(const Mat3& R, const std::string& what, const std::string& file) {
  if (!R.allFinite()) throw InputError(file, what + ": rotation is not finite");
  const double err = so3::orthonormality_error(R);
  if (!(err <= kRotationTolerance)) {
    std::ostringstream msg;
    msg << what << ": rotation is not orthonormal (error " << err << " > " << kRotationTolerance << ")";
    throw InputError(file, msg.str());
  }
}

SE3 yaml_transform(const YAML::Node& node, const std::string& key, const std::string& file) {
  const std::vector<double> v = flatten_matrix(field(node, key, file), key, file);
  Mat4 T;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T(r, c) = v[4 * r + c];
  }
  if (!T.allFinite()) throw InputError(file, key + ": not finite");
  if ((T.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > kRotationTolerance) {
    throw InputError(file, key + ": last row must be 0 0 0 1");
  }
  require_rotation(T.topLeftCorner<3, 3>(), key, file);
  return SE3(T);
}

}  // namespace vilslam
