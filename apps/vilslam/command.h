#pragma once
// Each subcommand lives in its own cmd_<name>.cpp and registers itself with a static Command:
//
//   static vilslam::cli::Command reg("info", "Describe a dataset", [](CLI::App& app) {
//     auto opts = std::make_shared<Options>();
//     app.add_option(...);
//     return [opts]() { ...; return 0; };   // the exit code
//   });
//
// main() builds the CLI11 app from the registry, runs the chosen command and maps errors to exit codes:
// InputError (bad input) and std::invalid_argument (unusable option values) -> 2 with "error: ...",
// other exceptions -> 1.
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace vilslam::cli {

using Runner = std::function<int()>;
using Setup = std::function<Runner(CLI::App&)>;

struct CommandSpec {
  std::string name;
  std::string description;
  Setup setup;
};

std::vector<CommandSpec>& registry();

struct Command {
  Command(std::string name, std::string description, Setup setup) {
    registry().push_back({std::move(name), std::move(description), std::move(setup)});
  }
};

}  // namespace vilslam::cli
