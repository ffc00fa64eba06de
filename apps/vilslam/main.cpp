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
