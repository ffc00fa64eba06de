#pragma once
// The serialization of ROS 2 messages (OMG CDR as the DDS RTPS encapsulation carries it, what rosbag2 stores
// with serialization_format "cdr"): a 4-byte encapsulation header (0x00 0x00 big-endian, 0x00 0x01
// little-endian, then two option bytes), then each primitive aligned to its own size (at most 8) counted
// from the end of that header; string as uint32 length including the terminating NUL, the characters and
// the NUL; sequence<T> as uint32 count then the elements; T[N] without a count.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "common/time.h"
#include "io/ros_wire.h"  // WireError

namespace vilslam {

class CdrReader {
 public:
  static constexpr bool kHeaderSeq = false;      // ROS 2's std_msgs/Header has no seq
  static constexpr std::size_t kMaxPadding = 7;   // a serialized message may be padded to 8 bytes

  // Reads and checks the encapsulation header (WireError for another representation or too few bytes).
  CdrReader(const std::uint8_t* data, std::size_t size);

  template <typename T>
  T read() {
    static_assert(std::is_arithmetic_v<T>);
    align(sizeof(T));
    std::uint8_t bytes[sizeof(T)];
    std::memcpy(bytes, take(sizeof(T)), sizeof(T));
    if (big_endian_) std::reverse(bytes, bytes + sizeof(T));
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }
  std::string string();
  std::vector<std::uint8_t> bytes();  // sequence<uint8>
  TimeNs time();                      // builtin_interfaces/Time: int32 sec, uint32 nanosec
  // Bytes not read yet.
  std::size_t remaining() const { return size_ - pos_; }

 private:
  void align(std::size_t n);
  const std::uint8_t* take(std::size_t n);
  const std::uint8_t* data_;  // after the encapsulation header: alignment counts from here
  std::size_t size_;
  std::size_t pos_ = 0;
  bool big_endian_ = false;
};

}  // namespace vilslam
