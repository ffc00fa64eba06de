// `vilslam map-info MAP [--vocabulary FILE] [--rig DATASET_OR_RIG_YAML]`: reads a saved map (loop/map_file.h,
// docs/formats.md "Map files") in full, checks it, and prints what it holds; with --vocabulary / --rig also
// whether a run with that vocabulary and rig could use it. A bad or foreign map exits 2 naming the file.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "io/calibration_io.h"
#include "io/dataset.h"
#include "loop/map_file.h"
#include "pipeline/offline_runner.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string map_dir, vocabulary, rig;
};

vilslam::cli::Command reg("map-info", "Check a saved map (vilslam run --save-map) and print what it holds",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("map", o->map_dir, "Map folder")->required();
  app.add_option("--vocabulary", o->vocabulary, "Also check it was built with this vocabulary ('default': the shipped one)");
  app.add_option("--rig", o->rig, "Also check it fits this rig: a dataset folder or a rig.yaml");
  return [o]() {
    const loop::SavedMap map = loop::load_map(o->map_dir);
    std::size_t points = 0, edges = 0, surfaces = 0;
    for (const loop::KeyFrame& k : map.key_frames) {
      points += k.image.num_points();
      edges += k.features_L.edges.size();
      surfaces += k.features_L.surfaces.size();
    }
    std::printf("key frames %zu (3D points %zu, edge features %zu, surface features %zu), poses %zu\n",
                map.key_frames.size(), points, edges, surfaces, map.poses.size());
    if (!map.poses.empty()) {
      std::printf("poses from %.3f s to %.3f s\n", ns_to_s(map.poses.front().t_ns), ns_to_s(map.poses.back().t_ns));
    }
    if (!o->vocabulary.empty() || !o->rig.empty()) {
      const std::string vocabulary = vocabulary_file(o->vocabulary.empty() ? "default" : o->vocabulary);
      RigCalibration rig = map.rig;
      if (!o->rig.empty()) {
        rig = std::filesystem::is_directory(o->rig) ? open_dataset(o->rig)->calibration() : read_rig_yaml(o->rig);
      }
      loop::check_map_fits(map, o->map_dir, loop::vocabulary_identity(vocabulary), rig);
      std::printf("fits the vocabulary %s and the rig %s\n", vocabulary.c_str(), o->rig.empty() ? "(the map's)" : o->rig.c_str());
    }
    return 0;
  };
});

}  // namespace
