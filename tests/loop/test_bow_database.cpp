// BowDatabase: inverted-index scores equal the L1 score, time gap, order; and on real EuRoC images:
// neighbouring frames score well above unrelated images, a perturbed view finds its own place first.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "loop/bow_database.h"
#include "loop/image_descriptors.h"
#include "loop_test_data.h"
#include "test_util.h"

namespace vilslam {
namespace {

constexpr TimeNs kSecond = kNsPerSecond;

TEST(BowDatabase, ScoresEqualTheL1ScoreAndComeBestFirst) {
  const BowVector q{{1, 0.4}, {2, 0.4}, {7, 0.2}};
  const std::vector<BowVector> entries{
      {{1, 0.5}, {3, 0.5}}, {{1, 0.4}, {2, 0.4}, {7, 0.2}}, {{9, 1.0}}, {{2, 0.3}, {7, 0.7}}, {{1, 2.0}, {3, 2.0}}};
  BowDatabase db;
  for (std::size_t i = 0; i < entries.size(); ++i)
    db.add(static_cast<std::int64_t>(100 + i), static_cast<TimeNs>(i) * kSecond, entries[i]);
  const std::vector<LoopCandidate> found = db.query(q, 10 * kSecond, 10, 0);
  // Entry 2 shares no word and is never listed; entries 0 and 4 are equal after normalization (tie: older first).
  ASSERT_EQ(found.size(), 4u);
  EXPECT_EQ(found[0].id, 101);
  EXPECT_NEAR(found[0].score, 1.0, 1e-12);
  for (const LoopCandidate& c : found) {
    EXPECT_NEAR(c.score, bow_score(q, entries[c.id - 100]), 1e-12) << c.id;
  }
  EXPECT_EQ(found[1].id, 103);
  EXPECT_EQ(found[2].id, 100);
  EXPECT_EQ(found[3].id, 104);
  EXPECT_EQ(found[2].score, found[3].score);
  EXPECT_EQ(db.query(q, 10 * kSecond, 2, 0).size(), 2u);
  EXPECT_TRUE(db.query(BowVector{}, 10 * kSecond, 5, 0).empty());
}

TEST(BowDatabase, TimeGapExcludesRecentEntries) {
  const BowVector v{{5, 1.0}};
  BowDatabase db;
  for (int i = 0; i < 10; ++i) db.add(i, i * kSecond, v);
  // Query at t = 9 s with a 3 s gap: entries up to and including t = 6 s.
  const std::vector<LoopCandidate> found = db.query(v, 9 * kSecond, 100, 3 * kSecond);
  ASSERT_EQ(found.size(), 7u);
  for (std::size_t i = 0; i < found.size(); ++i) EXPECT_EQ(found[i].id, static_cast<std::int64_t>(i));
  EXPECT_TRUE(db.query(v, 2 * kSecond, 100, 3 * kSecond).empty());
}

// EuRoC V1_01 micro: a vocabulary (k 8, 3 levels) trained on 2x3 tiles of 4 frames spread over the
// sequence; tiles are distinct places with real texture.
class RealImages : public ::testing::Test {
 protected:
  void SetUp() override {
    VILSLAM_REQUIRE_SHARED_DATA(dir, "euroc/V1_01_easy_micro");
    paths_ = test::euroc_left_paths(dir);
    ASSERT_GE(paths_.size(), 90u);
    std::vector<cv::Mat> training;
    for (std::size_t f : {0, 30, 60, 90}) {
      for (const cv::Mat& tile : test::tiles(test::read_grey(paths_[f]), 2, 3))
        training.push_back(describe_image(tile));
    }
    VocabularyConfig config;
    config.branching = 8;
    config.levels = 3;
    vocabulary_ = Vocabulary::train(training, config);
  }

  BowVector words(const cv::Mat& image) const { return vocabulary_.transform(describe_image(image)); }

  std::vector<std::string> paths_;
  Vocabulary vocabulary_;
};

TEST_F(RealImages, NeighbouringFramesScoreWellAboveUnrelatedImages) {
  const cv::Mat frame = test::read_grey(paths_[45]);
  const BowVector v = words(frame);
  const BowVector next = words(test::read_grey(paths_[46]));
  const BowVector later = words(test::read_grey(paths_[55]));
  // Unrelated images: white noise and blurred noise (blobs with corners of realistic scale).
  const BowVector noise = words(test::noise_image(frame.rows, frame.cols, 3));
  cv::Mat blobs;
  cv::GaussianBlur(test::noise_image(frame.rows, frame.cols, 4), blobs, cv::Size(0, 0), 2.0);
  cv::normalize(blobs, blobs, 0, 255, cv::NORM_MINMAX);
  const double s_next = bow_score(v, next), s_later = bow_score(v, later);
  const double s_unrelated = std::max(bow_score(v, noise), bow_score(v, words(blobs)));
  std::printf("score frame 45 vs 46: %.3f, vs 55: %.3f, vs unrelated (best of noise, blobs): %.3f\n", s_next, s_later,
              s_unrelated);
  EXPECT_GT(s_next, 0.6);
  EXPECT_GT(s_later, 0.6);
  EXPECT_GT(s_next, 1.5 * s_unrelated);
  EXPECT_GT(s_later, 1.5 * s_unrelated);
}

TEST_F(RealImages, PerturbedTileFindsItsOwnPlaceFirst) {
  // Database: the 6 tiles of frame 20, one per second; queries: the tiles of frame 70 (2.5 s later),
  // shifted by 3 px and blurred.
  const std::vector<cv::Mat> places = test::tiles(test::read_grey(paths_[20]), 2, 3);
  const cv::Mat later = test::read_grey(paths_[70]);
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, 3, 0, 1, -2);
  cv::Mat shifted;
  cv::warpAffine(later, shifted, shift, later.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  cv::GaussianBlur(shifted, shifted, cv::Size(3, 3), 0.8);
  const std::vector<cv::Mat> queries = test::tiles(shifted, 2, 3);
  BowDatabase db;
  for (std::size_t i = 0; i < places.size(); ++i)
    db.add(static_cast<std::int64_t>(i), static_cast<TimeNs>(i) * kSecond, words(places[i]));
  double worst_margin = 1;
  for (std::size_t i = 0; i < queries.size(); ++i) {
    const std::vector<LoopCandidate> found = db.query(words(queries[i]), 100 * kSecond, 3, 0);
    ASSERT_GE(found.size(), 2u);
    EXPECT_EQ(found[0].id, static_cast<std::int64_t>(i)) << "tile " << i;
    worst_margin = std::min(worst_margin, found[0].score - found[1].score);
  }
  std::printf("perturbed tiles: own place first, smallest margin over the runner-up %.3f\n", worst_margin);
  // With a time gap, the query at t = 5 s (tile 5) only sees tiles up to t = 2 s.
  for (const LoopCandidate& c : db.query(words(queries[5]), 5 * kSecond, 10, 3 * kSecond))
    EXPECT_LE(c.t_ns, 2 * kSecond);
}

}  // namespace
}  // namespace vilslam
