// `vilslam vocabulary --images DATASET [--images DATASET2 ...] --out FILE [--k --levels --seed --every]`:
// trains a bag-of-words vocabulary on the frontend's ORB descriptors of the left images.
#include <filesystem>
#include <iostream>

#include "common/error.h"
#include "io/dataset.h"
#include "loop/image_descriptors.h"
#include "loop/vocabulary.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::vector<std::string> datasets;
  std::string out;
  VocabularyConfig vocabulary;
  int every = 1;
};

// Descriptors of every `every`-th left image of the dataset, one matrix per image with descriptors.
void collect(const std::string& dataset, int every, std::vector<cv::Mat>* images) {
  const std::unique_ptr<DatasetReader> reader = open_dataset(dataset);
  const FrontendConfig frontend;
  long frame = 0;
  std::size_t found = 0;
  while (const std::optional<SensorEvent> event = reader->next()) {
    const auto* stereo = std::get_if<StereoFrame>(&event->data);
    if (!stereo || frame++ % every != 0) continue;
    cv::Mat descriptors = describe_image(stereo->left, frontend);
    if (descriptors.rows > 0) images->push_back(descriptors);
    ++found;
  }
  if (found == 0) throw InputError(dataset, "no stereo images to train a vocabulary on");
}

vilslam::cli::Command reg(
    "vocabulary", "Train a bag-of-words vocabulary on the ORB descriptors of left images", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      app.add_option("--images", o->datasets, "Dataset folder (repeat for several)")->required();
      app.add_option("--out", o->out, "Output vocabulary file")->required();
      app.add_option("--k", o->vocabulary.branching, "Branching factor")->capture_default_str();
      app.add_option("--levels", o->vocabulary.levels, "Depth of the tree")->capture_default_str();
      app.add_option("--seed", o->vocabulary.seed, "k-means++ seed")->capture_default_str();
      app.add_option("--every", o->every, "Use every N-th left image")->capture_default_str();
      return [o]() {
        validate_vocabulary_config(o->vocabulary);
        if (o->every < 1) throw std::invalid_argument("--every must be >= 1");
        const std::filesystem::path out_dir = std::filesystem::absolute(o->out).parent_path();
        if (!std::filesystem::is_directory(out_dir)) throw InputError(o->out, "output folder does not exist");
        std::vector<cv::Mat> images;
        for (const std::string& dataset : o->datasets) collect(dataset, o->every, &images);
        std::size_t descriptors = 0;
        for (const cv::Mat& d : images) descriptors += static_cast<std::size_t>(d.rows);
        if (descriptors == 0) throw InputError(o->datasets.front(), "no ORB descriptors in the selected images");
        const Vocabulary vocabulary = Vocabulary::train(images, o->vocabulary);
        vocabulary.save(o->out);
        std::cout << "wrote " << o->out << ": " << vocabulary.num_words() << " words (k " << vocabulary.branching()
                  << ", " << vocabulary.levels() << " levels) from " << images.size() << " images, " << descriptors
                  << " descriptors\n";
        return 0;
      };
    });

}  // namespace
