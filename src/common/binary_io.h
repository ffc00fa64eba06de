#pragma once
// Little-endian binary files as the host writes them (x86-64 / aarch64): fields appended to a byte string, and
// a reader whose every overrun is an InputError naming the file ("truncated file: ends inside ...").
#include <cstring>
#include <utility>
#include <string>

#include "common/error.h"

namespace vilslam {

template <typename T>
void put_binary(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

class BinaryReader {
 public:
  // bytes must outlive the reader.
  BinaryReader(std::string path, const std::string& bytes) : path_(std::move(path)), bytes_(bytes) {}

  template <typename T>
  T get(const char* what) {
    T value;
    take(&value, sizeof(T), what);
    return value;
  }
  void take(void* dst, std::size_t n, const char* what) {
    if (bytes_.size() - pos_ < n) fail(std::string("truncated file: ends inside ") + what);
    std::memcpy(dst, bytes_.data() + pos_, n);
    pos_ += n;
  }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(path_, problem); }

 private:
  std::string path_;
  const std::string& bytes_;
  std::size_t pos_ = 0;
};

}  // namespace vilslam
