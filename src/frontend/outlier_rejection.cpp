#include "frontend/outlier_rejection.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include <Eigen/SVD>
#include <limits>

namespace vilslam {

bool triangulate_stereo(const Eigen::Vector2d& xy0, const Eigen::Vector2d& xy1, const SE3& T_C1_C0, Vec3* p_C0) {
  // Hartley & Zisserman (12.2): rows x P3 - P1 and y P3 - P2 of both projection matrices, P0 = [I | 0].
  Eigen::Matrix<double, 3, 4> P1;
  P1 << T_C1_C0.rotation(), T_C1_C0.translation();
  Eigen::Matrix4d A;
  A << -1, 0, xy0.x(), 0,  //
      0, -1, xy0.y(), 0,   //
      xy1.x() * P1.row(2) - P1.row(0), xy1.y() * P1.row(2) - P1.row(1);
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  const Eigen::Vector4d X = svd.matrixV().col(3);
  if (std::abs(X.w()) < 1e-12) return false;
  *p_C0 = X.head<3>() / X.w();
  return p_C0->z() > 0 && (T_C1_C0 * *p_C0).z() > 0;
}

double stereo_reprojection_error_px(const StereoRig& rig, const Vec3& p_C0, const Eigen::Vector2d& left_px,
                                    const Eigen::Vector2d& right_px) {
  Eigen::Vector2d px0, px1;
  if (!rig.cam0.project(p_C0, &px0) || !rig.cam1.project(rig.T_C1_C0 * p_C0, &px1)) {
    return std::numeric_limits<double>::infinity();
  }
  return 0.5 * ((px0 - left_px).norm() + (px1 - right_px).norm());
}

MotionEstimate estimate_motion_pnp(const std::vector<Vec3>& p_C0prev, const std::vector<Eigen::Vector2d>& xy_cur,
                                   double focal_px, const FrontendConfig& config, PnpSolver solver) {
  MotionEstimate estimate;
  if (static_cast<int>(p_C0prev.size()) < config.pnp_min_points) return estimate;
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (std::size_t i = 0; i < p_C0prev.size(); ++i) {
    object.emplace_back(p_C0prev[i].x(), p_C0prev[i].y(), p_C0prev[i].z());
    image.emplace_back(xy_cur[i].x(), xy_cur[i].y());
  }
  const cv::Mat K = cv::Mat::eye(3, 3, CV_64F);
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  cv::theRNG().state = config.ransac_seed;
  const bool ok = cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false, config.pnp_ransac_iterations,
                                     static_cast<float>(config.pnp_ransac_threshold_px / focal_px), 0.99, inliers,
                                     solver == PnpSolver::kEPnP ? cv::SOLVEPNP_EPNP : cv::SOLVEPNP_P3P);
  if (!ok || static_cast<int>(inliers.size()) < config.pnp_min_points) return estimate;
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
  estimate.valid = true;
  estimate.T_C0cur_C0prev = SE3(R, t);
  estimate.inliers = static_cast<int>(inliers.size());
  return estimate;
}

}  // namespace vilslam
