#include "vio/visual_inertial_alignment.h"

#include <cmath>
#include <unordered_map>

#include <Eigen/Dense>

#include "common/lie.h"
#include "frontend/frontend_config.h"
#include "frontend/outlier_rejection.h"
#include "vio/preintegration.h"

namespace vilslam {
namespace {

using PointsByTrack = std::unordered_map<std::uint64_t, Vec3>;

PointsByTrack triangulate(const FrontendOutput& frame, const SE3& T_C1_C0) {
  PointsByTrack points;
  for (const StereoMatch& m : frame.matches) {
    Vec3 p;
    if (triangulate_stereo(m.left_norm, m.right_norm, T_C1_C0, &p)) points[m.track_id] = p;
  }
  return points;
}

// The first pair's left camera frame c: T_c_C0 of every pair, by PnP of a reference pair's stereo points in the
// pair's left image. The reference stays while enough of its points are tracked (the poses then share one
// reference's depth errors instead of chaining new ones at every pair), else it moves to the previous pair. Empty
// with the reason in *failure when a pair has too few tracked points.
std::vector<SE3> visual_motion(const std::vector<FrontendOutput>& frames, const RigCalibration& calib, double focal_px,
                               int min_inliers, std::string* failure) {
  const SE3 T_C1_C0 = calib.T_C0_C1().inverse();
  FrontendConfig pnp;
  pnp.pnp_min_points = min_inliers;
  std::vector<SE3> T_c_C0(frames.size());
  std::size_t ref = 0;
  PointsByTrack p_C0ref = triangulate(frames[0], T_C1_C0);
  for (std::size_t k = 1; k < frames.size(); ++k) {
    MotionEstimate e;
    for (bool moved = false;; moved = true) {
      std::vector<Vec3> p;
      std::vector<Eigen::Vector2d> xy_cur;
      for (const StereoMatch& m : frames[k].matches) {
        const auto it = p_C0ref.find(m.track_id);
        if (it == p_C0ref.end()) continue;
        p.push_back(it->second);
        xy_cur.push_back(m.left_norm);
      }
      e = estimate_motion_pnp(p, xy_cur, focal_px, pnp);
      if (e.valid && e.inliers >= 2 * min_inliers) break;
      if (ref == k - 1 || moved) break;
      ref = k - 1;
      p_C0ref = triangulate(frames[ref], T_C1_C0);
    }
    if (!e.valid) {
      *failure = "too few tracked stereo points between pairs " + std::to_string(ref) + " and " + std::to_string(k);
      return {};
    }
    T_c_C0[k] = T_c_C0[ref] * e.T_C0cur_C0prev.inverse();
  }
  return T_c_C0;
}

std::vector<Preintegration> preintegrate(const std::vector<FrontendOutput>& frames, const std::vector<ImuSample>& imu,
                                         const Vec3& bias_gyro_rad_s, const ImuNoise& noise) {
  std::vector<Preintegration> out;
  for (std::size_t k = 0; k + 1 < frames.size(); ++k) {
    out.emplace_back(bias_gyro_rad_s, Vec3::Zero(), noise);
    integrate_samples(imu, frames[k].t_ns, frames[k + 1].t_ns, out.back());
  }
  return out;
}

// The gyroscope bias from the visual rotations (VINS-Mono, Sec. V-B1): the rotation preintegrated from the first
// pair to each later one, corrected to first order (Forster et al. eq. (44): dR(bg) = dR Exp(dR_dbg bg)), must
// equal the visual one, so dR_dbg bg = log(dR^T R_0^T R_k) in the least-squares sense. Taken from the first pair
// (not pair by pair), each visual rotation's noise weighs against the whole interval's drift. Over a 1 s window a
// real MEMS gyro's bias (EuRoC's reach 0.08 rad/s) turns the chained rotation by more than the visual noise.
Vec3 gyro_bias_rad_s(const std::vector<FrontendOutput>& frames, const std::vector<ImuSample>& imu,
                     const std::vector<Mat3>& R_c_I_visual, const ImuNoise& noise) {
  Mat3 JtJ = Mat3::Zero();
  Vec3 Jtr = Vec3::Zero();
  for (std::size_t k = 1; k < frames.size(); ++k) {
    Preintegration pre(Vec3::Zero(), Vec3::Zero(), noise);
    integrate_samples(imu, frames[0].t_ns, frames[k].t_ns, pre);
    const Mat3 R_visual = R_c_I_visual[0].transpose() * R_c_I_visual[k];
    JtJ += pre.dR_dbg().transpose() * pre.dR_dbg();
    Jtr += pre.dR_dbg().transpose() * so3::log(Mat3(pre.delta_R().transpose() * R_visual));
  }
  return JtJ.ldlt().solve(Jtr);
}

// Velocities v_k (and, unless g_c is given, gravity) in c, from the kinematics of each interval (Forster et al.
// eq. (33) with R_k, p_k known): v_k dt + g dt^2 / 2 = p_k+1 - p_k - R_k dp_k and v_k+1 - v_k - g dt = R_k dv_k.
Eigen::VectorXd solve_velocities(const std::vector<Mat3>& R_c_I, const std::vector<Vec3>& p_c_I,
                                 const std::vector<Preintegration>& pre, const Vec3* g_c) {
  const int n = static_cast<int>(R_c_I.size());
  const int unknowns = 3 * n + (g_c ? 0 : 3);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(6 * (n - 1), unknowns);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(6 * (n - 1));
  for (int k = 0; k + 1 < n; ++k) {
    const double dt = pre[k].dt_s();
    const int row = 6 * k;
    H.block<3, 3>(row, 3 * k) = dt * Mat3::Identity();
    z.segment<3>(row) = p_c_I[k + 1] - p_c_I[k] - R_c_I[k] * pre[k].delta_p();
    H.block<3, 3>(row + 3, 3 * (k + 1)) = Mat3::Identity();
    H.block<3, 3>(row + 3, 3 * k) = -Mat3::Identity();
    z.segment<3>(row + 3) = R_c_I[k] * pre[k].delta_v();
    if (g_c) {
      z.segment<3>(row) -= 0.5 * dt * dt * *g_c;
      z.segment<3>(row + 3) += dt * *g_c;
    } else {
      H.block<3, 3>(row, 3 * n) = 0.5 * dt * dt * Mat3::Identity();
      H.block<3, 3>(row + 3, 3 * n) = -dt * Mat3::Identity();
    }
  }
  return H.colPivHouseholderQr().solve(z);
}

}  // namespace

VisualInertialAlignment align_visual_inertial(const std::vector<FrontendOutput>& frames,
                                              const std::vector<ImuSample>& imu, const RigCalibration& calib,
                                              double focal_px, double gravity_m_s2,
                                              const VisualInertialAlignmentConfig& config) {
  VisualInertialAlignment out;
  const std::size_t n = frames.size();
  if (n < 3) {
    out.failure = "fewer than 3 stereo pairs";
    return out;
  }
  const std::vector<SE3> T_c_C0 = visual_motion(frames, calib, focal_px, config.min_pnp_inliers, &out.failure);
  if (T_c_C0.empty()) return out;
  // Positions from vision; rotations from the gyroscope, its bias calibrated on the visual ones (over a second the
  // gyroscope's drift is then far below the rotation noise of frame-to-frame PnP on stereo depth), the visual ones
  // then only checking them.
  std::vector<Mat3> R_c_I_visual(n);
  std::vector<Vec3> p_c_I(n);
  for (std::size_t k = 0; k < n; ++k) {
    const SE3 T_c_I = T_c_C0[k] * calib.T_I_C0.inverse();
    R_c_I_visual[k] = T_c_I.rotation();
    p_c_I[k] = T_c_I.translation();
  }
  const Vec3 bias_gyro_rad_s = gyro_bias_rad_s(frames, imu, R_c_I_visual, calib.imu);
  const std::vector<Preintegration> pre = preintegrate(frames, imu, bias_gyro_rad_s, calib.imu);
  std::vector<Mat3> R_c_I(n);
  for (std::size_t k = 0; k < n; ++k) {
    R_c_I[k] = k == 0 ? R_c_I_visual[0] : Mat3(R_c_I[k - 1] * pre[k - 1].delta_R());
    const Vec3 mismatch = so3::log(Mat3(R_c_I[k].transpose() * R_c_I_visual[k]));
    if (!(mismatch.norm() <= config.max_rotation_mismatch_rad)) {
      out.failure = "the visual and the gyroscope rotation disagree by " + std::to_string(mismatch.norm()) +
                    " rad at pair " + std::to_string(k);
      return out;
    }
  }
  const Eigen::VectorXd free = solve_velocities(R_c_I, p_c_I, pre, nullptr);
  Vec3 g_c = free.tail<3>();
  if (!(std::abs(g_c.norm() - gravity_m_s2) <= config.max_gravity_error_m_s2)) {
    out.failure = "gravity came out at " + std::to_string(g_c.norm()) + " m/s^2";
    return out;
  }
  g_c *= gravity_m_s2 / g_c.norm();
  const Eigen::VectorXd v_c = solve_velocities(R_c_I, p_c_I, pre, &g_c);
  // W: z up along -g, yaw of the first body pose 0 (as the static initialization).
  const Mat3 R_tilt = Quat::FromTwoVectors(-g_c, Vec3::UnitZ()).toRotationMatrix();
  const Mat3 R_tilt_I = R_tilt * R_c_I[0];
  const Mat3 R_W_c = so3::rot_z(-so3::yaw_rad(R_tilt_I)) * R_tilt;
  NavState x;
  x.t_ns = frames[0].t_ns;
  x.R_W_I = R_W_c * R_c_I[0];
  x.v_W_m_s = R_W_c * v_c.head<3>();
  x.bias_gyro_rad_s = bias_gyro_rad_s;
  out.state = x;
  return out;
}

}  // namespace vilslam
