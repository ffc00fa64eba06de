#pragma once
// Hierarchical bag-of-words vocabulary over ORB descriptors (Galvez-Lopez and Tardos, "Bags of Binary
// Words", DBoW2): a k-ary tree of `levels` levels trained by k-medians, whose leaves are the words,
// each weighted by its inverse document frequency over the training images.
#include <cstdint>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "loop/binary_descriptor.h"

namespace vilslam {

using WordId = std::uint32_t;
// Sparse TF-IDF weights by word, L1-normalized (sum of weights 1, or empty).
using BowVector = std::map<WordId, double>;

struct VocabularyConfig {
  int branching = 10;       // k children per node
  int levels = 4;           // depth of the tree: at most k^levels words
  std::uint64_t seed = 1;   // k-means++ seeding (std::mt19937_64)
  int max_iterations = 20;  // k-medians iterations per node (stops earlier when assignments settle)
};

// Throws std::invalid_argument when a value is out of range (k in [2, 64], levels in [1, 8],
// k^levels <= 2^24 words, max_iterations >= 1).
void validate_vocabulary_config(const VocabularyConfig& config);

class Vocabulary {
 public:
  struct Node {
    OrbDescriptor center{};  // bitwise median of the descriptors below (unused for the root)
    std::uint32_t first_child = 0;
    std::uint32_t num_children = 0;  // 0 for a leaf
    std::int64_t word = -1;          // word id of a leaf, -1 otherwise
    bool operator==(const Node& o) const {
      return center == o.center && first_child == o.first_child && num_children == o.num_children && word == o.word;
    }
  };

  Vocabulary() = default;

  // Trains on the descriptors of each training image (N x 32 CV_8U each). Deterministic: the same
  // descriptors and config give the same tree bit for bit. Throws std::invalid_argument when there
  // are no descriptors at all.
  static Vocabulary train(const std::vector<cv::Mat>& image_descriptors, const VocabularyConfig& config);

  // The word of one descriptor: the closest child (Hamming) from the root down to a leaf.
  WordId word_of(const OrbDescriptor& descriptor) const;
  // TF-IDF bag of words of one image's descriptors, L1-normalized.
  BowVector transform(const cv::Mat& descriptors) const;

  int branching() const { return branching_; }
  int levels() const { return levels_; }
  std::size_t num_words() const { return idf_.size(); }
  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<double>& idf() const { return idf_; }
  bool empty() const { return nodes_.empty(); }

  // Binary file: magic, version, k, levels, nodes, IDF weights. Written atomically.
  void save(const std::string& path) const;
  // Throws InputError(path, problem) when the file is missing, truncated or inconsistent.
  static Vocabulary load(const std::string& path);

  bool operator==(const Vocabulary& o) const {
    return branching_ == o.branching_ && levels_ == o.levels_ && nodes_ == o.nodes_ && idf_ == o.idf_;
  }

 private:
  Vocabulary(int branching, int levels, std::vector<Node> nodes, std::vector<double> idf)
      : branching_(branching), levels_(levels), nodes_(std::move(nodes)), idf_(std::move(idf)) {}

  int branching_ = 0;
  int levels_ = 0;
  std::vector<Node> nodes_;  // nodes_[0] is the root; children of a node are contiguous
  std::vector<double> idf_;  // by word id
};

// DBoW2's L1 score: s = 1 - 0.5 |v/|v| - w/|w||_1, in [0, 1] (1 for equal vectors, 0 without common words).
double bow_score(const BowVector& v, const BowVector& w);

}  // namespace vilslam
