#include "io/event_merge.h"

namespace vilslam {

std::size_t EventMerge::add_stream(std::vector<TimeNs> times) {
  times_.push_back(std::move(times));
  cursor_.push_back(0);
  return times_.size() - 1;
}

std::optional<std::pair<std::size_t, std::size_t>> EventMerge::next() {
  std::optional<std::size_t> best;
  for (std::size_t s = 0; s < times_.size(); ++s) {
    if (cursor_[s] >= times_[s].size()) continue;
    if (!best || times_[s][cursor_[s]] < times_[*best][cursor_[*best]]) best = s;
  }
  if (!best) return std::nullopt;
  return std::make_pair(*best, cursor_[*best]++);
}

void EventMerge::rewind() {
  for (auto& c : cursor_) c = 0;
}

}  // namespace vilslam
