#pragma once
// Merges several time-sorted streams into one time-ordered sequence of (stream, index) pairs.
// Ties go to the stream added first, which fixes the tie order of DatasetReader::next().
#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include "common/time.h"

namespace vilslam {

class EventMerge {
 public:
  // Adds a stream of strictly increasing times; returns its id (0, 1, ...).
  std::size_t add_stream(std::vector<TimeNs> times);
  // (stream id, index in that stream) of the earliest event not yet returned; nullopt at the end.
  std::optional<std::pair<std::size_t, std::size_t>> next();
  void rewind();

 private:
  std::vector<std::vector<TimeNs>> times_;
  std::vector<std::size_t> cursor_;
};

}  // namespace vilslam
