// Loop constraint files, loops.csv (loop/loop_constraints_io.h).
#include "entry_util.h"
#include "loop/loop_constraints_io.h"

namespace vilslam::fuzz {

Outcome loops_csv(const std::uint8_t* data, std::size_t size) {
  const std::string path = write_temp_file("loops.csv", data, size);
  return outcome_of([&] { loop::read_loop_rows(path); });
}

}  // namespace vilslam::fuzz
