#include <malloc.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <stdexcept>

#include "common/error.h"
#include "common/log.h"
#include "vilslam/command.h"

namespace vilslam::cli {

std::vector<CommandSpec>& registry() {
  static std::vector<CommandSpec> commands;
  return commands;
}

}  // namespace vilslam::cli

int main(int argc, char** argv) {
  using namespace vilslam;
  // Image-sized buffers (OpenCV's corner, pyramid and flow buffers, MB each) are allocated and freed for
  // every frame on several threads. With glibc's defaults each came from mmap or a trimmed heap, so every
  // frame paid fresh page faults: in the hallway the frontend took 63 ms a frame, 13.5 s of a 32 s run in
  // the kernel. Keeping freed memory for reuse: 10.5 ms a frame, the same output (docs/pipeline.md).
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  CLI::App app{"vilslam: stereo visual-inertial-LiDAR SLAM"};
  app.require_subcommand(1);
  int verbosity = 1;
  app.add_option("-v,--verbosity", verbosity, "0 = warnings, 1 = info, 2 = debug")->capture_default_str();

  auto& commands = cli::registry();
  std::sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  std::map<CLI::App*, cli::Runner> runners;
  for (const auto& spec : commands) {
    CLI::App* sub = app.add_subcommand(spec.name, spec.description);
    runners[sub] = spec.setup(*sub);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  set_log_verbosity(verbosity);
  try {
    for (auto& [sub, run] : runners) {
      if (sub->parsed()) return run();
    }
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {  // a value given on the command line or in a config is unusable
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
