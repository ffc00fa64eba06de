#include "io/cdr_reader.h"

namespace vilslam {

CdrReader::CdrReader(const std::uint8_t* data, std::size_t size) {
  if (size < 4) throw WireError("CDR message of " + std::to_string(size) + " bytes has no encapsulation header");
  if (data[0] != 0 || data[1] > 1) {
    throw WireError("CDR encapsulation " + std::to_string(data[0]) + " " + std::to_string(data[1]) +
                    " is not plain CDR (0 0 big-endian, 0 1 little-endian)");
  }
  big_endian_ = data[1] == 0;
  data_ = data + 4;
  size_ = size - 4;
}

void CdrReader::align(std::size_t n) {
  take((n - pos_ % n) % n);
}

const std::uint8_t* CdrReader::take(std::size_t n) {
  if (n > size_ - pos_) {
    throw WireError("message truncated: needs " + std::to_string(n) + " more bytes at offset " + std::to_string(pos_ + 4) +
                    " of " + std::to_string(size_ + 4));
  }
  const std::uint8_t* p = data_ + pos_;
  pos_ += n;
  return p;
}

std::string CdrReader::string() {
  const auto n = read<std::uint32_t>();
  if (n == 0) return {};  // some writers leave out the NUL of an empty string
  const auto* p = take(n);
  if (p[n - 1] != 0) throw WireError("CDR string of " + std::to_string(n) + " bytes without its terminating NUL");
  return std::string(reinterpret_cast<const char*>(p), n - 1);
}

std::vector<std::uint8_t> CdrReader::bytes() {
  const auto n = read<std::uint32_t>();
  const auto* p = take(n);
  return std::vector<std::uint8_t>(p, p + n);
}

TimeNs CdrReader::time() {
  const auto sec = read<std::int32_t>();
  const auto nsec = read<std::uint32_t>();
  if (nsec >= kNsPerSecond) throw WireError("time with nanosec " + std::to_string(nsec) + " >= 1e9");
  if (sec < 0) throw WireError("time with negative sec " + std::to_string(sec));
  return static_cast<TimeNs>(sec) * kNsPerSecond + nsec;
}

}  // namespace vilslam
