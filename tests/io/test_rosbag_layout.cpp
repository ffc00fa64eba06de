// check_bag_layout on bags written by ROS's own writer: they pass, and each length, count or offset the
// storage library would trust, once made to point outside the file, its chunk or the records, is refused
// with the byte offset of the record (io/rosbag_layout.h).
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "common/error.h"
#include "io/rosbag_layout.h"
#include "rosbag_test_util.h"

namespace vilslam {
namespace {

using RosbagLayout = test::RosbagFixture;

std::uint32_t u32_at(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

void put_u32(std::string& bytes, std::size_t at, std::uint32_t v) { std::memcpy(&bytes[at], &v, sizeof v); }

// The byte after the '=' of the first header field `name` (the tests' bags have one match before the index).
std::size_t value_at(const std::string& bytes, const std::string& name) {
  const std::size_t at = bytes.find(name + "=");
  EXPECT_NE(at, std::string::npos) << name;
  return at + name.size() + 1;
}

// Where a record starts, given where the one before it starts: <header_len><header><data_len><data>.
std::size_t next_record(const std::string& bytes, std::size_t at) {
  const std::size_t data_len_at = at + 4 + u32_at(bytes, at);
  return data_len_at + 4 + u32_at(bytes, data_len_at);
}

class Bag {
 public:
  explicit Bag(const std::string& path) : path_(path), bytes_(test::read_file_bytes(path)) {}
  std::string& bytes() { return bytes_; }
  // The error check_bag_layout gives for the bytes as they are now (empty when it accepts them).
  std::string error() const {
    const std::string edited = path_ + ".edited.bag";
    std::ofstream(edited, std::ios::binary).write(bytes_.data(), static_cast<std::streamsize>(bytes_.size()));
    try {
      check_bag_layout(edited);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), edited);
      return e.what();
    }
    return {};
  }

 private:
  std::string path_;
  std::string bytes_;
};

constexpr std::size_t kBagHeaderAt = 13;  // after "#ROSBAG V2.0\n"

TEST_F(RosbagLayout, WrittenBagsPassAndEachBrokenLengthIsRefused) {
  for (const char* compression : {"none", "lz4", "bz2"}) {
    SCOPED_TRACE(compression);
    Bag bag(python_bag(compression, std::string("--compression ") + compression, false));
    EXPECT_EQ(bag.error(), "");
  }
  const std::string path = python_bag("plain", "--compression none", false);
  const std::size_t chunk_at = next_record(Bag(path).bytes(), kBagHeaderAt);
  {
    Bag bag(path);
    put_u32(bag.bytes(), value_at(bag.bytes(), "index_pos"), u32_at(bag.bytes(), value_at(bag.bytes(), "index_pos")) + 1);
    EXPECT_NE(bag.error().find("record at byte 13: its index_pos"), std::string::npos) << bag.error();
  }
  {
    Bag bag(path);
    put_u32(bag.bytes(), value_at(bag.bytes(), "conn_count"), u32_at(bag.bytes(), value_at(bag.bytes(), "conn_count")) + 1);
    EXPECT_NE(bag.error().find("connections and"), std::string::npos) << bag.error();
  }
  {
    Bag bag(path);
    put_u32(bag.bytes(), value_at(bag.bytes(), "size"), u32_at(bag.bytes(), value_at(bag.bytes(), "size")) + 1);
    EXPECT_NE(bag.error().find("record at byte " + std::to_string(chunk_at) + ": an uncompressed chunk"), std::string::npos)
        << bag.error();
  }
  {
    // The first record inside the chunk declares a header longer than the chunk.
    Bag bag(path);
    const std::size_t inner_at = chunk_at + 4 + u32_at(bag.bytes(), chunk_at) + 4;
    put_u32(bag.bytes(), inner_at, 0x7fffffff);
    EXPECT_NE(bag.error().find("record at byte " + std::to_string(inner_at) + ": its header of 2147483647 bytes runs "
                               "past the end of its chunk"),
              std::string::npos)
        << bag.error();
  }
  {
    // The index record after the chunk: its first entry's offset moved by one byte into a record.
    Bag bag(path);
    const std::size_t index_at = next_record(bag.bytes(), chunk_at);
    const std::size_t first_entry = index_at + 4 + u32_at(bag.bytes(), index_at) + 4;
    put_u32(bag.bytes(), first_entry + 8, u32_at(bag.bytes(), first_entry + 8) + 1);
    EXPECT_NE(bag.error().find("record at byte " + std::to_string(index_at) + ": index entry 0 points to no record"),
              std::string::npos)
        << bag.error();
  }
  {
    // The file cut inside its bag header record.
    Bag bag(path);
    bag.bytes().resize(500);
    EXPECT_NE(bag.error().find("truncated or corrupt bag: record at byte 13: its data of"), std::string::npos) << bag.error();
  }
  {
    Bag bag(python_bag("lz4", "--compression lz4", false));
    put_u32(bag.bytes(), value_at(bag.bytes(), "size"), 0x7fffffff);
    EXPECT_NE(bag.error().find("a compressed chunk declares 2147483647 bytes uncompressed"), std::string::npos) << bag.error();
  }
  {
    Bag bag(path);
    bag.bytes() = "#ROSBAG V1.2\n" + bag.bytes().substr(kBagHeaderAt);
    EXPECT_NE(bag.error().find("not a ROS1 bag of format 2.0"), std::string::npos) << bag.error();
  }
}

}  // namespace
}  // namespace vilslam
