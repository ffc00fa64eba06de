#include "sim/imu_alignment.h"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace vilslam::sim {
namespace {

// Rotation R minimizing sum |R a_k - b_k|^2 (orthogonal Procrustes / Kabsch via SVD of sum b a^T).
Mat3 procrustes(const Mat3& sum_b_at) {
  const Eigen::JacobiSVD<Mat3> svd(sum_b_at, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 D = Mat3::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

double rms(double sum_sq, std::size_t count) { return std::sqrt(sum_sq / (3.0 * static_cast<double>(count))); }

struct Recorded {
  Vec3 omega_B;
  Mat3 R_V_B;
  Vec3 a_V;
};

double gyro_sum_sq(const std::vector<Recorded>& rec, const std::vector<ImuSample>& s, const Mat3& R_B_I, const Vec3& b_g) {
  double sum = 0;
  for (std::size_t k = 0; k < s.size(); ++k) sum += (s[k].gyro_rad_s - R_B_I.transpose() * rec[k].omega_B - b_g).squaredNorm();
  return sum;
}

double accel_sum_sq(const std::vector<Recorded>& rec, const std::vector<ImuSample>& s, const Mat3& R_B_I, const Vec3& g_V,
                    const Vec3& b_a) {
  double sum = 0;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const Mat3 R_I_V = (rec[k].R_V_B * R_B_I).transpose();
    sum += (s[k].accel_m_s2 - R_I_V * (rec[k].a_V - g_V) - b_a).squaredNorm();
  }
  return sum;
}

}  // namespace

ImuAlignment align_imu_to_motion(const BodyMotion& motion, const std::vector<ImuSample>& samples) {
  if (samples.size() < 10) throw std::invalid_argument("align_imu_to_motion: needs at least 10 IMU samples");
  std::vector<Recorded> rec;
  rec.reserve(samples.size());
  Mat3 omega_scatter = Mat3::Zero();
  for (const ImuSample& s : samples) {
    const MotionState m = motion.state(s.t_ns);
    rec.push_back({m.omega_I, m.T_W_I.rotation(), m.a_W});
    omega_scatter += m.omega_I * m.omega_I.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat3> spread(omega_scatter / static_cast<double>(samples.size()));
  // (10 mrad/s)^2: with rates about at most one axis R_B_I is not determined and stays the identity.
  const bool rotation_observable = spread.eigenvalues()(1) > 1e-4;

  ImuAlignment out;
  const Vec3 g0(0, 0, -9.81);
  out.gyro_rms_identity_rad_s = rms(gyro_sum_sq(rec, samples, Mat3::Identity(), Vec3::Zero()), samples.size());
  out.accel_rms_identity_m_s2 = rms(accel_sum_sq(rec, samples, Mat3::Identity(), g0, Vec3::Zero()), samples.size());

  // Gyro: alternate the bias (mean residual) and the rotation (Procrustes of omega_B onto gyro - b_g).
  Mat3 R_B_I = Mat3::Identity();
  Vec3 b_g = Vec3::Zero();
  for (int it = 0; it < (rotation_observable ? 20 : 1); ++it) {
    Vec3 mean = Vec3::Zero();
    for (std::size_t k = 0; k < samples.size(); ++k) mean += samples[k].gyro_rad_s - R_B_I.transpose() * rec[k].omega_B;
    b_g = mean / static_cast<double>(samples.size());
    Mat3 sum = Mat3::Zero();  // R_I_B maps omega_B onto gyro - b_g
    for (std::size_t k = 0; k < samples.size(); ++k) sum += (samples[k].gyro_rad_s - b_g) * rec[k].omega_B.transpose();
    if (rotation_observable) R_B_I = procrustes(sum).transpose();
  }

  // Accelerometer, with |g_V| = 9.81: alternate the two exact block minimizers. For fixed b_a the cost is
  // N |g_V + mean(R_V_I (accel - b_a) - a_V)|^2 + const, minimized on the sphere by the scaled direction;
  // for fixed g_V, b_a is the mean residual. Starting from b_a = 0 a static recording (where the two are
  // not separable) keeps b_a = 0 and levels gravity along the measured specific force.
  std::vector<Mat3> R_V_I(samples.size());
  for (std::size_t k = 0; k < samples.size(); ++k) R_V_I[k] = rec[k].R_V_B * R_B_I;
  const double n = static_cast<double>(samples.size());
  Vec3 g_V = g0, b_a = Vec3::Zero();
  for (int it = 0; it < 50; ++it) {
    Vec3 mean = Vec3::Zero();
    for (std::size_t k = 0; k < samples.size(); ++k) mean += R_V_I[k] * (samples[k].accel_m_s2 - b_a) - rec[k].a_V;
    g_V = -g0.norm() * mean.normalized();
    Vec3 bias_sum = Vec3::Zero();
    for (std::size_t k = 0; k < samples.size(); ++k)
      bias_sum += samples[k].accel_m_s2 - R_V_I[k].transpose() * (rec[k].a_V - g_V);
    b_a = bias_sum / n;
  }
  out.rotation_estimated = rotation_observable;
  out.R_B_I = R_B_I;
  out.gyro_bias_rad_s = b_g;
  out.gravity_V_m_s2 = g_V;
  out.accel_bias_m_s2 = b_a;
  out.gyro_rms_rad_s = rms(gyro_sum_sq(rec, samples, R_B_I, b_g), samples.size());
  out.accel_rms_m_s2 = rms(accel_sum_sq(rec, samples, R_B_I, out.gravity_V_m_s2, out.accel_bias_m_s2), samples.size());
  return out;
}

ImuAlignedMotion::ImuAlignedMotion(std::unique_ptr<BodyMotion> recorded, const ImuAlignment& alignment)
    : recorded_(std::move(recorded)), R_B_I_(alignment.R_B_I) {
  const Mat3 R_W_V = Quat::FromTwoVectors(alignment.gravity_V_m_s2, Vec3(0, 0, -1)).toRotationMatrix();
  const Vec3 pivot_V = recorded_->pose(recorded_->start_ns()).translation();
  T_W_V_ = SE3(R_W_V, pivot_V - R_W_V * pivot_V);
}

MotionState ImuAlignedMotion::state(TimeNs t_ns) const {
  const MotionState b = recorded_->state(t_ns);
  MotionState out;
  out.t_ns = b.t_ns;
  out.T_W_I = T_W_V_ * b.T_W_I * SE3(R_B_I_, Vec3::Zero());
  out.v_W = T_W_V_.rotation() * b.v_W;
  out.a_W = T_W_V_.rotation() * b.a_W;
  out.omega_I = R_B_I_.transpose() * b.omega_I;
  return out;
}

}  // namespace vilslam::sim
