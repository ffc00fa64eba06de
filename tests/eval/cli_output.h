#pragma once
// Reading what the CLI wrote, for the command tests of tests/eval.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace vilslam::test {

// The number after "key": inside the JSON object introduced by "object": (first match after it).
inline double json_number(const std::string& doc, const std::string& object, const std::string& key) {
  const auto at = doc.find("\"" + object + "\":");
  EXPECT_NE(at, std::string::npos) << object;
  const auto k = doc.find("\"" + key + "\":", at);
  EXPECT_NE(k, std::string::npos) << object << "." << key;
  return std::strtod(doc.c_str() + k + key.size() + 3, nullptr);
}

}  // namespace vilslam::test
