#include "loop/bow_database.h"

#include <algorithm>
#include <cmath>

namespace vilslam {
namespace {

double l1_norm(const BowVector& v) {
  double sum = 0;
  for (const auto& e : v) sum += std::abs(e.second);
  return sum;
}

}  // namespace

void BowDatabase::add(std::int64_t id, TimeNs t_ns, const BowVector& v) {
  const auto entry = static_cast<std::uint32_t>(entries_.size());
  entries_.push_back({id, t_ns});
  const double norm = l1_norm(v);
  if (norm <= 0) return;
  for (const auto& [word, weight] : v) inverted_index_[word].push_back({entry, weight / norm});
}

std::vector<LoopCandidate> BowDatabase::query(const BowVector& v, TimeNs query_t_ns, std::size_t max_results,
                                              TimeNs min_time_gap_ns) const {
  const double norm = l1_norm(v);
  if (norm <= 0 || max_results == 0) return {};
  const TimeNs newest_t_ns = query_t_ns - min_time_gap_ns;
  // For L1-normalized a, b: |a - b|_1 = 2 + sum over common words of (|a_i - b_i| - |a_i| - |b_i|), so
  // the score 1 - 0.5 |a - b|_1 needs only the common words (DBoW2's L1 scoring).
  std::unordered_map<std::uint32_t, double> common_sum;  // by entry index, only entries sharing a word
  for (const auto& [word, weight] : v) {
    const auto it = inverted_index_.find(word);
    if (it == inverted_index_.end()) continue;
    const double a = std::abs(weight / norm);
    for (const Posting& p : it->second) {
      if (entries_[p.entry].t_ns > newest_t_ns) continue;
      const double b = std::abs(p.weight);
      common_sum[p.entry] += std::abs(a - b) - a - b;
    }
  }
  std::vector<std::pair<std::uint32_t, LoopCandidate>> candidates;
  candidates.reserve(common_sum.size());
  for (const auto& [e, sum] : common_sum) {
    candidates.push_back({e, {entries_[e].id, entries_[e].t_ns, std::clamp(-0.5 * sum, 0.0, 1.0)}});
  }
  // A total order (the entry index last), so the hash map's iteration order never shows.
  const auto better = [](const auto& x, const auto& y) {
    if (x.second.score != y.second.score) return x.second.score > y.second.score;
    if (x.second.t_ns != y.second.t_ns) return x.second.t_ns < y.second.t_ns;
    if (x.second.id != y.second.id) return x.second.id < y.second.id;
    return x.first < y.first;
  };
  const std::size_t n = std::min(max_results, candidates.size());
  std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(n), candidates.end(), better);
  std::vector<LoopCandidate> best;
  best.reserve(n);
  for (std::size_t i = 0; i < n; ++i) best.push_back(candidates[i].second);
  return best;
}

}  // namespace vilslam
