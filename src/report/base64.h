#pragma once
// Numeric arrays in the report's JSON as base64 of little-endian float32 (the page reads them back into a
// Float32Array): a quarter of the size of decimal text, and the same bytes on every host.
#include <string>
#include <vector>

namespace vilslam::report {

std::string base64_float32(const std::vector<float>& values);

}  // namespace vilslam::report
