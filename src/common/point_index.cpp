#include "common/point_index.h"

#include <stdexcept>

namespace vilslam {

PointIndex::PointIndex(std::vector<Eigen::Vector3f> points) : cloud_{std::move(points)} {
  if (cloud_.points.empty()) throw std::invalid_argument("cannot index an empty point set");
  tree_ = std::make_unique<Tree>(3, cloud_, nanoflann::KDTreeSingleIndexAdaptorParams(10));
}

PointIndex::Neighbour PointIndex::nearest(const Eigen::Vector3f& q) const {
  Neighbour n;
  tree_->knnSearch(q.data(), 1, &n.index, &n.dist_sq);
  return n;
}

std::vector<PointIndex::Neighbour> PointIndex::nearest_k(const Eigen::Vector3f& q, std::size_t k) const {
  std::vector<std::size_t> ids(k);
  std::vector<float> dists(k);
  const std::size_t found = tree_->knnSearch(q.data(), k, ids.data(), dists.data());
  std::vector<Neighbour> out(found);
  for (std::size_t i = 0; i < found; ++i) out[i] = {ids[i], dists[i]};
  return out;
}

}  // namespace vilslam
