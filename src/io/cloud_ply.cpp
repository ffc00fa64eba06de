// PLY codec: reads binary_little_endian and ascii (vertex x y z, optional intensity, ring, time; other properties and
// elements skipped by their declared types), writes binary_little_endian x y z intensity.
#include <map>
#include <optional>

#include "common/error.h"
#include "io/cloud_formats.h"

namespace vilslam::cloud_detail {

namespace {

struct Property {
  std::string name;
  Scalar type = Scalar::kF32;
  bool is_list = false;
  Scalar count_type = Scalar::kU8;  // list properties only
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  bool ascii = false;
  std::vector<Element> elements;
  std::size_t payload_begin = 0;
  long lines = 0;  // header lines, including end_header
};

std::optional<Scalar> ply_scalar(const std::string& name) {
  static const std::map<std::string, Scalar> kTypes = {
      {"char", Scalar::kI8},     {"int8", Scalar::kI8},     {"uchar", Scalar::kU8},   {"uint8", Scalar::kU8},
      {"short", Scalar::kI16},   {"int16", Scalar::kI16},   {"ushort", Scalar::kU16}, {"uint16", Scalar::kU16},
      {"int", Scalar::kI32},     {"int32", Scalar::kI32},   {"uint", Scalar::kU32},   {"uint32", Scalar::kU32},
      {"float", Scalar::kF32},   {"float32", Scalar::kF32}, {"double", Scalar::kF64}, {"float64", Scalar::kF64}};
  const auto it = kTypes.find(name);
  if (it == kTypes.end()) return std::nullopt;
  return it->second;
}

Header parse_header(const std::string& path, const std::string& bytes) {
  Header header;
  std::size_t pos = 0;
  bool have_format = false;
  while (true) {
    const std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) throw InputError(path, "bad header: no end_header line", header.lines + 1);
    std::string line = bytes.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end + 1;
    ++header.lines;
    const std::vector<std::string> w = split_words(line);
    const auto fail = [&](const std::string& problem) { throw InputError(path, "bad header: " + problem, header.lines); };
    if (header.lines == 1) {
      if (line != "ply") fail("first line must be 'ply'");
      continue;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() < 2) fail("incomplete format line");
      if (w[1] == "ascii") {
        header.ascii = true;
      } else if (w[1] != "binary_little_endian") {
        fail("unsupported format '" + w[1] + "' (binary_little_endian and ascii are supported)");
      }
      have_format = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) fail("element line needs a name and a count");
      header.elements.push_back({w[1], static_cast<std::size_t>(std::strtoull(w[2].c_str(), nullptr, 10)), {}});
    } else if (w[0] == "property") {
      if (header.elements.empty()) fail("property before any element");
      Property p;
      if (w.size() == 5 && w[1] == "list") {
        const auto count_type = ply_scalar(w[2]);
        const auto item_type = ply_scalar(w[3]);
        if (!count_type || !item_type) fail("unknown list property type");
        p = {w[4], *item_type, true, *count_type};
      } else if (w.size() == 3) {
        const auto type = ply_scalar(w[1]);
        if (!type) fail("unknown property type '" + w[1] + "'");
        p = {w[2], *type, false, Scalar::kU8};
      } else {
        fail("malformed property line");
      }
      header.elements.back().properties.push_back(p);
    } else {
      fail("unknown keyword '" + w[0] + "'");
    }
  }
  if (!have_format) throw InputError(path, "bad header: no format line");
  header.payload_begin = pos;
  return header;
}

// Byte length of one binary record at bytes[at] of an element that precedes the vertices (list lengths read
// in place); throws when the record runs past the end of the file.
std::size_t binary_record_size(const std::string& path, const std::string& bytes, std::size_t at, const Element& e) {
  const std::size_t available = bytes.size() - at;  // at <= bytes.size()
  std::size_t size = 0;
  for (const Property& p : e.properties) {
    std::size_t n = 1;
    if (p.is_list) {
      if (scalar_size(p.count_type) > available - size) throw InputError(path, "truncated payload");
      const double length = load_scalar(bytes.data() + at + size, p.count_type);
      if (!(length >= 0 && length <= static_cast<double>(available))) {
        throw InputError(path, "bad list length in element '" + e.name + "'");
      }
      n = static_cast<std::size_t>(length);
      size += scalar_size(p.count_type);
    }
    if (n > (available - size) / scalar_size(p.type)) throw InputError(path, "truncated payload");
    size += n * scalar_size(p.type);
  }
  return size;
}

// The offset after `e.count` binary records of an element that precedes the vertices. Each record is checked
// against the file's end, so a count the file cannot hold ends at the end of the file, not after count steps.
std::size_t skip_binary_records(const std::string& path, const std::string& bytes, std::size_t begin,
                                const Element& e) {
  for (std::size_t i = 0; i < e.count; ++i) {
    const std::size_t size = binary_record_size(path, bytes, begin, e);
    if (size == 0) break;  // records without properties take no bytes, however many there are
    begin += size;
  }
  return begin;
}

}  // namespace

PointCloud decode_ply(const std::string& path, const std::string& bytes) {
  const Header header = parse_header(path, bytes);
  std::size_t begin = header.payload_begin;
  long line = header.lines + 1;
  for (const Element& e : header.elements) {
    if (e.name != "vertex") {
      if (!header.ascii) {
        begin = skip_binary_records(path, bytes, begin, e);
        continue;
      }
      for (std::size_t i = 0; i < e.count; ++i) {
        const std::size_t end = bytes.find('\n', begin);
        if (end == std::string::npos) throw InputError(path, "truncated payload", line);
        begin = end + 1;
        ++line;
      }
      continue;
    }
    RecordLayout layout;
    for (const Property& p : e.properties) {
      if (p.is_list) throw InputError(path, "bad header: list property '" + p.name + "' in vertex element");
      layout.add_field(p.name, p.type, header.ascii ? 1 : scalar_size(p.type));
    }
    if (!layout.has[kX] || !layout.has[kY] || !layout.has[kZ]) {
      throw InputError(path, "bad header: vertex element lacks x, y or z");
    }
    return header.ascii ? decode_ascii(path, bytes, begin, e.count, layout, line)
                        : decode_binary(path, bytes, begin, e.count, layout);
  }
  throw InputError(path, "bad header: no vertex element");
}

std::string encode_ply(const PointCloud& cloud) {
  return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(cloud.size()) +
         "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\nend_header\n" +
         pack_xyzi(cloud);
}

}  // namespace vilslam::cloud_detail
