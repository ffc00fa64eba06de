#include "sim/spline.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

namespace vilslam::sim {
namespace {

// Uniform cubic B-spline basis on local t in [0,1] and its derivatives (de Boor, "A Practical Guide
// to Splines", uniform knots; matrix form of Qin 2000).
Eigen::Vector4d basis(double t) {
  const double s = 1.0 - t;
  return Eigen::Vector4d(s * s * s, 3 * t * t * t - 6 * t * t + 4, -3 * t * t * t + 3 * t * t + 3 * t + 1, t * t * t) /
         6.0;
}
Eigen::Vector4d basis_d1(double t) {
  const double s = 1.0 - t;
  return Eigen::Vector4d(-s * s, 3 * t * t - 4 * t, -3 * t * t + 2 * t + 1, t * t) / 2.0;
}
Eigen::Vector4d basis_d2(double t) { return Eigen::Vector4d(1.0 - t, 3 * t - 2, -3 * t + 1, t); }

// Segment index and local parameter of an open spline with `segments` segments, clamped.
std::pair<int, double> open_segment(double u, int segments) {
  u = std::clamp(u, 0.0, static_cast<double>(segments));
  const int i = std::min(static_cast<int>(std::floor(u)), segments - 1);
  return {i, u - i};
}

}  // namespace

UniformBSpline UniformBSpline::periodic(Eigen::MatrixXd controls) {
  if (controls.cols() < 4) throw std::invalid_argument("periodic B-spline needs at least 4 control points");
  return UniformBSpline(std::move(controls), true);
}

UniformBSpline UniformBSpline::fit(const std::vector<double>& u, const Eigen::MatrixXd& values, int num_controls,
                                   double smoothing) {
  if (num_controls < 4) throw std::invalid_argument("open B-spline needs at least 4 control points");
  if (static_cast<Eigen::Index>(u.size()) != values.cols()) throw std::invalid_argument("fit: size mismatch");
  const int segments = num_controls - 3;
  std::vector<Eigen::Triplet<double>> normal;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(num_controls, values.rows());
  for (std::size_t j = 0; j < u.size(); ++j) {
    const auto [i, t] = open_segment(u[j], segments);
    const Eigen::Vector4d b = basis(t);
    for (int r = 0; r < 4; ++r) {
      rhs.row(i + r) += b[r] * values.col(static_cast<Eigen::Index>(j)).transpose();
      for (int c = 0; c < 4; ++c) normal.emplace_back(i + r, i + c, b[r] * b[c]);
    }
  }
  const Eigen::Vector3d second_difference(1.0, -2.0, 1.0);
  for (int i = 0; i + 2 < num_controls; ++i) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) normal.emplace_back(i + r, i + c, smoothing * second_difference[r] * second_difference[c]);
  }
  Eigen::SparseMatrix<double> A(num_controls, num_controls);
  A.setFromTriplets(normal.begin(), normal.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) throw std::invalid_argument("fit: singular normal equations");
  Eigen::MatrixXd controls = solver.solve(rhs).transpose();
  return UniformBSpline(std::move(controls), false);
}

double UniformBSpline::max_u() const {
  return periodic_ ? static_cast<double>(controls_.cols()) : static_cast<double>(controls_.cols() - 3);
}

SplinePoint UniformBSpline::eval(double u) const {
  const int n = static_cast<int>(controls_.cols());
  int first = 0;
  double t = 0;
  if (periodic_) {
    u = std::fmod(u, static_cast<double>(n));
    if (u < 0) u += n;
    const int i = std::min(static_cast<int>(std::floor(u)), n - 1);
    t = u - i;
    first = i - 1;
  } else {
    std::tie(first, t) = open_segment(u, n - 3);
  }
  const Eigen::Vector4d b = basis(t), b1 = basis_d1(t), b2 = basis_d2(t);
  SplinePoint p{Eigen::VectorXd::Zero(controls_.rows()), Eigen::VectorXd::Zero(controls_.rows()),
                Eigen::VectorXd::Zero(controls_.rows())};
  for (int r = 0; r < 4; ++r) {
    const int c = ((first + r) % n + n) % n;
    p.value += b[r] * controls_.col(c);
    p.d1 += b1[r] * controls_.col(c);
    p.d2 += b2[r] * controls_.col(c);
  }
  return p;
}

}  // namespace vilslam::sim
