#pragma once
// A bounds check of a ROS1 bag's record layout (format 2.0) before rosbag_storage opens it. The storage
// library trusts the lengths and counts a file declares (a record header length of 1.6 GB in a 15 kB file
// is an allocation of 1.6 GB); this walk refuses every such file with an InputError naming the byte
// offset, so what reaches the library is a sequence of records that fit the file.
#include <cstdint>
#include <string>

namespace vilslam {

// The largest chunk rosbag_storage is let to decompress (rosbag records chunks of 768 kB by default).
constexpr std::uint64_t kMaxBagChunkBytes = std::uint64_t{1} << 30;

// Throws InputError(path, ...) unless: the file starts with "#ROSBAG V2.0"; every record (and every record
// of an uncompressed chunk) has its header fields and data inside the file; the bag header's index_pos is
// the start of a record, with at least conn_count connection and chunk_count chunk-info records after it;
// a chunk declares an uncompressed size equal to its data (compression none) or at most kMaxBagChunkBytes;
// an index record's entries fit its data and point inside the chunk before it; a chunk-info record's
// entries fit its data and its chunk_pos is the start of a chunk. A bag whose index_pos is 0 (never
// indexed) passes after its header: rosbag_storage reports it as unindexed.
void check_bag_layout(const std::string& path);

}  // namespace vilslam
