#pragma once
// zstd frames (Debian's libzstd), as ROS 2 bags store them: whole files (rosbag2's compression_mode FILE),
// single messages (MESSAGE) and MCAP chunks. Errors are WireErrors; the caller names the file.
#include <cstdint>
#include <string>
#include <vector>

namespace vilslam {

// One or more concatenated zstd frames, whether or not they record their content size; more than max_size
// bytes of output is a WireError (a corrupt or hostile frame).
std::vector<std::uint8_t> zstd_decompress(const std::uint8_t* data, std::size_t size, std::size_t max_size);
// The file `in` decompressed into the file `out`, streamed.
void zstd_decompress_file(const std::string& in, const std::string& out);

}  // namespace vilslam
