#include <filesystem>
#include <iostream>

#include "common/error.h"
#include "sim/scenario_figures.h"
#include "vilslam/command.h"

namespace {

struct Options {
  std::string out;
  std::uint64_t seed = 1;
  std::vector<std::string> scenarios{"highbay", "hallway", "tunnel", "loop", "outdoor", "room"};
};

vilslam::cli::Command reg("sim-figures", "Write the left image, a LiDAR sweep and the map (top views) of each simulated scenario as PNG",
                          [](CLI::App& app) {
  auto opts = std::make_shared<Options>();
  app.add_option("--out", opts->out, "Output folder (created when missing)")->required();
  app.add_option("--seed", opts->seed, "World and noise seed")->capture_default_str();
  app.add_option("--scenarios", opts->scenarios, "Scenarios to draw")->capture_default_str();
  return [opts]() {
    using namespace vilslam::sim;
    std::error_code ec;
    std::filesystem::create_directories(opts->out, ec);
    if (ec) throw vilslam::InputError(opts->out, "cannot create the output folder: " + ec.message());
    for (const std::string& name : opts->scenarios) {
      Scenario scenario;
      try {
        scenario = parse_scenario(name);
      } catch (const std::invalid_argument&) {
        throw vilslam::InputError("--scenarios", "unknown scenario '" + name + "'");
      }
      const World world = World::generate(scenario, opts->seed);
      for (const std::string& path : write_scenario_figures(world, opts->seed, opts->out)) std::cout << path << "\n";
    }
    return 0;
  };
});

}  // namespace
