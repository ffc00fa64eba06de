#include "loop/constraint_fusion.h"

#include <Eigen/Cholesky>

namespace vilslam::loop {

Mat6 pnp_information(const SE3& T_C0cur_C0prev, const std::vector<Vec3>& p_C0prev,
                     const std::vector<Eigen::Vector2d>& xy_cur, double focal_px, double inlier_px, double sigma_px) {
  Mat6 information = Mat6::Zero();
  const Mat3 R = T_C0cur_C0prev.rotation();
  for (std::size_t i = 0; i < p_C0prev.size(); ++i) {
    const Vec3 p = T_C0cur_C0prev * p_C0prev[i];
    if (!(p.z() > 0.0)) continue;
    const Eigen::Vector2d px_error = focal_px * (p.head<2>() / p.z() - xy_cur[i]);
    if (!(px_error.norm() <= inlier_px)) continue;
    // d(pixel)/d(p_cur) of the pinhole, times d(p_cur)/d[rho; phi] = R [I, -hat(p_prev)] (T Exp(d) p_prev).
    Eigen::Matrix<double, 2, 3> d_pixel;
    d_pixel << 1.0 / p.z(), 0.0, -p.x() / (p.z() * p.z()), 0.0, 1.0 / p.z(), -p.y() / (p.z() * p.z());
    d_pixel *= focal_px;
    Eigen::Matrix<double, 3, 6> d_point;
    d_point << R, -R * so3::hat(p_C0prev[i]);
    const Eigen::Matrix<double, 2, 6> J = d_pixel * d_point;
    information.noalias() += J.transpose() * J / (sigma_px * sigma_px);
  }
  return information;
}

Mat6 information_in_lidar_frames(const Mat6& information_C0v_C0u, const SE3& T_C0v_C0u, const SE3& T_Lv_C0v) {
  // T_Lu_C0u (T_C0v_C0u Exp(d))^-1 T_C0v_Lv = T_Lu_Lv Exp(-Ad(T_Lv_C0u) d): eps = -M d, info_eps = M^-T info M^-1.
  const Mat6 M_inverse = (T_Lv_C0v * T_C0v_C0u).inverse().adjoint();
  const Mat6 information = M_inverse.transpose() * information_C0v_C0u * M_inverse;
  return 0.5 * (information + information.transpose());
}

SE3 fuse_estimates(const SE3& T_a, const Mat6& info_a, const SE3& T_b, const Mat6& info_b) {
  const Vec6 a_in_b = (T_b.inverse() * T_a).log();
  const Vec6 step = (info_a + info_b).ldlt().solve(info_a * a_in_b);
  return T_b * SE3::exp(step);
}

Mat6 information_with_floor(const Mat6& estimate_information, const Mat6& floor_information) {
  // (A^-1 + F^-1)^-1 = A (A + F)^-1 F, which needs no inverse of a singular A.
  const Mat6 sum = estimate_information + floor_information;
  const Mat6 information = estimate_information * sum.ldlt().solve(floor_information);
  return 0.5 * (information + information.transpose());
}

}  // namespace vilslam::loop
