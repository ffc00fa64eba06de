#include "loop/vocabulary.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace vilslam {

std::vector<OrbDescriptor> descriptor_rows(const cv::Mat& descriptors) {
  if (descriptors.empty()) return {};
  if (descriptors.type() != CV_8UC1 || descriptors.cols != 32) {
    throw std::invalid_argument("ORB descriptors must be N x 32 CV_8U, got " + std::to_string(descriptors.rows) +
                                " x " + std::to_string(descriptors.cols) + " of type " +
                                std::to_string(descriptors.type()));
  }
  std::vector<OrbDescriptor> rows(static_cast<std::size_t>(descriptors.rows));
  for (int r = 0; r < descriptors.rows; ++r) std::memcpy(rows[r].data(), descriptors.ptr<std::uint8_t>(r), 32);
  return rows;
}

void validate_vocabulary_config(const VocabularyConfig& config) {
  if (config.branching < 2 || config.branching > 64) throw std::invalid_argument("vocabulary k must be in [2, 64]");
  if (config.levels < 1 || config.levels > 8) throw std::invalid_argument("vocabulary levels must be in [1, 8]");
  if (config.levels * std::log2(config.branching) > 24.0) {
    throw std::invalid_argument("vocabulary k^levels must be at most 2^24 words");
  }
  if (config.max_iterations < 1) throw std::invalid_argument("vocabulary max_iterations must be >= 1");
}

WordId Vocabulary::word_of(const OrbDescriptor& descriptor) const {
  if (nodes_.empty()) throw std::logic_error("word_of on an empty vocabulary");
  const Node* node = &nodes_[0];
  while (node->num_children > 0) {
    const Node* best = &nodes_[node->first_child];
    int best_distance = hamming_distance(descriptor, best->center);
    for (std::uint32_t c = 1; c < node->num_children; ++c) {
      const Node& child = nodes_[node->first_child + c];
      const int d = hamming_distance(descriptor, child.center);
      if (d < best_distance) {
        best_distance = d;
        best = &child;
      }
    }
    node = best;
  }
  return static_cast<WordId>(node->word);
}

BowVector Vocabulary::transform(const cv::Mat& descriptors) const {
  const std::vector<OrbDescriptor> rows = descriptor_rows(descriptors);
  BowVector counts;
  for (const OrbDescriptor& d : rows) counts[word_of(d)] += 1.0;
  // DBoW2 TF-IDF: v_i = (n_i / n) * log(N / N_i); the 1/n cancels in the L1 normalization.
  BowVector v;
  double sum = 0;
  for (const auto& [word, count] : counts) {
    const double weight = count * idf_[word];
    if (weight > 0) {
      v.emplace(word, weight);
      sum += weight;
    }
  }
  for (auto& entry : v) entry.second /= sum;
  return v;
}

double bow_score(const BowVector& v, const BowVector& w) {
  double sum_v = 0, sum_w = 0;
  for (const auto& e : v) sum_v += std::abs(e.second);
  for (const auto& e : w) sum_w += std::abs(e.second);
  if (sum_v <= 0 || sum_w <= 0) return 0;
  // |a - b|_1 over the union of words, walking both sorted maps once.
  double l1 = 0;
  auto a = v.begin();
  auto b = w.begin();
  while (a != v.end() || b != w.end()) {
    if (b == w.end() || (a != v.end() && a->first < b->first)) {
      l1 += std::abs(a->second / sum_v);
      ++a;
    } else if (a == v.end() || b->first < a->first) {
      l1 += std::abs(b->second / sum_w);
      ++b;
    } else {
      l1 += std::abs(a->second / sum_v - b->second / sum_w);
      ++a;
      ++b;
    }
  }
  const double s = 1.0 - 0.5 * l1;
  return s < 0 ? 0 : (s > 1 ? 1 : s);
}

}  // namespace vilslam
