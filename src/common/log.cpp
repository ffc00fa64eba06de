#include "common/log.h"

namespace vilslam {

void set_log_verbosity(int level) {
  spdlog::set_pattern("[%^%l%$] %v");
  spdlog::set_level(level <= 0 ? spdlog::level::warn : level == 1 ? spdlog::level::info : spdlog::level::debug);
}

}  // namespace vilslam
