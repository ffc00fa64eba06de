#include "io/mcap_file.h"

#include <lz4frame.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "common/error.h"
#include "io/ros2_messages.h"
#include "io/ros_wire.h"
#include "io/zstd_util.h"

namespace vilslam {
namespace {

constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
enum Opcode : std::uint8_t { kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05, kChunk = 0x06, kDataEnd = 0x0F };
constexpr std::uint64_t kRecordHeader = 1 + 8;    // opcode, content length
constexpr std::uint64_t kMessagePrefix = 2 + 4 + 8 + 8;  // channel id, sequence, log time, publish time
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 32;  // a larger chunk is a corrupt length

struct Entry {
  std::uint64_t log_time_ns;
  std::size_t order;     // position of the record in the files, for equal log times
  std::size_t file;
  std::ptrdiff_t chunk;  // index in chunks, or -1 for a record at the top level of the file
  std::uint64_t offset;  // of the message data: in the file, or in the chunk's uncompressed records
  std::uint64_t size;
};

struct ChunkLocation {
  std::size_t file;
  std::uint64_t offset;  // of the (compressed) records in the file
  std::uint64_t size;
  std::uint64_t uncompressed_size;
  std::string compression;
};

std::vector<std::uint8_t> read_at(std::ifstream& in, const std::string& file, std::uint64_t offset, std::uint64_t n) {
  std::vector<std::uint8_t> bytes(n);
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(n));
  if (static_cast<std::uint64_t>(in.gcount()) != n) {
    throw InputError(file, "truncated: " + std::to_string(n) + " bytes at offset " + std::to_string(offset) + " cannot be read");
  }
  return bytes;
}

std::vector<std::uint8_t> lz4_frame_decompress(const std::vector<std::uint8_t>& in, std::uint64_t size) {
  std::vector<std::uint8_t> out(size);
  LZ4F_dctx* ctx = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) throw WireError("LZ4 context");
  std::size_t in_pos = 0, out_pos = 0, hint = 1;
  while (hint != 0 && in_pos < in.size()) {
    std::size_t dst = out.size() - out_pos, src = in.size() - in_pos;
    hint = LZ4F_decompress(ctx, out.data() + out_pos, &dst, in.data() + in_pos, &src, nullptr);
    if (LZ4F_isError(hint)) {
      LZ4F_freeDecompressionContext(ctx);
      throw WireError(std::string("LZ4: ") + LZ4F_getErrorName(hint));
    }
    if (dst == 0 && src == 0) break;  // no progress: the output is full
    in_pos += src;
    out_pos += dst;
  }
  LZ4F_freeDecompressionContext(ctx);
  if (hint != 0 || out_pos != size) throw WireError("LZ4 frame ends early or holds more than uncompressed_size");
  return out;
}

std::vector<std::uint8_t> decompress(const ChunkLocation& chunk, std::vector<std::uint8_t> records) {
  if (chunk.compression.empty()) {
    if (records.size() != chunk.uncompressed_size) throw WireError("uncompressed chunk size differs from its records");
    return records;
  }
  if (chunk.compression == "lz4") return lz4_frame_decompress(records, chunk.uncompressed_size);
  if (chunk.compression == "zstd") {
    std::vector<std::uint8_t> out = zstd_decompress(records.data(), records.size(), chunk.uncompressed_size);
    if (out.size() != chunk.uncompressed_size) {
      throw WireError("zstd chunk holds " + std::to_string(out.size()) + " bytes, not uncompressed_size");
    }
    return out;
  }
  throw WireError("chunk compression '" + chunk.compression + "' is not supported (none, lz4, zstd)");
}

// The files' records as read so far, and the chunk last uncompressed (fetching a topic's messages in log order
// mostly walks the chunks in order).
struct McapStorage {
  std::string path;
  std::vector<std::string> files;
  std::vector<std::ifstream> streams;
  std::vector<ChunkLocation> chunks;
  std::map<std::string, std::vector<Entry>> entries;  // by topic, in file order
  // Per file: schema id -> type name, channel id -> (topic, CDR or not).
  std::vector<std::map<std::uint16_t, std::string>> schemas;
  std::vector<std::map<std::uint16_t, std::pair<std::string, std::string>>> channels;  // topic, listed type
  std::map<std::string, std::string> type_of;  // topic -> listed type
  std::size_t order = 0;
  std::ptrdiff_t cached_chunk = -1;
  std::vector<std::uint8_t> cached_records;

