#pragma once
// Logging goes through spdlog; this header only fixes the project's logger setup.
#include <spdlog/spdlog.h>

namespace vilslam {

// Verbosity for the CLI: 0 = warnings and errors, 1 = info, 2 = debug.
void set_log_verbosity(int level);

}  // namespace vilslam
