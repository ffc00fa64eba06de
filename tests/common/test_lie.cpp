#include <gtest/gtest.h>

#include <random>

#include "common/lie.h"

namespace vilslam {
namespace {

Vec3 random_vec3(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

TEST(So3, ExpLogRoundTrip) {
  std::mt19937 rng(1);
  for (int i = 0; i < 100; ++i) {
    const Vec3 phi = random_vec3(rng, 1.5);
    EXPECT_LT((so3::log(so3::exp(phi)) - phi).norm(), 1e-10);
  }
  EXPECT_LT(so3::log(so3::exp(Vec3(1e-10, -2e-10, 0))).norm(), 1e-9);
}

TEST(So3, RightJacobianMatchesNumericDerivative) {
  std::mt19937 rng(2);
  const double h = 1e-6;
  for (int i = 0; i < 20; ++i) {
    const Vec3 phi = random_vec3(rng, 1.5);
    Mat3 numeric;
    for (int k = 0; k < 3; ++k) {
      const Vec3 d = Vec3::Unit(k) * h;
      // Exp(phi)^-1 Exp(phi + d) = Exp(Jr d)
      numeric.col(k) = so3::log(so3::exp(phi).transpose() * so3::exp(phi + d)) / h;
    }
    EXPECT_LT((numeric - so3::right_jacobian(phi)).norm(), 1e-5);
    EXPECT_LT((so3::right_jacobian_inv(phi) * so3::right_jacobian(phi) - Mat3::Identity()).norm(), 1e-10);
  }
}

TEST(So3, LogOfPerturbedProductUsesInverseRightJacobian) {
  std::mt19937 rng(3);
  const double h = 1e-6;
  const Vec3 phi = random_vec3(rng, 1.0);
  Mat3 numeric;
  for (int k = 0; k < 3; ++k) {
    numeric.col(k) = (so3::log(so3::exp(phi) * so3::exp(Vec3::Unit(k) * h)) - phi) / h;
  }
  EXPECT_LT((numeric - so3::right_jacobian_inv(phi)).norm(), 1e-5);
}

TEST(So3, ProjectGivesRotation) {
  Mat3 M = so3::exp(Vec3(0.3, -0.2, 0.5));
  M(0, 1) += 0.01;
  EXPECT_GT(so3::orthonormality_error(M), 1e-3);
  EXPECT_LT(so3::orthonormality_error(so3::project(M)), 1e-12);
}

TEST(So3, YawIsTheZAngleOfTheZyxDecomposition) {
  for (const double yaw : {-3.0, -0.4, 0.0, 1.2, 3.1}) {
    const Mat3 R = so3::rot_z(yaw) * so3::exp(Vec3(0, 0.3, 0)) * so3::exp(Vec3(-0.2, 0, 0));  // yaw, pitch, roll
    EXPECT_NEAR(so3::yaw_rad(R), yaw, 1e-12);
    EXPECT_NEAR(so3::yaw_rad(so3::rot_z(-yaw) * R), 0.0, 1e-12);
  }
}

TEST(Se3, ExpLogRoundTripAndComposition) {
  std::mt19937 rng(4);
  for (int i = 0; i < 50; ++i) {
    Vec6 xi;
    xi << random_vec3(rng, 3.0), random_vec3(rng, 1.5);
    const SE3 T = SE3::exp(xi);
    EXPECT_LT((T.log() - xi).norm(), 1e-9);
    const Vec3 p = random_vec3(rng, 5.0);
    EXPECT_LT(((T.inverse() * T) * p - p).norm(), 1e-12);
    EXPECT_LT((T.matrix() * p.homogeneous() - (T * p).homogeneous()).norm(), 1e-12);
  }
}

TEST(Se3, AdjointMatchesConjugation) {
  std::mt19937 rng(5);
  Vec6 a, xi;
  a << random_vec3(rng, 2.0), random_vec3(rng, 1.0);
  xi << random_vec3(rng, 0.5), random_vec3(rng, 0.5);
  const SE3 T = SE3::exp(a);
  const SE3 lhs = T * SE3::exp(xi) * T.inverse();
  const SE3 rhs = SE3::exp(T.adjoint() * xi);
  EXPECT_LT((lhs.matrix() - rhs.matrix()).norm(), 1e-10);
}

TEST(Se3, ExpDerivativeAtIdentityIsTangent) {
  // d/dh Exp(h xi) at h = 0 is the matrix hat(xi): numeric check of the tangent ordering [rho; phi].
  Vec6 xi;
  xi << 0.1, -0.2, 0.3, 0.4, -0.5, 0.6;
  const double h = 1e-7;
  const Mat4 numeric = (SE3::exp(h * xi).matrix() - Mat4::Identity()) / h;
  Mat4 expected = Mat4::Zero();
  expected.topLeftCorner<3, 3>() = so3::hat(xi.tail<3>());
  expected.topRightCorner<3, 1>() = xi.head<3>();
  EXPECT_LT((numeric - expected).norm(), 1e-6);
}

TEST(Se3, InterpolationEndpointsAndMidpoint) {
  const SE3 a(so3::exp_quat(Vec3(0, 0, 0.2)), Vec3(1, 2, 3));
  const SE3 b(so3::exp_quat(Vec3(0, 0, 1.0)), Vec3(3, 2, 1));
  EXPECT_LT((interpolate(a, b, 0.0).matrix() - a.matrix()).norm(), 1e-12);
  EXPECT_LT((interpolate(a, b, 1.0).matrix() - b.matrix()).norm(), 1e-12);
  const SE3 mid = interpolate(a, b, 0.5);
  EXPECT_NEAR(so3::log(mid.quat()).z(), 0.6, 1e-12);
  EXPECT_LT((mid.translation() - Vec3(2, 2, 2)).norm(), 1e-12);
}

}  // namespace
}  // namespace vilslam
