#include "loop/loop_constraint.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

namespace vilslam::loop {

PnpEstimate estimate_pnp(const std::vector<Vec3>& p_C0u, const std::vector<Eigen::Vector2d>& xy_C0v,
                         const PnpSettings& settings) {
  PnpEstimate estimate;
  constexpr std::size_t kEpnpMinPoints = 5;  // the minimal sample of OpenCV's EPnP RANSAC kernel
  if (p_C0u.size() < kEpnpMinPoints || p_C0u.size() != xy_C0v.size()) return estimate;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (std::size_t i = 0; i < p_C0u.size(); ++i) {
    object.emplace_back(p_C0u[i].x(), p_C0u[i].y(), p_C0u[i].z());
    image.emplace_back(xy_C0v[i].x(), xy_C0v[i].y());
  }
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);  // normalized coordinates
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  cv::theRNG().state = settings.seed;
  const bool ok = cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, settings.ransac_iterations,
                                     static_cast<float>(settings.reprojection_px / settings.focal_px), 0.999, inliers,
                                     cv::SOLVEPNP_EPNP);
  if (!ok || inliers.size() < kEpnpMinPoints) return estimate;
  std::vector<cv::Point3d> object_in;
  std::vector<cv::Point2d> image_in;
  for (int i : inliers) {
    object_in.push_back(object[i]);
    image_in.push_back(image[i]);
  }
  cv::solvePnPRefineLM(object_in, image_in, K, cv::noArray(), rvec, tvec);
  cv::Mat R_cv;
  cv::Rodrigues(rvec, R_cv);
  Mat3 R;
  Vec3 t;
  cv::cv2eigen(R_cv, R);
  cv::cv2eigen(tvec, t);
  estimate.valid = R.allFinite() && t.allFinite();
  estimate.T_C0v_C0u = SE3(R, t);
  estimate.inliers = static_cast<int>(inliers.size());
  return estimate;
}

SE3 lidar_constraint_from_camera(const SE3& T_C0v_C0u, const SE3& T_Lu_C0u, const SE3& T_Lv_C0v) {
  return T_Lu_C0u * T_C0v_C0u.inverse() * T_Lv_C0v.inverse();
}

PoseDifference pose_difference(const SE3& a, const SE3& b) {
  const SE3 d = a.inverse() * b;
  return {d.translation().norm(), so3::log(d.quat()).norm()};
}

}  // namespace vilslam::loop
