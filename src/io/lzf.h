#pragma once
// LZF decompression (Marc Lehmann's liblzf format), the codec of PCL's `DATA binary_compressed` PCD files.
// The stream is a sequence of chunks, each starting with a control byte c:
//   c < 32:  a literal run: the next c + 1 bytes are copied to the output;
//   c >= 32: a back reference: length L = c >> 5 (if L == 7, L += next byte), distance
//            D = ((c & 31) << 8) + next byte + 1; L + 2 bytes are copied from D bytes back in the
//            output, byte by byte (so a reference may overlap the bytes it produces).
#include <cstddef>
#include <stdexcept>
#include <string>

namespace vilslam {

class LzfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Decompresses `size` bytes at `in`, which must produce exactly `expected_size` bytes. Throws LzfError
// naming the problem and the input offset on a truncated chunk, a reference before the start of the
// output, or an output longer or shorter than expected (an expected size more than 88 times the input,
// more than LZF can encode, is refused before allocating); never reads or writes out of bounds.
std::string lzf_decompress(const char* in, std::size_t size, std::size_t expected_size);

}  // namespace vilslam
