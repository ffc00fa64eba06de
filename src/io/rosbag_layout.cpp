// The record walk of check_bag_layout (rosbag_layout.h) over the ROS bag format 2.0: a file is the line
// "#ROSBAG V2.0\n" and records <header_len u32><header><data_len u32><data>, a header being fields
// <field_len u32><name>=<value>. Only headers (and the small index records) are read; data is skipped.
#include "io/rosbag_layout.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <vector>

#include "common/error.h"

namespace vilslam {
namespace {

constexpr char kMagic[] = "#ROSBAG V2.0\n";
constexpr std::uint64_t kMagicBytes = sizeof kMagic - 1;
enum Op : std::uint8_t { kBagHeader = 0x03, kIndexData = 0x04, kChunk = 0x05, kChunkInfo = 0x06, kConnection = 0x07 };
constexpr std::uint64_t kIndexEntryBytes = 12;      // time (sec, nsec) and offset, u32 each
constexpr std::uint64_t kChunkInfoEntryBytes = 8;   // conn and count, u32 each

struct Record {
  std::uint64_t at = 0;  // byte offset of its header_len
  std::map<std::string, std::string> fields;
  std::uint64_t data_at = 0;
  std::uint64_t data_len = 0;
  std::uint64_t end() const { return data_at + data_len; }
};

std::uint64_t little_endian(const std::string& bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = bytes.size(); i-- > 0;) v = (v << 8) | static_cast<std::uint8_t>(bytes[i]);
  return v;
}

class LayoutWalk {
 public:
  explicit LayoutWalk(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw InputError(path, "cannot open the bag");
    size_ = std::filesystem::file_size(path);
  }

  std::uint64_t size() const { return size_; }

  [[noreturn]] void fail(std::uint64_t at, const std::string& problem) const {
    throw InputError(path_, "truncated or corrupt bag: record at byte " + std::to_string(at) + ": " + problem);
  }

  std::string bytes(std::uint64_t at, std::uint64_t n) {
    std::string out(n, '\0');
    in_.clear();
    in_.seekg(static_cast<std::streamoff>(at));
    if (!in_.read(out.data(), static_cast<std::streamsize>(n))) throw InputError(path_, "cannot read the bag");
    return out;
  }

  // The record at `at`, which must end by `limit` (the file's or its chunk's end, named by `within`).
  Record record(std::uint64_t at, std::uint64_t limit, const char* within) {
    const auto past = [&](const char* what, std::uint64_t n) {
      fail(at, std::string("its ") + what + " of " + std::to_string(n) + " bytes runs past the end of " + within +
                   " (byte " + std::to_string(limit) + ")");
    };
    Record r;
    r.at = at;
    if (limit - at < 4) past("header length", limit - at);
    const std::uint64_t header_len = little_endian(bytes(at, 4));
    if (header_len > limit - at - 4) past("header", header_len);
    const std::string header = bytes(at + 4, header_len);
    const std::uint64_t data_len_at = at + 4 + header_len;
    if (limit - data_len_at < 4) past("data length", limit - data_len_at);
    r.data_len = little_endian(bytes(data_len_at, 4));
    r.data_at = data_len_at + 4;
    if (r.data_len > limit - r.data_at) past("data", r.data_len);
    for (std::size_t i = 0; i < header.size();) {
      if (header.size() - i < 4) fail(at, "a header field's length is cut off");
      const std::uint64_t field_len = little_endian(header.substr(i, 4));
      i += 4;
      if (field_len > header.size() - i) fail(at, "a header field of " + std::to_string(field_len) + " bytes runs past its header");
      const std::string field = header.substr(i, field_len);
      i += field_len;
      const std::size_t eq = field.find('=');
      if (eq == std::string::npos) fail(at, "a header field has no '='");
      r.fields[field.substr(0, eq)] = field.substr(eq + 1);
    }
    if (field(r, "op").size() != 1) fail(at, "its op field is not one byte");
    return r;
  }

  const std::string& field(const Record& r, const std::string& name) const {
    const auto it = r.fields.find(name);
    if (it == r.fields.end()) fail(r.at, "no " + name + " field");
    return it->second;
  }

  // A little-endian unsigned field of exactly `width` bytes.
  std::uint64_t number(const Record& r, const std::string& name, std::size_t width) const {
    const std::string& v = field(r, name);
    if (v.size() != width) fail(r.at, "its " + name + " field is not " + std::to_string(width) + " bytes");
    return little_endian(v);
  }

