// PCD codec: reads DATA binary and ascii (FIELDS/SIZE/TYPE/COUNT; x y z, optional intensity, other fields
// skipped), rejects binary_compressed with a clear message, writes DATA binary x y z intensity.
#include "common/error.h"
#include "io/cloud_formats.h"

namespace vilslam::cloud_detail {

namespace {

struct Header {
  std::vector<std::string> fields;
  std::vector<std::size_t> sizes;
  std::vector<char> types;
  std::vector<std::size_t> counts;
  std::size_t width = 0, height = 1, points = 0;
  bool have_points = false;
  std::string data;
  std::size_t payload_begin = 0;
  long lines = 0;
};

std::size_t parse_count(const std::string& path, const std::string& word, long line) {
  char* stop = nullptr;
  const unsigned long long v = std::strtoull(word.c_str(), &stop, 10);
  if (word.empty() || *stop != '\0' || word[0] == '-') throw InputError(path, "bad header: not a count: " + word, line);
  return static_cast<std::size_t>(v);
}

Header parse_header(const std::string& path, const std::string& bytes) {
  Header h;
  std::size_t pos = 0;
  while (h.data.empty()) {
    const std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) throw InputError(path, "bad header: no DATA line", h.lines + 1);
    const std::vector<std::string> w = split_words(bytes.substr(pos, end - pos));
    pos = end + 1;
    ++h.lines;
    if (w.empty() || w[0][0] == '#') continue;
    const std::string& key = w[0];
    const auto counts = [&]() {
      std::vector<std::size_t> v;
      for (std::size_t i = 1; i < w.size(); ++i) v.push_back(parse_count(path, w[i], h.lines));
      return v;
    };
    if (key == "VERSION" || key == "VIEWPOINT") continue;
    if (key == "FIELDS") {
      h.fields.assign(w.begin() + 1, w.end());
    } else if (key == "SIZE") {
      h.sizes = counts();
    } else if (key == "COUNT") {
      h.counts = counts();
    } else if (key == "TYPE") {
      for (std::size_t i = 1; i < w.size(); ++i) h.types.push_back(w[i].size() == 1 ? w[i][0] : '?');
    } else if (key == "WIDTH" && w.size() == 2) {
      h.width = parse_count(path, w[1], h.lines);
    } else if (key == "HEIGHT" && w.size() == 2) {
      h.height = parse_count(path, w[1], h.lines);
    } else if (key == "POINTS" && w.size() == 2) {
      h.points = parse_count(path, w[1], h.lines);
      h.have_points = true;
    } else if (key == "DATA" && w.size() == 2) {
      h.data = w[1];
    } else {
      throw InputError(path, "bad header: unexpected line starting with '" + key + "'", h.lines);
    }
  }
  if (!h.have_points) h.points = h.width * h.height;
  if (h.counts.empty()) h.counts.assign(h.fields.size(), 1);
  if (h.fields.empty() || h.sizes.size() != h.fields.size() || h.types.size() != h.fields.size() ||
      h.counts.size() != h.fields.size()) {
    throw InputError(path, "bad header: FIELDS, SIZE, TYPE and COUNT must list the same number of entries");
  }
  if (h.data == "binary_compressed") {
    throw InputError(path, "DATA binary_compressed is unsupported (re-save the cloud as binary or ascii PCD)");
  }
  if (h.data != "binary" && h.data != "ascii") throw InputError(path, "bad header: unknown DATA '" + h.data + "'");
  h.payload_begin = pos;
  return h;
}

Scalar pcd_scalar(const std::string& path, char type, std::size_t size) {
  if (type == 'F' && size == 4) return Scalar::kF32;
  if (type == 'F' && size == 8) return Scalar::kF64;
  if (type == 'I' && size == 1) return Scalar::kI8;
  if (type == 'I' && size == 2) return Scalar::kI16;
  if (type == 'I' && size == 4) return Scalar::kI32;
  if (type == 'U' && size == 1) return Scalar::kU8;
  if (type == 'U' && size == 2) return Scalar::kU16;
  if (type == 'U' && size == 4) return Scalar::kU32;
  throw InputError(path, std::string("bad header: unsupported field type ") + type + std::to_string(size));
}

}  // namespace

PointCloud decode_pcd(const std::string& path, const std::string& bytes) {
  const Header h = parse_header(path, bytes);
  const bool ascii = h.data == "ascii";
  RecordLayout layout;
  bool found[4] = {false, false, false, false};
  for (std::size_t f = 0; f < h.fields.size(); ++f) {
    const std::string& name = h.fields[f];
    const int slot = name == "x" ? 0 : name == "y" ? 1 : name == "z" ? 2 : name == "intensity" ? 3 : -1;
    if (slot >= 0 && !found[slot]) {
      found[slot] = true;
      layout.offset[slot] = layout.stride;
      layout.type[slot] = pcd_scalar(path, h.types[f], h.sizes[f]);
    }
    layout.stride += ascii ? h.counts[f] : h.sizes[f] * h.counts[f];
  }
  if (!found[0] || !found[1] || !found[2]) throw InputError(path, "bad header: FIELDS lacks x, y or z");
  layout.has_intensity = found[3];
  return ascii ? decode_ascii(path, bytes, h.payload_begin, h.points, layout, h.lines + 1)
               : decode_binary(path, bytes, h.payload_begin, h.points, layout);
}

std::string encode_pcd(const PointCloud& cloud) {
  const std::string n = std::to_string(cloud.size());
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\n"
         "TYPE F F F F\nCOUNT 1 1 1 1\nWIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n +
         "\nDATA binary\n" + pack_xyzi(cloud);
}

}  // namespace vilslam::cloud_detail
