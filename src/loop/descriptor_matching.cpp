#include "loop/descriptor_matching.h"

#include <limits>

#include "loop/binary_descriptor.h"

namespace vilslam::loop {

std::vector<DescriptorMatch> match_descriptors(const cv::Mat& query, const cv::Mat& train,
                                               const DescriptorMatchConfig& config) {
  const std::vector<OrbDescriptor> q = descriptor_rows(query), t = descriptor_rows(train);
  std::vector<DescriptorMatch> matches;
  if (q.empty() || t.empty()) return matches;
  const int nq = static_cast<int>(q.size()), nt = static_cast<int>(t.size());
  constexpr int kNone = std::numeric_limits<int>::max();
  // Nearest and second-nearest train row of each query row; nearest query row of each train row.
  std::vector<int> best_train(nq, -1), best_d(nq, kNone), second_d(nq, kNone);
  std::vector<int> best_query(nt, -1), best_query_d(nt, kNone);
  for (int i = 0; i < nq; ++i) {
    for (int j = 0; j < nt; ++j) {
      const int d = hamming_distance(q[i], t[j]);
      if (d < best_d[i]) {
        second_d[i] = best_d[i];
        best_d[i] = d;
        best_train[i] = j;
      } else if (d < second_d[i]) {
        second_d[i] = d;
      }
      if (d < best_query_d[j]) {
        best_query_d[j] = d;
        best_query[j] = i;
      }
    }
  }
  for (int i = 0; i < nq; ++i) {
    if (best_d[i] > config.max_distance) continue;
    if (second_d[i] != kNone && best_d[i] >= config.ratio_test * second_d[i]) continue;
    if (best_query[best_train[i]] != i) continue;
    matches.push_back({i, best_train[i]});
  }
  return matches;
}

}  // namespace vilslam::loop
