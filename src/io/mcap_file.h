#pragma once
// ROS 2 bags in MCAP storage (the default of ROS 2 since Iron; mcap.dev/spec, major version 0): one or more
// .mcap files of records (uint8 opcode, uint64 length, content). The data section is read record by record
// up to its Data End or Footer: Schema (the type name), Channel (topic, message encoding, schema) and
// Message records, at the top level or inside Chunks, whose records are stored uncompressed, or compressed
// with zstd or LZ4 frames (Debian's libzstd and liblz4). The summary section is not needed and not read.
// Any malformed or truncated record, unknown compression or size mismatch is an InputError naming the file.
#include <memory>
#include <string>
#include <vector>

#include "io/message_log.h"

namespace vilslam {

// path: what the user named (a bag folder or one .mcap file); files: the .mcap files in order. Topic types are
// listed by their ROS1 names, md5sum "*"; a channel whose messages are not CDR is listed with its encoding
// before the type ("json:std_msgs/String"). A topic's messages come in the order of their log times, then of
// the records in the files.
std::unique_ptr<IndexedLog> open_mcap_bag(const std::string& path, const std::vector<std::string>& files);

}  // namespace vilslam
