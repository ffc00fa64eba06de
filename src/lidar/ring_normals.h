#pragma once
// Normals of ring surface features, for the registration's normal test (correspondences.h). A ring alone is
// a curve, so a point's normal comes from its window along its own ring together with the windows at the
// same azimuth on the rings just above and below it in elevation: the neighbourhood of a range image (as the
// normal map of SuMa, Behley & Stachniss 2018). A normal is kept only where the windows of three rings lie on
// one plane within the range noise; at a crease the rings on the other surface are left out, and where no
// three rings around the point share its plane the point has no normal.
#include <vector>

#include <Eigen/Core>

#include "common/types.h"

namespace vilslam::lidar {

class RingNormals {
 public:
  // rings[k]: ring k's points in azimuth order (kept by pointer: they must outlive this object).
  RingNormals(const std::vector<const std::vector<Eigen::Vector3f>*>& rings, int half_window);

  // Unit normal at point i of ring k, or zero when no two neighbouring rings' windows lie on one plane with
  // the point's own within max_thickness_m (rms off the plane).
  Vec3 normal(int k, int i, double max_thickness_m) const;

 private:
  // The point of ring k nearest in (pseudo-)azimuth to azimuth, if within tolerance; -1 otherwise.
  int nearest_in_azimuth(int k, float azimuth, float tolerance) const;

  std::vector<const std::vector<Eigen::Vector3f>*> rings_;
  std::vector<std::vector<float>> azimuth_;      // per ring, ascending pseudo-azimuths (ring_normals.cpp)
  std::vector<int> by_elevation_;                // the non-empty rings, lowest elevation first
  std::vector<int> rank_;                        // ring k's place in by_elevation_ (-1: empty)
  int half_window_;
};

}  // namespace vilslam::lidar
