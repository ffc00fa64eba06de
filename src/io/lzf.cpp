#include "io/lzf.h"

#include <cstdint>

namespace vilslam {
namespace {

[[noreturn]] void fail(const std::string& problem, std::size_t at) {
  throw LzfError("LZF data corrupt at compressed byte " + std::to_string(at) + ": " + problem);
}

}  // namespace

std::string lzf_decompress(const char* in, std::size_t size, std::size_t expected_size) {
  // The longest chunk, a back reference of 7 + 255 + 2 bytes, takes 3 input bytes.
  constexpr std::size_t kMaxExpansion = 88;
  if (expected_size / kMaxExpansion > size) {
    throw LzfError("LZF data of " + std::to_string(size) + " bytes cannot expand to the expected " +
                   std::to_string(expected_size) + " bytes");
  }
  const auto* data = reinterpret_cast<const std::uint8_t*>(in);
  std::string out(expected_size, '\0');
  std::size_t ip = 0;  // next input byte
  std::size_t op = 0;  // next output byte
  const auto need_output = [&](std::size_t n, std::size_t chunk) {
    if (n > expected_size - op) {
      fail("output would exceed the expected " + std::to_string(expected_size) + " bytes", chunk);
    }
  };
  while (ip < size) {
    const std::size_t chunk = ip;
    const unsigned ctrl = data[ip++];
    if (ctrl < 32) {
      const std::size_t len = ctrl + 1;
      if (len > size - ip) fail("literal run of " + std::to_string(len) + " bytes is truncated", chunk);
      need_output(len, chunk);
      out.replace(op, len, in + ip, len);
      ip += len;
      op += len;
      continue;
    }
    std::size_t len = ctrl >> 5;
    if (len == 7) {
      if (ip >= size) fail("back reference is truncated", chunk);
      len += data[ip++];
    }
    if (ip >= size) fail("back reference is truncated", chunk);
    const std::size_t distance = ((static_cast<std::size_t>(ctrl & 31) << 8) | data[ip++]) + 1;
    len += 2;
    if (distance > op) {
      fail("back reference " + std::to_string(distance) + " bytes before the start of the output", chunk);
    }
    need_output(len, chunk);
    for (std::size_t k = 0; k < len; ++k, ++op) out[op] = out[op - distance];
  }
  if (op != expected_size) {
    throw LzfError("LZF data ends after " + std::to_string(op) + " of the expected " + std::to_string(expected_size) +
                   " bytes");
  }
  return out;
}

}  // namespace vilslam
