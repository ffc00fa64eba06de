#include "io/zstd_util.h"

#include <zstd.h>

#include <fstream>
#include <memory>

#include "io/ros_wire.h"  // WireError

namespace vilslam {
namespace {

struct DStreamFree {
  void operator()(ZSTD_DStream* s) const { ZSTD_freeDStream(s); }
};

// Feeds all of `in` to the stream and hands each decompressed block to sink, until the input is used up and
// the stream holds nothing more (an output block left unfilled). last: the stream's last hint (0: a frame ended).
template <typename Sink>
void decompress_stream(ZSTD_DStream* stream, ZSTD_inBuffer& in, std::vector<std::uint8_t>& block, std::size_t& last,
                       Sink sink) {
  while (true) {
    ZSTD_outBuffer out{block.data(), block.size(), 0};
    last = ZSTD_decompressStream(stream, &out, &in);
    if (ZSTD_isError(last)) throw WireError(std::string("zstd: ") + ZSTD_getErrorName(last));
    sink(block.data(), out.pos);
    if (in.pos == in.size && out.pos < out.size) return;
  }
}

std::unique_ptr<ZSTD_DStream, DStreamFree> new_stream() {
  std::unique_ptr<ZSTD_DStream, DStreamFree> s(ZSTD_createDStream());
  if (!s || ZSTD_isError(ZSTD_initDStream(s.get()))) throw WireError("zstd: cannot create a decompression stream");
  return s;
}

}  // namespace

std::vector<std::uint8_t> zstd_decompress(const std::uint8_t* data, std::size_t size, std::size_t max_size) {
  auto stream = new_stream();
  std::vector<std::uint8_t> block(ZSTD_DStreamOutSize()), out;
  ZSTD_inBuffer in{data, size, 0};
  std::size_t last = 1;
  decompress_stream(stream.get(), in, block, last, [&](const std::uint8_t* p, std::size_t n) {
    if (n > max_size - out.size()) throw WireError("zstd: more than " + std::to_string(max_size) + " bytes");
    out.insert(out.end(), p, p + n);
  });
  if (last != 0) throw WireError("zstd: the data ends inside a frame");
  return out;
}

void zstd_decompress_file(const std::string& in_path, const std::string& out_path) {
  std::ifstream in_file(in_path, std::ios::binary);
  std::ofstream out_file(out_path, std::ios::binary);
  if (!in_file || !out_file) throw WireError("cannot open " + (in_file ? out_path : in_path));
  auto stream = new_stream();
  std::vector<std::uint8_t> chunk(ZSTD_DStreamInSize()), block(ZSTD_DStreamOutSize());
  std::size_t last = 1;
  while (in_file) {
    in_file.read(reinterpret_cast<char*>(chunk.data()), static_cast<std::streamsize>(chunk.size()));
    ZSTD_inBuffer in{chunk.data(), static_cast<std::size_t>(in_file.gcount()), 0};
    decompress_stream(stream.get(), in, block, last, [&](const std::uint8_t* p, std::size_t n) {
      out_file.write(reinterpret_cast<const char*>(p), static_cast<std::streamsize>(n));
    });
  }
  if (last != 0) throw WireError("zstd: the file ends inside a frame");
  if (!out_file) throw WireError("cannot write " + out_path);
}

}  // namespace vilslam