 private:
  std::string path_;
  std::ifstream in_;
  std::uint64_t size_ = 0;
};

std::uint8_t op_of(const Record& r) { return static_cast<std::uint8_t>(r.fields.at("op")[0]); }

}  // namespace

void check_bag_layout(const std::string& path) {
  LayoutWalk walk(path);
  if (walk.size() < kMagicBytes || walk.bytes(0, kMagicBytes) != kMagic) {
    throw InputError(path, "not a ROS1 bag of format 2.0 (no \"#ROSBAG V2.0\" line at its start)");
  }
  const Record header = walk.record(kMagicBytes, walk.size(), "the file");
  if (op_of(header) != kBagHeader) walk.fail(header.at, "the first record is not the bag header");
  const std::uint64_t index_pos = walk.number(header, "index_pos", 8);
  const std::uint64_t conn_count = walk.number(header, "conn_count", 4);
  const std::uint64_t chunk_count = walk.number(header, "chunk_count", 4);
  if (index_pos == 0) return;  // never indexed: rosbag_storage says so

  std::set<std::uint64_t> record_starts;
  std::set<std::uint64_t> chunk_starts;
  // The chunk before an index record: its uncompressed size and, when uncompressed, its records' offsets.
  std::uint64_t chunk_bytes = 0;
  bool chunk_uncompressed = false;
  std::set<std::uint64_t> chunk_records;
  bool seen_chunk = false;
  std::uint64_t connections_in_index = 0, chunk_infos_in_index = 0;

  for (std::uint64_t at = header.end(); at < walk.size();) {
    const Record r = walk.record(at, walk.size(), "the file");
    record_starts.insert(at);
    switch (op_of(r)) {
      case kChunk: {
        chunk_bytes = walk.number(r, "size", 4);
        chunk_uncompressed = walk.field(r, "compression") == "none";
        chunk_records.clear();
        if (chunk_uncompressed) {
          if (chunk_bytes != r.data_len) {
            walk.fail(at, "an uncompressed chunk of " + std::to_string(r.data_len) + " bytes declares size " +
                              std::to_string(chunk_bytes));
          }
          for (std::uint64_t inner = r.data_at; inner < r.end();) {
            chunk_records.insert(inner - r.data_at);
            inner = walk.record(inner, r.end(), "its chunk").end();
          }
        } else if (chunk_bytes > kMaxBagChunkBytes) {
          walk.fail(at, "a compressed chunk declares " + std::to_string(chunk_bytes) + " bytes uncompressed, more than " +
                            std::to_string(kMaxBagChunkBytes));
        }
        chunk_starts.insert(at);
        seen_chunk = true;
        break;
      }
      case kIndexData: {
        const std::uint64_t count = walk.number(r, "count", 4);
        if (count * kIndexEntryBytes > r.data_len) walk.fail(at, "its " + std::to_string(count) + " index entries exceed its data");
        if (!seen_chunk) walk.fail(at, "an index record before any chunk");
        const std::string entries = walk.bytes(r.data_at, count * kIndexEntryBytes);
        for (std::uint64_t i = 0; i < count; ++i) {
          const std::uint64_t offset = little_endian(entries.substr(i * kIndexEntryBytes + 8, 4));
          const bool inside = chunk_uncompressed ? chunk_records.count(offset) > 0 : offset < chunk_bytes;
          if (!inside) walk.fail(at, "index entry " + std::to_string(i) + " points to no record of its chunk");
        }
        break;
      }
      case kChunkInfo: {
        const std::uint64_t count = walk.number(r, "count", 4);
        if (count * kChunkInfoEntryBytes > r.data_len) walk.fail(at, "its " + std::to_string(count) + " entries exceed its data");
        if (chunk_starts.count(walk.number(r, "chunk_pos", 8)) == 0) walk.fail(at, "its chunk_pos is not the start of a chunk");
        if (at >= index_pos) ++chunk_infos_in_index;
        break;
      }
      case kConnection:
        if (at >= index_pos) ++connections_in_index;
        break;
      default:
        break;
    }
    at = r.end();
  }
  if (index_pos != walk.size() && record_starts.count(index_pos) == 0) {
    walk.fail(header.at, "its index_pos " + std::to_string(index_pos) + " is not the start of a record");
  }
  if (connections_in_index < conn_count || chunk_infos_in_index < chunk_count) {
    walk.fail(header.at, "it declares " + std::to_string(conn_count) + " connections and " + std::to_string(chunk_count) +
                             " chunks; the index holds " + std::to_string(connections_in_index) + " and " +
                             std::to_string(chunk_infos_in_index));
  }
}

}  // namespace vilslam
