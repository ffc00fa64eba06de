#pragma once
// A k-d tree (nanoflann) over a fixed set of 3D points, for nearest-neighbour queries.
#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <vector>

#include <nanoflann.hpp>

namespace vilslam {

class PointIndex {
 public:
  explicit PointIndex(std::vector<Eigen::Vector3f> points);
  PointIndex(const PointIndex&) = delete;  // the tree points into cloud_
  PointIndex& operator=(const PointIndex&) = delete;

  struct Neighbour {
    std::size_t index = 0;
    float dist_sq = 0;
  };

  // Nearest point to q (the index must not be empty).
  Neighbour nearest(const Eigen::Vector3f& q) const;
  // Up to k nearest points, closest first.
  std::vector<Neighbour> nearest_k(const Eigen::Vector3f& q, std::size_t k) const;

  const std::vector<Eigen::Vector3f>& points() const { return cloud_.points; }
  std::size_t size() const { return cloud_.points.size(); }

 private:
  struct Cloud {  // nanoflann dataset adaptor
    std::vector<Eigen::Vector3f> points;
    std::size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][static_cast<Eigen::Index>(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Cloud>, Cloud, 3, std::size_t>;

  Cloud cloud_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace vilslam
