#include "common/yaml_config.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace vilslam {

YAML::Node load_yaml_file(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw InputError(path, "cannot open file");
  std::stringstream buffer;
  buffer << f.rdbuf();
  std::string text = buffer.str();
  // OpenCV writes "%YAML:1.0", which is not a valid YAML directive: drop that first line.
  if (text.rfind("%YAML:", 0) == 0) {
    const auto eol = text.find('\n');
    text = eol == std::string::npos ? std::string() : text.substr(eol + 1);
  }
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(path, "malformed YAML: " + e.msg, e.mark.line >= 0 ? e.mark.line + 1 : 0);
  }
}

void read_yaml_fields(const YAML::Node& node, const std::string& file, const std::string& key_path,
                      const YamlFields& fields) {
  if (!node || node.IsNull()) return;
  const std::string where = key_path.empty() ? "the file" : "'" + key_path + "'";
  if (!node.IsMap()) throw InputError(file, where + " must be a map of keys", node.Mark().line + 1);
  for (const auto& entry : node) {
    const long line = entry.first.Mark().line + 1;
    if (!entry.first.IsScalar()) throw InputError(file, "keys of " + where + " must be names", line);
    const std::string key = entry.first.Scalar();
    const std::string path = key_path.empty() ? key : key_path + "." + key;
    const YamlField* field = nullptr;
    for (const YamlField& f : fields) field = f.key == key ? &f : field;
    if (!field) throw InputError(file, "unknown key '" + path + "'", line);
    try {
      field->read(entry.second, file, path);
    } catch (const YAML::Exception&) {
      throw InputError(file, "bad value for '" + path + "'", entry.second.Mark().line + 1);
    }
  }
}

YAML::Node write_yaml_fields(const YamlFields& fields) {
  YAML::Node map(YAML::NodeType::Map);
  for (const YamlField& f : fields) map[f.key] = f.write();
  return map;
}

std::string shortest_double_text(double v) {
  char buf[32];
  // Whole numbers keep a ".0" (40.0, not 4e+01), so that the text still reads as a floating-point value.
  if (v == std::floor(v) && std::fabs(v) < 1e15) {
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
  }
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

YamlField yaml_section(const std::string& key, YamlFields fields) {
  YamlField f;
  f.key = key;
  f.read = [fields](const YAML::Node& node, const std::string& file, const std::string& key_path) {
    read_yaml_fields(node, file, key_path, fields);
  };
  f.write = [fields]() { return write_yaml_fields(fields); };
  return f;
}

}  // namespace vilslam
