// Vocabulary file: "VILSLAM_VOCAB" magic, u32 version, i32 k, i32 levels, u32 node count, nodes
// (32-byte center, u32 first_child, u32 num_children, i64 word), u32 word count, f64 IDF per word.
// Little-endian, as written by the host (x86-64 / aarch64).
#include <cmath>
#include <fstream>
#include <iterator>

#include "common/binary_io.h"
#include "common/error.h"
#include "common/json_writer.h"
#include "loop/vocabulary.h"

namespace vilslam {
namespace {

constexpr char kMagic[] = "VILSLAM_VOCAB";
constexpr std::size_t kMagicSize = sizeof(kMagic) - 1;
constexpr std::uint32_t kVersion = 1;

// Structure checks: children lie after their parent and inside the array (a tree, no cycles), only
// leaves carry words, word ids are 0..W-1 each once, and fan-out respects k.
void check_tree(const BinaryReader& in, const std::vector<Vocabulary::Node>& nodes, std::size_t num_words, int k) {
  std::vector<bool> seen(num_words, false);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Vocabulary::Node& n = nodes[i];
    if (n.num_children > static_cast<std::uint32_t>(k))
      in.fail("node " + std::to_string(i) + " has more than k children");
    if (n.num_children > 0) {
      if (n.first_child <= i || n.first_child + static_cast<std::uint64_t>(n.num_children) > nodes.size()) {
        in.fail("node " + std::to_string(i) + " has children out of range");
      }
      if (n.word != -1) in.fail("inner node " + std::to_string(i) + " carries a word");
    } else {
      if (n.word < 0 || static_cast<std::uint64_t>(n.word) >= num_words || seen[n.word]) {
        in.fail("leaf " + std::to_string(i) + " has a bad word id");
      }
      seen[n.word] = true;
    }
  }
  for (bool s : seen) {
    if (!s) in.fail("a word has no leaf");
  }
}

}  // namespace

void Vocabulary::save(const std::string& path) const {
  std::string out(kMagic, kMagicSize);
  put_binary(out, kVersion);
  put_binary(out, static_cast<std::int32_t>(branching_));
  put_binary(out, static_cast<std::int32_t>(levels_));
  put_binary(out, static_cast<std::uint32_t>(nodes_.size()));
  for (const Node& n : nodes_) {
    out.append(reinterpret_cast<const char*>(n.center.data()), n.center.size());
    put_binary(out, n.first_child);
    put_binary(out, n.num_children);
    put_binary(out, n.word);
  }
  put_binary(out, static_cast<std::uint32_t>(idf_.size()));
  for (double w : idf_) put_binary(out, w);
  write_file_atomic(path, out);
}

Vocabulary Vocabulary::load(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, "cannot open vocabulary file");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  BinaryReader in(path, bytes);

  char magic[kMagicSize];
  in.take(magic, kMagicSize, "the magic string");
  if (std::string(magic, kMagicSize) != kMagic) in.fail("not a vilslam vocabulary (bad magic string)");
  const auto version = in.get<std::uint32_t>("the version");
  if (version != kVersion) in.fail("unsupported vocabulary version " + std::to_string(version));
  const auto k = in.get<std::int32_t>("the header");
  const auto levels = in.get<std::int32_t>("the header");
  if (k < 2 || k > 64 || levels < 1 || levels > 8) in.fail("bad k or levels in the header");
  const auto num_nodes = in.get<std::uint32_t>("the header");
  constexpr std::size_t kNodeBytes = 32 + 4 + 4 + 8;
  if (num_nodes == 0 || num_nodes > in.remaining() / kNodeBytes) in.fail("truncated file: node count exceeds the file");
  std::vector<Node> nodes(num_nodes);
  for (Node& n : nodes) {
    in.take(n.center.data(), n.center.size(), "a node");
    n.first_child = in.get<std::uint32_t>("a node");
    n.num_children = in.get<std::uint32_t>("a node");
    n.word = in.get<std::int64_t>("a node");
  }
  const auto num_words = in.get<std::uint32_t>("the word count");
  if (num_words > in.remaining() / sizeof(double)) in.fail("truncated file: word count exceeds the file");
  std::vector<double> idf(num_words);
  for (double& w : idf) {
    w = in.get<double>("the IDF weights");
    if (!std::isfinite(w) || w < 0) in.fail("IDF weight not finite and non-negative");
  }
  if (in.remaining() != 0) in.fail(std::to_string(in.remaining()) + " unexpected bytes after the IDF weights");
  check_tree(in, nodes, num_words, k);
  return Vocabulary(k, levels, std::move(nodes), std::move(idf));
}

}  // namespace vilslam
