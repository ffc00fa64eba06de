#pragma once
// The LiDAR mount's tilt error in the VIO's up directions (GlobalPoseGraphConfig::tilt_offset). Each pose gives
// epsilon_k = u x v, the rotation from its measured up direction u (the VIO's, through the calibrated mount) to
// the LiDAR's own v, both in L. Model: epsilon_k = P (epsilon_L + R_L_W epsilon_W), P = I - u u^T (a rotation
// about u does not move it): epsilon_L, fixed in L, is the mount's error (and any tilt error the VIO carries in
// its body frame); epsilon_W, fixed in the world, is the map's own tilt (its first sweeps' and any wobble's).
// Only the rig's turns (R_L_W changing) tell them apart. Each sample weighs as its tilt factor does (1 / sigma^2,
// the VIO's own sigma when larger: a VIO started again in motion is off by its own tilt error for a while). The
// solution has a prior on epsilon_L of kMountPriorShare of the samples' weight, so that without turns the whole
// goes to epsilon_W and the tilt factors keep pulling the map's own tilt towards gravity, as without the offset.
#include "common/lie.h"

namespace vilslam::loop {

// The samples' normal equations in [epsilon_L; epsilon_W] and their total weight.
struct UpOffsetSamples {
  Eigen::Matrix<double, 6, 6> normal = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  double weight = 0.0;

  // One pose: its measured up direction u in L, its rotation R_W_L, the sample's weight.
  void add(const Vec3& up_L_measured, const Mat3& R_W_L, double weight);
  // The poses moved rigidly by R_new_old (GlobalPoseGraph::transform): epsilon_W is now seen in the new frame.
  void rotate_world(const Mat3& R_new_old);
  // epsilon_L: the rotation to apply to a measured up direction (zero without samples).
  Vec3 mount() const;
};

}  // namespace vilslam::loop
