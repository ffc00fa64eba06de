#pragma once
// Database of key images' bags of words with an inverted index (word -> images containing it), queried
// for loop candidates among images older than a time gap (the paper's time threshold).
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/time.h"
#include "loop/vocabulary.h"

namespace vilslam {

struct LoopCandidate {
  std::int64_t id = 0;
  TimeNs t_ns = 0;
  double score = 0;  // bow_score in [0, 1]
};

class BowDatabase {
 public:
  // Stores an image's vector (normalized again here) under a caller's id.
  void add(std::int64_t id, TimeNs t_ns, const BowVector& v);

  // The entries with t_ns <= query_t_ns - min_time_gap_ns sharing at least one word with v, best score
  // first (ties: older first, then smaller id), at most max_results. Visits only the entries listed
  // under v's words.
  std::vector<LoopCandidate> query(const BowVector& v, TimeNs query_t_ns, std::size_t max_results,
                                   TimeNs min_time_gap_ns) const;

  std::size_t size() const { return entries_.size(); }

 private:
  struct Posting {
    std::uint32_t entry = 0;
    double weight = 0;
  };
  struct Entry {
    std::int64_t id = 0;
    TimeNs t_ns = 0;
  };
  std::vector<Entry> entries_;
  std::unordered_map<WordId, std::vector<Posting>> inverted_index_;
};

}  // namespace vilslam
