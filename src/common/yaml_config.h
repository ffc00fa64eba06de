#pragma once
// Config structs <-> YAML maps through one table of named fields per struct. Reading applies the keys a
// map holds over the struct's current values (its defaults), so every key is optional; an unknown key,
// a value of the wrong type or a non-finite number is an InputError naming the file and the key path
// ("vio.smoother.window_size"). Writing gives every field's value, e.g. the effective config of a run.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

#include "common/error.h"

namespace vilslam {

struct YamlField {
  std::string key;
  // Reads node (the key's value) into the bound field; key_path names it in errors. Throws
  // YAML::Exception or InputError.
  std::function<void(const YAML::Node& node, const std::string& file, const std::string& key_path)> read;
  std::function<YAML::Node()> write;
};
using YamlFields = std::vector<YamlField>;

// Loads a YAML file; an OpenCV "%YAML:1.0" first line is accepted. Missing or malformed: InputError.
YAML::Node load_yaml_file(const std::string& path);

// Applies the keys of node (a map; null or absent changes nothing) to the fields. key_path is the path
// of node itself ("" at the top of the file).
void read_yaml_fields(const YAML::Node& node, const std::string& file, const std::string& key_path,
                      const YamlFields& fields);

// A map with every field's current value, in table order.
YAML::Node write_yaml_fields(const YamlFields& fields);

// Shortest decimal text that reads back to the same double; whole numbers as "40.0".
std::string shortest_double_text(double v);

// A field of the nested map `key`.
YamlField yaml_section(const std::string& key, YamlFields fields);

// A scalar field (bool, integer, floating point or string); floating-point values must be finite.
template <typename T>
YamlField yaml_value(const std::string& key, T& value) {
  YamlField f;
  f.key = key;
  f.read = [&value](const YAML::Node& node, const std::string& file, const std::string& key_path) {
    if (!node.IsScalar()) throw YAML::TypedBadConversion<T>(node.Mark());
    const T v = node.as<T>();
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(v)) throw InputError(file, "'" + key_path + "' is not finite", node.Mark().line + 1);
    }
    value = v;
  };
  f.write = [&value]() {
    if constexpr (std::is_floating_point_v<T>) {
      return YAML::Node(shortest_double_text(value));
    } else {
      return YAML::Node(value);
    }
  };
  return f;
}

}  // namespace vilslam
