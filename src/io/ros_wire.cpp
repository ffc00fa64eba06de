#include "io/ros_wire.h"

namespace vilslam {

const std::uint8_t* WireReader::take(std::size_t n) {
  if (n > size_ - pos_) {
    throw WireError("message truncated: needs " + std::to_string(n) + " more bytes at offset " + std::to_string(pos_) +
                    " of " + std::to_string(size_));
  }
  const std::uint8_t* p = data_ + pos_;
  pos_ += n;
  return p;
}

std::string WireReader::string() {
  const auto n = read<std::uint32_t>();
  const auto* p = take(n);
  return std::string(reinterpret_cast<const char*>(p), n);
}

std::vector<std::uint8_t> WireReader::bytes() {
  const auto n = read<std::uint32_t>();
  const auto* p = take(n);
  return std::vector<std::uint8_t>(p, p + n);
}

TimeNs WireReader::time() {
  const auto sec = read<std::uint32_t>();
  const auto nsec = read<std::uint32_t>();
  if (nsec >= kNsPerSecond) throw WireError("time with nsec " + std::to_string(nsec) + " >= 1e9");
  return static_cast<TimeNs>(sec) * kNsPerSecond + nsec;
}

void WireWriter::string(const std::string& s) {
  bytes(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
}

void WireWriter::bytes(const std::uint8_t* data, std::size_t n) {
  write(static_cast<std::uint32_t>(n));
  bytes_.insert(bytes_.end(), data, data + n);
}

void WireWriter::time(TimeNs t_ns) {
  if (t_ns < 0 || t_ns / kNsPerSecond > 0xffffffffLL) throw std::invalid_argument("time outside the ROS time range");
  write(static_cast<std::uint32_t>(t_ns / kNsPerSecond));
  write(static_cast<std::uint32_t>(t_ns % kNsPerSecond));
}

}  // namespace vilslam