  // One record at the top level or in a chunk: the bytes of its content at hand (of a message, at least the
  // fixed fields: its data is not copied), the content's full length, and where the content starts (in the
  // file, or in the chunk's records).
  void record(std::size_t f, std::uint8_t opcode, const std::uint8_t* content, std::size_t size, std::uint64_t length,
              std::ptrdiff_t chunk, std::uint64_t data_offset) {
    WireReader r(content, size);
    if (opcode == kSchema) {
      const auto id = r.read<std::uint16_t>();
      schemas[f][id] = r.string();
    } else if (opcode == kChannel) {
      const auto id = r.read<std::uint16_t>();
      const auto schema_id = r.read<std::uint16_t>();
      const std::string topic = r.string(), encoding = r.string();
      const auto schema = schemas[f].find(schema_id);
      const std::string type = schema == schemas[f].end() ? "" : ros1_type_name(schema->second);
      const std::string listed = encoding == "cdr" ? type : encoding + ":" + type;
      const auto known = type_of.find(topic);
      if (known != type_of.end() && known->second != listed) {
        throw InputError(path, "topic " + topic + " has messages of two types, " + known->second + " and " + listed);
      }
      type_of[topic] = listed;
      channels[f][id] = {topic, listed};
    } else if (opcode == kMessage) {
      if (length < kMessagePrefix || size < kMessagePrefix) throw WireError("message record shorter than its fixed fields");
      const auto channel_id = r.read<std::uint16_t>();
      r.read<std::uint32_t>();  // sequence
      const auto log_time_ns = r.read<std::uint64_t>();
      const auto channel = channels[f].find(channel_id);
      if (channel == channels[f].end()) throw WireError("message on channel " + std::to_string(channel_id) + " before its Channel record");
      entries[channel->second.first].push_back(
          {log_time_ns, order++, f, chunk, data_offset + kMessagePrefix, length - kMessagePrefix});
    }
  }

  // The records of one chunk, uncompressed: schemas, channels and messages in them.
  void chunk_records(std::size_t f, std::ptrdiff_t chunk, const std::vector<std::uint8_t>& records) {
    std::uint64_t pos = 0;
    while (pos < records.size()) {
      if (records.size() - pos < kRecordHeader) throw WireError("chunk ends inside a record header");
      const std::uint8_t opcode = records[pos];
      std::uint64_t length = 0;
      std::memcpy(&length, records.data() + pos + 1, 8);
      if (length > records.size() - pos - kRecordHeader) throw WireError("record in chunk longer than the chunk");
      const auto* start = records.data() + pos + kRecordHeader;
      record(f, opcode, start, length, length, chunk, pos + kRecordHeader);
      pos += kRecordHeader + length;
    }
  }

