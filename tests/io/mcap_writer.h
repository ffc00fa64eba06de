#pragma once
// Writes a dataset as an MCAP file of ROS 2 messages (CDR by eProsima Fast CDR, ros2_bag_writer.h) for the
// MCAP tests, record by record as mcap.dev/spec lays them out: magic, Header, then Schema and Channel records
// and the messages at the top level or in Chunks (uncompressed, zstd or an LZ4 frame), Data End, Footer, magic.
#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ros2_bag_writer.h"

namespace vilslam::test {

struct McapOptions {
  std::size_t messages_per_chunk = 0;  // 0: every message a top-level record, no chunks
  std::string compression;             // of the chunks: "", "zstd" or "lz4"
  bool reverse_in_chunk = false;       // store each chunk's messages newest first (log order must still come out)
};

class McapBytes {
 public:
  McapBytes& u8(std::uint8_t v) { return raw(&v, 1); }
  McapBytes& u16(std::uint16_t v) { return raw(&v, 2); }
  McapBytes& u32(std::uint32_t v) { return raw(&v, 4); }
  McapBytes& u64(std::uint64_t v) { return raw(&v, 8); }
  McapBytes& str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    return raw(s.data(), s.size());
  }
  McapBytes& bytes(const std::vector<std::uint8_t>& b) { return raw(b.data(), b.size()); }
  // A record: opcode, uint64 content length, content.
  McapBytes& record(std::uint8_t opcode, const McapBytes& content) {
    u8(opcode).u64(content.data.size());
    return bytes(content.data);
  }
  std::vector<std::uint8_t> data;

 private:
  McapBytes& raw(const void* p, std::size_t n) {
    const auto* b = static_cast<const std::uint8_t*>(p);
    data.insert(data.end(), b, b + n);
    return *this;
  }
};

inline std::vector<std::uint8_t> mcap_compress(const std::vector<std::uint8_t>& in, const std::string& compression) {
  if (compression == "zstd") {
    std::vector<std::uint8_t> out(ZSTD_compressBound(in.size()));
    out.resize(ZSTD_compress(out.data(), out.size(), in.data(), in.size(), 3));
    return out;
  }
  if (compression == "lz4") {
    std::vector<std::uint8_t> out(LZ4F_compressFrameBound(in.size(), nullptr));
    out.resize(LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr));
    return out;
  }
  return in;
}

inline void write_mcap(DatasetReader& reader, const std::filesystem::path& file, const McapOptions& options = {}) {
  const std::vector<Ros2Message> messages = ros2_messages(reader, false);
  const auto& topics = ros2_topics();
  McapBytes definitions;  // a Schema and a Channel per topic (ids from 1)
  for (std::size_t k = 0; k < topics.size(); ++k) {
    const auto id = static_cast<std::uint16_t>(k + 1);
    McapBytes schema, channel;
    schema.u16(id).str(topics[k].second).str("ros2msg").str("# definition not needed");
    channel.u16(id).u16(id).str(topics[k].first).str("cdr").u32(0);
    definitions.record(0x03, schema).record(0x04, channel);
  }
  const auto message_record = [&](const Ros2Message& m, std::uint32_t sequence) {
    std::uint16_t id = 0;
    for (std::size_t k = 0; k < topics.size(); ++k) {
      if (topics[k].first == m.topic) id = static_cast<std::uint16_t>(k + 1);
    }
    McapBytes content, out;
    content.u16(id).u32(sequence).u64(static_cast<std::uint64_t>(m.t_ns)).u64(static_cast<std::uint64_t>(m.t_ns)).bytes(m.data);
    return out.record(0x05, content);
  };

  McapBytes file_bytes, header;
  const std::uint8_t magic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
  for (std::uint8_t b : magic) file_bytes.u8(b);
  header.str("ros2").str("vilslam tests");
  file_bytes.record(0x01, header);
  if (options.messages_per_chunk == 0) {
    file_bytes.bytes(definitions.data);
    for (std::size_t i = 0; i < messages.size(); ++i) file_bytes.bytes(message_record(messages[i], i).data);
  } else {
    for (std::size_t first = 0; first < messages.size(); first += options.messages_per_chunk) {
      const std::size_t last = std::min(messages.size(), first + options.messages_per_chunk);
      McapBytes records;
      if (first == 0) records.bytes(definitions.data);  // as writers do: definitions in the chunk of first use
      for (std::size_t j = first; j < last; ++j) {
        const std::size_t i = options.reverse_in_chunk ? first + last - 1 - j : j;
        records.bytes(message_record(messages[i], i).data);
      }
      const std::vector<std::uint8_t> stored = mcap_compress(records.data, options.compression);
      McapBytes chunk;
      chunk.u64(messages[first].t_ns).u64(messages[last - 1].t_ns).u64(records.data.size()).u32(0);
      chunk.str(options.compression).u64(stored.size()).bytes(stored);
      file_bytes.record(0x06, chunk);
    }
  }
  McapBytes data_end, footer;
  data_end.u32(0);
  footer.u64(0).u64(0).u32(0);
  file_bytes.record(0x0F, data_end).record(0x02, footer);
  for (std::uint8_t b : magic) file_bytes.u8(b);
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(file_bytes.data.data()),
                                              static_cast<std::streamsize>(file_bytes.data.size()));
}

}  // namespace vilslam::test
