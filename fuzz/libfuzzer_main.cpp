// One libFuzzer binary per entry: VILSLAM_FUZZ_ENTRY names it (fuzz/CMakeLists.txt).
#include <spdlog/spdlog.h>

#include "entries.h"

// Readers warn about skipped rows; at millions of inputs that is only noise.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  spdlog::set_level(spdlog::level::off);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  vilslam::fuzz::VILSLAM_FUZZ_ENTRY(data, size);
  return 0;
}
