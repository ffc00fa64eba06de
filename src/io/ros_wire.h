#pragma once
// The ROS1 serialization format (wiki.ros.org/roscpp/Overview/MessagesSerializationAndAdaptingTypes,
// wiki.ros.org/msg): numbers little-endian at their natural size, no padding; string and T[] carry a
// uint32 length prefix, T[N] none; time is uint32 sec + uint32 nsec.
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "common/time.h"

namespace vilslam {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "ROS1 messages are little-endian; so must the host be");

// A message whose bytes end early or hold an impossible value; the caller names the file and topic.
class WireError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class WireReader {
 public:
  static constexpr bool kHeaderSeq = true;       // std_msgs/Header starts with uint32 seq
  static constexpr std::size_t kMaxPadding = 0;   // a message ends with its last field

  WireReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  template <typename T>
  T read() {
    static_assert(std::is_arithmetic_v<T>);
    T value;
    std::memcpy(&value, take(sizeof(T)), sizeof(T));
    return value;
  }
  std::string string();
  std::vector<std::uint8_t> bytes();  // uint8[]
  TimeNs time();                      // sec, nsec (nsec < 1e9)
  std::size_t remaining() const { return size_ - pos_; }

 private:
  const std::uint8_t* take(std::size_t n);
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

class WireWriter {
 public:
  template <typename T>
  void write(T value) {
    static_assert(std::is_arithmetic_v<T>);
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void string(const std::string& s);
  void bytes(const std::uint8_t* data, std::size_t n);  // uint8[]
  void time(TimeNs t_ns);                               // t_ns >= 0
  const std::vector<std::uint8_t>& data() const { return bytes_; }
  std::vector<std::uint8_t> release() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

}  // namespace vilslam
