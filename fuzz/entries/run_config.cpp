// The run config YAML of `vilslam run` (pipeline/run_config.h).
#include "entry_util.h"
#include "pipeline/run_config.h"

namespace vilslam::fuzz {

Outcome run_config(const std::uint8_t* data, std::size_t size) {
  const std::string path = write_temp_file("run.yaml", data, size);
  return outcome_of([&] { load_run_config(path); });
}

}  // namespace vilslam::fuzz
