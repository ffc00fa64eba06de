#include "sim/bvh.h"

#include <array>

namespace vilslam::sim {
namespace {

constexpr int kBins = 16;
constexpr int kMaxLeafSize = 2;
constexpr int kMaxDepth = 40;  // the traversal stacks hold 64 entries

double half_area(const Eigen::AlignedBox3d& box) {
  if (box.isEmpty()) return 0;
  const Eigen::Vector3d e = box.sizes();
  return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

}  // namespace

void Bvh::build(const std::vector<Eigen::AlignedBox3d>& boxes) {
  nodes_.clear();
  order_.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) order_[i] = static_cast<int>(i);
  if (boxes.empty()) return;
  nodes_.reserve(2 * boxes.size());
  nodes_.emplace_back();
  build_node(boxes, 0, 0, static_cast<int>(boxes.size()), 0);
}

// Builds the subtree of order_[begin, end) into nodes_[index]; splits by the binned surface area
// heuristic (Wald 2007) along the widest axis of the centroids.
void Bvh::build_node(const std::vector<Eigen::AlignedBox3d>& boxes, int index, int begin, int end, int depth) {
  Eigen::AlignedBox3d box, centroids;
  for (int i = begin; i < end; ++i) {
    box.extend(boxes[order_[i]]);
    centroids.extend(boxes[order_[i]].center());
  }
  nodes_[index].box = box;
  const int count = end - begin;
  int axis;
  const double extent = centroids.sizes().maxCoeff(&axis);
  if (count <= kMaxLeafSize || depth >= kMaxDepth || extent <= 0) {
    nodes_[index].first = begin;
    nodes_[index].count = count;
    return;
  }
  const double lo = centroids.min()[axis];
  auto bin_of = [&](int item) {
    const int b = static_cast<int>(kBins * (boxes[item].center()[axis] - lo) / extent);
    return std::min(b, kBins - 1);
  };
  std::array<Eigen::AlignedBox3d, kBins> bin_box;
  std::array<int, kBins> bin_count{};
  for (int i = begin; i < end; ++i) {
    const int b = bin_of(order_[i]);
    bin_box[b].extend(boxes[order_[i]]);
    ++bin_count[b];
  }
  // Cost of splitting after bin s: area(left) * n_left + area(right) * n_right.
  std::array<double, kBins> left_cost{};
  Eigen::AlignedBox3d acc;
  int n = 0;
  for (int s = 0; s < kBins - 1; ++s) {
    acc.extend(bin_box[s]);
    n += bin_count[s];
    left_cost[s] = half_area(acc) * n;
  }
  acc.setEmpty();
  n = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  int best_split = 0;
  for (int s = kBins - 1; s > 0; --s) {
    acc.extend(bin_box[s]);
    n += bin_count[s];
    const double cost = left_cost[s - 1] + half_area(acc) * n;
    if (cost < best_cost) best_cost = cost, best_split = s;
  }
  const int* mid_ptr = std::stable_partition(order_.data() + begin, order_.data() + end,
                                             [&](int item) { return bin_of(item) < best_split; });
  int mid = static_cast<int>(mid_ptr - order_.data());
  if (mid == begin || mid == end) mid = begin + count / 2;
  const int left = static_cast<int>(nodes_.size());
  nodes_[index].first = left;
  nodes_[index].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  build_node(boxes, left, begin, mid, depth + 1);
  build_node(boxes, left + 1, mid, end, depth + 1);
}

}  // namespace vilslam::sim
