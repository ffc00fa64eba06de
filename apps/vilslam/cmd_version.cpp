#include <iostream>

#include "vilslam/command.h"

namespace {

vilslam::cli::Command reg("version", "Print the vilslam version", [](CLI::App&) {
  return []() {
    std::cout << "vilslam 0.1.0\n";
    return 0;
  };
});

}  // namespace
