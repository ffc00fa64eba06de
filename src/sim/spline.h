#pragma once
// Uniform cubic B-splines in R^n: periodic (closed curves) and open (fitted to timestamped samples).
// Parameter u is in knot intervals; the curve and its first two derivatives d/du are C2-continuous.
#include <Eigen/Core>
#include <vector>

namespace vilslam::sim {

struct SplinePoint {
  Eigen::VectorXd value;
  Eigen::VectorXd d1;  // d value / du
  Eigen::VectorXd d2;  // d^2 value / du^2
};

class UniformBSpline {
 public:
  // Closed curve over the control polygon (columns of controls, at least 4); u in [0, num_controls).
  // At u = i the curve is (P[i-1] + 4 P[i] + P[i+1]) / 6.
  static UniformBSpline periodic(Eigen::MatrixXd controls);
  // Least-squares fit of an open spline with num_controls (>= 4) controls to samples (u_j, columns of
  // values), u_j in [0, num_controls - 3]; smoothing weighs squared second differences of the controls
  // (it also keeps knots without samples well-posed).
  static UniformBSpline fit(const std::vector<double>& u, const Eigen::MatrixXd& values, int num_controls,
                            double smoothing);

  // u is wrapped (periodic) or clamped (open) into the valid range.
  SplinePoint eval(double u) const;
  double max_u() const;
  int dimension() const { return static_cast<int>(controls_.rows()); }
  bool is_periodic() const { return periodic_; }

 private:
  UniformBSpline(Eigen::MatrixXd controls, bool periodic) : controls_(std::move(controls)), periodic_(periodic) {}
  Eigen::MatrixXd controls_;
  bool periodic_;
};

}  // namespace vilslam::sim
