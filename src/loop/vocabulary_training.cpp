// Vocabulary::train: hierarchical k-medians with k-means++ seeding (DBoW2), then IDF weights.
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

#include "loop/vocabulary.h"

namespace vilslam {
namespace {

using Indices = std::vector<std::uint32_t>;

// Bitwise majority of the selected descriptors: the median under the Hamming distance, bit by bit.
OrbDescriptor majority_center(const std::vector<OrbDescriptor>& all, const Indices& members) {
  std::array<std::uint32_t, 256> ones{};
  for (std::uint32_t m : members) {
    for (int bit = 0; bit < 256; ++bit) ones[bit] += (all[m][bit / 8] >> (7 - bit % 8)) & 1u;
  }
  OrbDescriptor center{};
  for (int bit = 0; bit < 256; ++bit) {
    if (2 * ones[bit] > members.size()) center[bit / 8] |= static_cast<std::uint8_t>(1u << (7 - bit % 8));
  }
  return center;
}

std::size_t nearest_center(const OrbDescriptor& d, const std::vector<OrbDescriptor>& centers) {
  std::size_t best = 0;
  int best_distance = hamming_distance(d, centers[0]);
  for (std::size_t c = 1; c < centers.size(); ++c) {
    const int dist = hamming_distance(d, centers[c]);
    if (dist < best_distance) {
      best_distance = dist;
      best = c;
    }
  }
  return best;
}

// k-means++ (Arthur and Vassilvitskii 2007): each next seed drawn with probability proportional to the
// squared distance to the nearest seed so far. Integer arithmetic keeps it bit-exact everywhere.
std::vector<OrbDescriptor> seed_centers(const std::vector<OrbDescriptor>& all, const Indices& members, int k,
                                        std::mt19937_64& rng) {
  std::vector<OrbDescriptor> centers{all[members[rng() % members.size()]]};
  std::vector<std::uint64_t> nearest_sq(members.size());
  for (std::size_t i = 0; i < members.size(); ++i) {
    const std::uint64_t d = static_cast<std::uint64_t>(hamming_distance(all[members[i]], centers[0]));
    nearest_sq[i] = d * d;
  }
  while (static_cast<int>(centers.size()) < k) {
    std::uint64_t total = 0;
    for (std::uint64_t d : nearest_sq) total += d;
    if (total == 0) break;  // every descriptor already coincides with a seed
    const std::uint64_t target = rng() % total;
    std::size_t pick = 0;
    std::uint64_t cumulative = nearest_sq[0];
    while (cumulative <= target) cumulative += nearest_sq[++pick];
    centers.push_back(all[members[pick]]);
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::uint64_t d = static_cast<std::uint64_t>(hamming_distance(all[members[i]], centers.back()));
      nearest_sq[i] = std::min(nearest_sq[i], d * d);
    }
  }
  return centers;
}

// Clusters of one node's descriptors: k-medians from k-means++ seeds until the assignment settles.
// Returns the non-empty clusters with their centers, in seed order.
std::vector<std::pair<OrbDescriptor, Indices>> cluster(const std::vector<OrbDescriptor>& all, const Indices& members,
                                                       const VocabularyConfig& config, std::mt19937_64& rng) {
  std::vector<std::pair<OrbDescriptor, Indices>> clusters;
  if (members.size() <= static_cast<std::size_t>(config.branching)) {
    // DBoW2: too few descriptors to cluster, each one is its own cluster.
    for (std::uint32_t m : members) clusters.push_back({all[m], Indices{m}});
    return clusters;
  }
  std::vector<OrbDescriptor> centers = seed_centers(all, members, config.branching, rng);
  std::vector<std::size_t> assignment(members.size(), centers.size());
  for (int iteration = 0; iteration < config.max_iterations; ++iteration) {
    bool changed = false;
    for (std::size_t i = 0; i < members.size(); ++i) {
      const std::size_t c = nearest_center(all[members[i]], centers);
      changed = changed || c != assignment[i];
      assignment[i] = c;
    }
    if (!changed) break;
    std::vector<Indices> groups(centers.size());
    for (std::size_t i = 0; i < members.size(); ++i) groups[assignment[i]].push_back(members[i]);
    for (std::size_t c = 0; c < centers.size(); ++c) {
      if (!groups[c].empty()) centers[c] = majority_center(all, groups[c]);
    }
  }
  std::vector<Indices> groups(centers.size());
  for (std::size_t i = 0; i < members.size(); ++i) groups[assignment[i]].push_back(members[i]);
  for (std::size_t c = 0; c < centers.size(); ++c) {
    if (!groups[c].empty()) clusters.push_back({centers[c], std::move(groups[c])});
  }
  return clusters;
}

// Grows the children of `parent` (at depth `level`) depth-first; children of a node are contiguous.
void grow(std::vector<Vocabulary::Node>& nodes, std::uint32_t parent, const Indices& members, int level,
          const std::vector<OrbDescriptor>& all, const VocabularyConfig& config, std::mt19937_64& rng) {
  if (level >= config.levels || members.size() <= 1) return;
  std::vector<std::pair<OrbDescriptor, Indices>> clusters = cluster(all, members, config, rng);
  if (clusters.size() <= 1 && level > 0) return;  // a single cluster would only repeat its parent
  nodes[parent].first_child = static_cast<std::uint32_t>(nodes.size());
  nodes[parent].num_children = static_cast<std::uint32_t>(clusters.size());
  for (const auto& c : clusters) {
    Vocabulary::Node child;
    child.center = c.first;
    nodes.push_back(child);
  }
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    grow(nodes, nodes[parent].first_child + static_cast<std::uint32_t>(c), clusters[c].second, level + 1, all, config,
         rng);
  }
}

}  // namespace

Vocabulary Vocabulary::train(const std::vector<cv::Mat>& image_descriptors, const VocabularyConfig& config) {
  validate_vocabulary_config(config);
  std::vector<OrbDescriptor> all;
  std::vector<std::size_t> image_of;
  for (std::size_t image = 0; image < image_descriptors.size(); ++image) {
    for (const OrbDescriptor& d : descriptor_rows(image_descriptors[image])) {
      all.push_back(d);
      image_of.push_back(image);
    }
  }
  if (all.empty()) throw std::invalid_argument("no descriptors to train a vocabulary on");

  std::mt19937_64 rng(config.seed);
  std::vector<Node> nodes(1);
  Indices everything(all.size());
  for (std::uint32_t i = 0; i < everything.size(); ++i) everything[i] = i;
  grow(nodes, 0, everything, 0, all, config, rng);
  // With a single distinct descriptor the root is the only node and the only word.
  std::int64_t words = 0;
  for (Node& node : nodes) {
    if (node.num_children == 0) node.word = words++;
  }

  Vocabulary vocabulary(config.branching, config.levels, std::move(nodes), {});
  // IDF of word i: log(N / N_i), N training images, N_i of them containing the word (DBoW2).
  std::vector<std::set<std::size_t>> images_with(static_cast<std::size_t>(words));
  for (std::size_t i = 0; i < all.size(); ++i) images_with[vocabulary.word_of(all[i])].insert(image_of[i]);
  const double n_images = static_cast<double>(image_descriptors.size());
  vocabulary.idf_.resize(images_with.size());
  for (std::size_t w = 0; w < images_with.size(); ++w) {
    // A word reached by no training descriptor (possible when a median drifts) counts as in one image.
    vocabulary.idf_[w] = std::log(n_images / static_cast<double>(std::max<std::size_t>(1, images_with[w].size())));
  }
  return vocabulary;
}

}  // namespace vilslam
