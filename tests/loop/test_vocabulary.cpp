// Vocabulary: k-medians on separable prototypes, tree shape, determinism, scores, file round trip and
// corrupt files.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <random>
#include <set>

#include "common/error.h"
#include "loop/vocabulary.h"
#include "loop_test_data.h"
#include "test_util.h"

namespace vilslam {
namespace {

OrbDescriptor random_descriptor(std::mt19937_64& rng) {
  OrbDescriptor d;
  for (auto& byte : d) byte = static_cast<std::uint8_t>(rng() & 0xff);
  return d;
}

OrbDescriptor flip_bits(OrbDescriptor d, int flips, std::mt19937_64& rng) {
  for (int i = 0; i < flips; ++i) {
    const int bit = static_cast<int>(rng() % 256);
    d[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
  }
  return d;
}

cv::Mat to_mat(const std::vector<OrbDescriptor>& rows) {
  cv::Mat m(static_cast<int>(rows.size()), 32, CV_8U);
  for (int r = 0; r < m.rows; ++r) std::memcpy(m.ptr<std::uint8_t>(r), rows[r].data(), 32);
  return m;
}

// `images` images of `per_image` random descriptors each.
std::vector<cv::Mat> random_images(int images, int per_image, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<cv::Mat> out;
  for (int i = 0; i < images; ++i) {
    std::vector<OrbDescriptor> rows;
    for (int j = 0; j < per_image; ++j) rows.push_back(random_descriptor(rng));
    out.push_back(to_mat(rows));
  }
  return out;
}

VocabularyConfig small_config() {
  VocabularyConfig c;
  c.branching = 8;
  c.levels = 3;
  return c;
}

int depth_of_leaves(const Vocabulary& v, std::uint32_t node, int depth, int* max_depth) {
  const auto& n = v.nodes()[node];
  if (n.num_children == 0) {
    *max_depth = std::max(*max_depth, depth);
    return 1;
  }
  int leaves = 0;
  for (std::uint32_t c = 0; c < n.num_children; ++c)
    leaves += depth_of_leaves(v, n.first_child + c, depth + 1, max_depth);
  return leaves;
}

TEST(Vocabulary, OneLevelFindsSeparatedPrototypesAndTheirMedians) {
  // 8 random prototypes (about 128 bits apart), 40 copies of each with 4 bits flipped.
  std::mt19937_64 rng(7);
  std::vector<OrbDescriptor> prototypes;
  for (int p = 0; p < 8; ++p) prototypes.push_back(random_descriptor(rng));
  std::vector<std::vector<OrbDescriptor>> copies(8);
  std::vector<cv::Mat> images;
  for (int p = 0; p < 8; ++p) {
    for (int i = 0; i < 40; ++i) copies[p].push_back(flip_bits(prototypes[p], 4, rng));
    images.push_back(to_mat(copies[p]));
  }
  VocabularyConfig config;
  config.branching = 8;
  config.levels = 1;
  const Vocabulary v = Vocabulary::train(images, config);
  ASSERT_EQ(v.num_words(), 8u);
  std::set<WordId> words;
  for (int p = 0; p < 8; ++p) {
    const WordId w = v.word_of(prototypes[p]);
    words.insert(w);
    for (const OrbDescriptor& c : copies[p]) EXPECT_EQ(v.word_of(c), w) << "prototype " << p;
    // The bitwise majority of 40 noisy copies is the prototype itself.
    const auto& leaf = v.nodes()[v.nodes()[0].first_child + w];
    EXPECT_EQ(hamming_distance(leaf.center, prototypes[p]), 0) << "prototype " << p;
    // Each word occurs in exactly one of the 8 images: idf = log 8.
    EXPECT_NEAR(v.idf()[w], std::log(8.0), 1e-12);
  }
  EXPECT_EQ(words.size(), 8u);
}

TEST(Vocabulary, TreeShapeRespectsBranchingAndLevels) {
  const Vocabulary v = Vocabulary::train(random_images(8, 200, 3), small_config());
  EXPECT_EQ(v.nodes()[0].num_children, 8u);
  int max_depth = 0;
  const int leaves = depth_of_leaves(v, 0, 0, &max_depth);
  EXPECT_EQ(max_depth, 3);
  EXPECT_EQ(static_cast<std::size_t>(leaves), v.num_words());
  EXPECT_GT(v.num_words(), 64u * 4);  // 1600 descriptors fill most of the 512 leaves
  EXPECT_LE(v.num_words(), 512u);
  for (const auto& n : v.nodes()) EXPECT_LE(n.num_children, 8u);
}

TEST(Vocabulary, SameDescriptorsAndSeedGiveTheSameTree) {
  const auto images = random_images(6, 150, 4);
  const Vocabulary a = Vocabulary::train(images, small_config());
  const Vocabulary b = Vocabulary::train(images, small_config());
  EXPECT_TRUE(a == b);
  VocabularyConfig other = small_config();
  other.seed = 2;
  EXPECT_FALSE(a == Vocabulary::train(images, other));
}

TEST(Vocabulary, TransformIsNormalizedAndScoresOneAgainstItselfSymmetrically) {
  const auto images = random_images(8, 200, 5);
  const Vocabulary v = Vocabulary::train(images, small_config());
  const BowVector a = v.transform(images[0]);
  const BowVector b = v.transform(images[1]);
  double sum = 0;
  for (const auto& e : a) sum += e.second;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(bow_score(a, a), 1.0);
  EXPECT_EQ(bow_score(a, b), bow_score(b, a));
  EXPECT_LT(bow_score(a, b), 0.5);
  EXPECT_EQ(bow_score(a, BowVector{}), 0.0);
  // Scale does not matter: the score normalizes both vectors.
  BowVector a3 = a;
  for (auto& e : a3) e.second *= 3;
  EXPECT_NEAR(bow_score(a3, b), bow_score(a, b), 1e-12);
}

TEST(Vocabulary, ScoreMatchesTheL1Formula) {
  const BowVector v{{1, 0.5}, {2, 0.5}};
  const BowVector w{{2, 0.25}, {3, 0.75}};
  // |v - w|_1 = 0.5 + 0.25 + 0.75 = 1.5 -> s = 1 - 0.75.
  EXPECT_DOUBLE_EQ(bow_score(v, w), 0.25);
}

TEST(Vocabulary, BadConfigAndDescriptorsAreRejected) {
  VocabularyConfig c = small_config();
  c.branching = 1;
  EXPECT_THROW(Vocabulary::train(random_images(2, 10, 1), c), std::invalid_argument);
  EXPECT_THROW(Vocabulary::train({cv::Mat(0, 32, CV_8U)}, small_config()), std::invalid_argument);
  EXPECT_THROW(Vocabulary::train({cv::Mat(5, 16, CV_8U)}, small_config()), std::invalid_argument);
  EXPECT_THROW(Vocabulary::train({cv::Mat(5, 32, CV_32F)}, small_config()), std::invalid_argument);
}

TEST(Vocabulary, SaveLoadRoundTripIsExact) {
  const auto dir = test::temp_dir();
  const Vocabulary v = Vocabulary::train(random_images(6, 150, 6), small_config());
  const std::string path = (dir / "voc.bin").string();
  v.save(path);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  const Vocabulary loaded = Vocabulary::load(path);
  EXPECT_TRUE(loaded == v);
  const auto images = random_images(1, 100, 9);
  EXPECT_EQ(loaded.transform(images[0]), v.transform(images[0]));
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << bytes;
}

void expect_input_error(const std::string& path, const std::string& problem_part) {
  try {
    Vocabulary::load(path);
    ADD_FAILURE() << "no InputError for " << problem_part;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(std::string(e.what()).find(problem_part), std::string::npos) << e.what();
  }
}

TEST(Vocabulary, TruncatedAndCorruptFilesThrowInputError) {
  const auto dir = test::temp_dir();
  const std::string good = (dir / "voc.bin").string();
  Vocabulary::train(random_images(6, 150, 6), small_config()).save(good);
  const std::string bytes = test::read_file_bytes(good);
  const std::string bad = (dir / "bad.bin").string();

  expect_input_error((dir / "missing.bin").string(), "cannot open");
  for (std::size_t cut : {std::size_t{0}, std::size_t{5}, std::size_t{20}, bytes.size() / 2, bytes.size() - 1}) {
    write_bytes(bad, bytes.substr(0, cut));
    expect_input_error(bad, "truncated");
  }
  write_bytes(bad, "NOT_A_VOCABULARY" + bytes.substr(16));
  expect_input_error(bad, "magic");
  std::string version = bytes;
  version[13] = 9;  // the version follows the 13-byte magic string
  write_bytes(bad, version);
  expect_input_error(bad, "version");
  write_bytes(bad, bytes + "x");
  expect_input_error(bad, "unexpected bytes");
  // Point the root's first child at the root itself (a cycle).
  std::string cycle = bytes;
  const std::size_t root_first_child = 13 + 4 + 4 + 4 + 4 + 32;
  std::memset(&cycle[root_first_child], 0, 4);
  write_bytes(bad, cycle);
  expect_input_error(bad, "children out of range");
  // A negative IDF weight (the last 8 bytes).
  std::string idf = bytes;
  const double negative = -1.0;
  std::memcpy(&idf[idf.size() - 8], &negative, 8);
  write_bytes(bad, idf);
  expect_input_error(bad, "IDF");
}

}  // namespace
}  // namespace vilslam
