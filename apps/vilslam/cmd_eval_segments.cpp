// `vilslam eval-segments --run DIR --gt GT`: a run with resets (run --reset-at): when each segment joined the map
// of the ones before it, and how close to the truth it was joined (eval/join_eval.h; docs/loop.md, "Forced resets").
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "common/error.h"
#include "common/json_writer.h"
#include "common/yaml_config.h"
#include "eval/join_eval.h"
#include "io/dataset_groundtruth.h"
#include "io/trajectory_io.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string run_dir, gt_path, json_path;
  double window_s = 10.0;
};

struct Segment {
  TimeNs start_t_ns = 0;
  std::optional<TimeNs> relocalized_t_ns;
};

std::vector<Segment> read_segments(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  std::vector<Segment> segments;
  try {
    for (const YAML::Node& s : root["segments"]) {
      Segment segment;
      segment.start_t_ns = s["start_t_ns"].as<TimeNs>();
      if (s["relocalized"].as<bool>()) segment.relocalized_t_ns = s["relocalized_t_ns"].as<TimeNs>();
      segments.push_back(segment);
    }
  } catch (const YAML::Exception& e) {
    throw InputError(path, std::string("not a segments file: ") + e.what());
  }
  if (segments.empty()) throw InputError(path, "no segments");
  return segments;
}

vilslam::cli::Command reg("eval-segments",
                          "A run with resets: when each segment joined the map before it, and its error there",
                          [](CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("--run", o->run_dir, "Output folder of `run --reset-at` (segments.json, lidar_final.tum)")->required();
  app.add_option("--gt", o->gt_path, "Ground truth: a dataset folder, or a TUM file of LiDAR poses T_W_L")->required();
  app.add_option("--window", o->window_s,
                 "Seconds before the reset (fit) and after the join (compared, up to the next reset)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--json", o->json_path, "Also write the results as JSON to this file");
  return [o]() {
    const std::string segments_path = o->run_dir + "/segments.json";
    const std::string final_path = o->run_dir + "/lidar_final.tum";
    const std::vector<Segment> segments = read_segments(segments_path);
    const Trajectory est = read_trajectory(final_path, TrajectoryFormat::kTum);
    const Trajectory gt = read_groundtruth(o->gt_path, GroundTruthFrame::kLidar);
    JsonWriter json;
    json.begin_object();
    json.key("window_s").value(o->window_s);
    json.key("segments").begin_array();
    std::printf("%-8s %-20s %8s %11s %13s %8s %10s %10s\n", "segment", "reset_t_ns", "join_s", "junction_m",
                "junction_deg", "poses", "max_m", "rmse_m");
    for (std::size_t i = 1; i < segments.size(); ++i) {
      const Segment& s = segments[i];
      json.begin_object();
      json.key("start_t_ns").value(static_cast<std::int64_t>(s.start_t_ns));
      json.key("joined").value(s.relocalized_t_ns.has_value());
      if (!s.relocalized_t_ns) {
        std::printf("%-8zu %-20lld never joined\n", i, static_cast<long long>(s.start_t_ns));
        json.end_object();
        continue;
      }
      eval::JoinError e;
      try {
        const TimeNs end_t_ns = i + 1 < segments.size() ? segments[i + 1].start_t_ns : std::numeric_limits<TimeNs>::max();
        e = eval::join_error(est, gt, s.start_t_ns, *s.relocalized_t_ns, end_t_ns, o->window_s);
      } catch (const std::invalid_argument& err) {
        throw InputError(final_path, std::string("cannot evaluate against ") + o->gt_path + ": " + err.what());
      }
      const double join_s = ns_to_s(*s.relocalized_t_ns - s.start_t_ns);
      std::printf("%-8zu %-20lld %8.2f %11.4f %13.4f %8zu %10.4f %10.4f\n", i, static_cast<long long>(s.start_t_ns),
                  join_s, e.junction_translation_m, e.junction_rotation_deg, e.joined_poses, e.max_translation_m,
                  e.rmse_translation_m);
      json.key("join_s").value(join_s);
      json.key("junction_translation_m").value(e.junction_translation_m);
      json.key("junction_rotation_deg").value(e.junction_rotation_deg);
      json.key("fitted_poses").value(static_cast<std::uint64_t>(e.fitted_poses));
      json.key("joined_poses").value(static_cast<std::uint64_t>(e.joined_poses));
      json.key("max_translation_m").value(e.max_translation_m);
      json.key("rmse_translation_m").value(e.rmse_translation_m);
      json.end_object();
    }
    json.end_array();
    json.end_object();
    if (!o->json_path.empty()) write_file_atomic(o->json_path, json.str());
    return 0;
  };
});

}  // namespace