  void scan(std::size_t f) {
    const std::string& file = files[f];
    std::ifstream& in = streams[f];
    const std::uint64_t file_size = std::filesystem::file_size(file);
    const auto magic = read_at(in, file, 0, sizeof kMagic);
    if (!std::equal(magic.begin(), magic.end(), kMagic)) throw InputError(file, "not an MCAP file (magic bytes)");
    std::uint64_t pos = sizeof kMagic;
    while (true) {
      if (file_size - pos < kRecordHeader) throw InputError(file, "truncated: the data section has no Data End or Footer record");
      const auto head = read_at(in, file, pos, kRecordHeader);
      std::uint64_t length = 0;
      std::memcpy(&length, head.data() + 1, 8);
      if (length > file_size - pos - kRecordHeader) {
        throw InputError(file, "truncated: record at offset " + std::to_string(pos) + " runs past the end");
      }
      const std::uint8_t opcode = head[0];
      const std::uint64_t content_offset = pos + kRecordHeader;
      try {
        if (opcode == kDataEnd || opcode == kFooter) break;
        if (opcode == kSchema || opcode == kChannel) {
          const auto content = read_at(in, file, content_offset, length);
          record(f, opcode, content.data(), content.size(), length, -1, content_offset);
        } else if (opcode == kMessage) {  // the data is read when asked for
          const auto prefix = read_at(in, file, content_offset, std::min(length, kMessagePrefix));
          record(f, opcode, prefix.data(), prefix.size(), length, -1, content_offset);
        } else if (opcode == kChunk) {
          const auto content = read_at(in, file, content_offset, length);
          WireReader r(content.data(), content.size());
          r.read<std::uint64_t>();  // message start time
          r.read<std::uint64_t>();  // message end time
          const auto uncompressed_size = r.read<std::uint64_t>();
          r.read<std::uint32_t>();  // uncompressed CRC (0: none)
          ChunkLocation chunk{f, 0, 0, uncompressed_size, r.string()};
          chunk.size = r.read<std::uint64_t>();
          if (chunk.size != r.remaining()) throw WireError("chunk records length differs from the record's");
          if (uncompressed_size > kMaxChunkBytes) throw WireError("chunk of " + std::to_string(uncompressed_size) + " bytes");
          chunk.offset = content_offset + (content.size() - chunk.size);
          const std::vector<std::uint8_t> compressed(content.end() - static_cast<std::ptrdiff_t>(chunk.size), content.end());
          chunks.push_back(chunk);
          chunk_records(f, static_cast<std::ptrdiff_t>(chunks.size()) - 1, decompress(chunk, compressed));
        }
      } catch (const WireError& e) {
        throw InputError(file, "record at offset " + std::to_string(pos) + ": " + e.what());
      }
      pos = content_offset + length;
    }
  }

  std::vector<std::uint8_t> data(const Entry& e) {
    if (e.chunk < 0) return read_at(streams[e.file], files[e.file], e.offset, e.size);
    if (cached_chunk != e.chunk) {
      const ChunkLocation& c = chunks[static_cast<std::size_t>(e.chunk)];
      try {
        cached_records = decompress(c, read_at(streams[c.file], files[c.file], c.offset, c.size));
      } catch (const WireError& err) {
        throw InputError(files[c.file], std::string("chunk: ") + err.what());
      }
      cached_chunk = e.chunk;
    }
    const auto* p = cached_records.data() + e.offset;
    return std::vector<std::uint8_t>(p, p + e.size);
  }

};

}  // namespace

std::unique_ptr<IndexedLog> open_mcap_bag(const std::string& path, const std::vector<std::string>& files) {
  auto storage = std::make_shared<McapStorage>();
  McapStorage& d = *storage;
  d.path = path;
  d.files = files;
  d.schemas.resize(files.size());
  d.channels.resize(files.size());
  for (std::size_t f = 0; f < files.size(); ++f) {
    if (!std::filesystem::is_regular_file(files[f])) throw InputError(files[f], "MCAP file does not exist");
    d.streams.emplace_back(files[f], std::ios::binary);
    if (!d.streams.back()) throw InputError(files[f], "cannot open");
    d.scan(f);
  }
  std::vector<BagTopic> topics;
  std::map<std::string, std::vector<std::size_t>> ids;
  auto all = std::make_shared<std::vector<Entry>>();
  for (const auto& [topic, type] : d.type_of) {
    std::vector<Entry>& list = d.entries[topic];
    std::sort(list.begin(), list.end(),
              [](const Entry& a, const Entry& b) { return std::tie(a.log_time_ns, a.order) < std::tie(b.log_time_ns, b.order); });
    topics.push_back({topic, type, "*", list.size()});
    for (const Entry& e : list) {
      ids[topic].push_back(all->size());
      all->push_back(e);
    }
  }
  d.entries.clear();
  return std::make_unique<IndexedLog>(path, std::move(topics), std::move(ids),
                                      [storage, all](std::size_t id) { return storage->data((*all)[id]); });
}

}  // namespace vilslam
