#include "vio/smoother.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <stdexcept>

#include "vio/imu_factor.h"

namespace vilslam {
namespace {

// Whitened factor of a residual r with covariance cov: L^-1 r, L^-1 J with cov = L L^T.
template <int Rows>
LinearFactor whitened(std::vector<int> slots, const Eigen::Matrix<double, Rows, Rows>& cov,
                      const Eigen::Matrix<double, Rows, 1>& r, const Eigen::Matrix<double, Rows, kStateDim>& J_i,
                      const Eigen::Matrix<double, Rows, kStateDim>& J_j) {
  const Eigen::LLT<Eigen::Matrix<double, Rows, Rows>> llt(cov);
  Eigen::MatrixXd J(Rows, 2 * kStateDim);
  J << J_i, J_j;
  const Eigen::MatrixXd Jw = llt.matrixL().solve(J);
  const Eigen::VectorXd rw = llt.matrixL().solve(r);
  return make_linear_factor(std::move(slots), Jw, rw);
}

// Wilson-Hilferty approximation of the chi-square quantile with dof degrees of freedom.
double chi2_quantile(int dof, double normal_quantile) {
  const double k = dof;
  const double c = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - c + normal_quantile * std::sqrt(c), 3);
}

}  // namespace

Smoother::Smoother(const SmootherConfig& config, const StereoExtrinsics& extrinsics, const ImuNoise& noise,
                   double focal_px)
    : config_(config), extrinsics_(extrinsics), noise_(noise), sigma_norm_(config.pixel_sigma_px / focal_px) {
  if (config.window_size < 2) throw std::invalid_argument("Smoother: window_size must be at least 2");
  if (!(focal_px > 0) || !(config.pixel_sigma_px > 0)) throw std::invalid_argument("Smoother: bad pixel noise");
}

void Smoother::initialize(const NavState& x0, const Vec15& prior_sigma, const FrontendOutput& frame) {
  reset();
  const std::uint64_t id = next_id_++;
  window_.push_back({id, x0, std::nullopt});
  prior_ = diagonal_prior(id, x0, prior_sigma);
  newest_covariance_ = prior_sigma.cwiseAbs2().asDiagonal();
  add_observations(id, frame);
}

const NavState& Smoother::newest() const {
  if (window_.empty()) throw std::logic_error("Smoother::newest before initialize or after reset");
  return window_.back().x;
}

void Smoother::reset() {
  window_.clear();
  tracks_.clear();
  rejected_tracks_.clear();
  stats_ = {};
}

void Smoother::add_frame(const Preintegration& preint, const FrontendOutput& frame) {
  if (window_.empty()) throw std::logic_error("Smoother::add_frame before initialize");
  if (frame.t_ns <= newest().t_ns) throw std::invalid_argument("Smoother::add_frame: frame time not increasing");
  NavState x = predict_state(preint, newest(), gravity_W());
  x.t_ns = frame.t_ns;
  const std::uint64_t id = next_id_++;
  window_.push_back({id, x, preint});
  add_observations(id, frame);
  optimize();
  if (static_cast<int>(window_.size()) > config_.window_size) marginalize_oldest();
}

std::vector<NavState> Smoother::window_states() const {
  std::vector<NavState> states;
  for (const Entry& e : window_) states.push_back(e.x);
  return states;
}

void Smoother::add_observations(std::uint64_t state_id, const FrontendOutput& frame) {
  for (const StereoMatch& m : frame.matches) {
    if (rejected_tracks_.count(m.track_id) || !m.left_norm.allFinite() || !m.right_norm.allFinite()) continue;
    tracks_[m.track_id].push_back({state_id, m.left_norm, m.right_norm});
  }
}

int Smoother::slot_of(std::uint64_t id) const {
  for (size_t i = 0; i < window_.size(); ++i) {
    if (window_[i].id == id) return static_cast<int>(i);
  }
  throw std::logic_error("Smoother: state id not in window");
}

std::vector<LinearFactor> Smoother::imu_factors(const std::vector<NavState>& states, int j) const {
  const Preintegration& preint = *window_[j].from_previous;
  const ImuResidual imu = imu_residual(preint, states[j - 1], states[j], gravity_W());
  const BiasResidual bias = bias_residual(states[j - 1], states[j]);
  return {whitened<9>({j - 1, j}, preint.covariance(), imu.r, imu.J_i, imu.J_j),
          whitened<6>({j - 1, j}, bias_covariance(noise_, preint.dt_s()), bias.r, bias.J_i, bias.J_j)};
}

std::optional<LinearFactor> Smoother::vision_factor(const std::vector<TrackObservation>& track,
                                                    const std::vector<NavState>& states) const {
  if (track.size() < 2) return std::nullopt;  // one stereo pair alone does not constrain the motion
  std::vector<StereoObservation> obs;
  for (const TrackObservation& t : track) obs.push_back({slot_of(t.state_id), t.left_norm, t.right_norm});
  const std::optional<Vec3> x_W = triangulate(obs, states, extrinsics_);
  if (!x_W) return std::nullopt;
  return structureless_factor(obs, linearize_landmark(obs, states, extrinsics_, *x_W, sigma_norm_));
}

std::vector<LinearFactor> Smoother::linearize(const std::vector<NavState>& states) const {
  std::vector<LinearFactor> factors;
  std::vector<int> prior_slots;
  for (std::uint64_t id : prior_.state_ids) prior_slots.push_back(slot_of(id));
  factors.push_back(prior_linear_factor(prior_, states, prior_slots));
  for (int j = 1; j < static_cast<int>(states.size()); ++j) {
    for (LinearFactor& f : imu_factors(states, j)) factors.push_back(std::move(f));
  }
  for (const auto& [track_id, track] : tracks_) {
    if (std::optional<LinearFactor> f = vision_factor(track, states)) factors.push_back(std::move(*f));
  }
  return factors;
}

int Smoother::reject_outliers(const std::vector<NavState>& states) {
  int rejected = 0;
  for (auto it = tracks_.begin(); it != tracks_.end();) {
    const std::optional<LinearFactor> f = vision_factor(it->second, states);
    const int dof = 4 * static_cast<int>(it->second.size()) - 3;
    if (f && f->cost > chi2_quantile(dof, config_.outlier_normal_quantile)) {
      rejected_tracks_.insert(it->first);
      it = tracks_.erase(it);
      ++rejected;
    } else {
      ++it;
    }
  }
  return rejected;
}

void Smoother::optimize() {
  std::vector<NavState> states = window_states();
  const Linearizer lin = [this](const std::vector<NavState>& s) { return linearize(s); };
  LmSummary summary = solve_lm(lin, states, config_.lm);
  const int rejected = reject_outliers(states);
  if (rejected > 0) {
    const int first_iterations = summary.iterations;
    summary = solve_lm(lin, states, config_.lm);
    summary.iterations += first_iterations;
  }
  for (size_t i = 0; i < window_.size(); ++i) window_[i].x = states[i];
  stats_.rejected_landmarks += rejected;
  stats_.lm_iterations = summary.iterations;
  stats_.final_cost = summary.final_cost;
  stats_.landmarks = 0;
  for (const auto& [track_id, track] : tracks_) stats_.landmarks += track.size() >= 2 ? 1 : 0;

  // Newest state's covariance: the last 15 columns of H^-1.
  const int n = static_cast<int>(summary.H.rows());
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(n, kStateDim);
  unit.bottomRows(kStateDim).setIdentity();
  const Eigen::MatrixXd cols = summary.H.ldlt().solve(unit);
  newest_covariance_ = cols.bottomRows(kStateDim);
  newest_covariance_ = 0.5 * (newest_covariance_ + newest_covariance_.transpose()).eval();
}

void Smoother::marginalize_oldest() {
  const std::vector<NavState> states = window_states();
  const std::uint64_t oldest = window_.front().id;
  std::vector<std::uint64_t> ids;
  for (const Entry& e : window_) ids.push_back(e.id);

  // Every factor touching the oldest state: the prior, the IMU and bias factors to the next state, and
  // the vision factors of the landmarks it observes (their observations are consumed by the prior).
  std::vector<LinearFactor> factors;
  std::vector<int> prior_slots;
  for (std::uint64_t id : prior_.state_ids) prior_slots.push_back(slot_of(id));
  factors.push_back(prior_linear_factor(prior_, states, prior_slots));
  for (LinearFactor& f : imu_factors(states, 1)) factors.push_back(std::move(f));
  for (auto it = tracks_.begin(); it != tracks_.end();) {
    if (it->second.front().state_id != oldest) {
      ++it;
      continue;
    }
    if (std::optional<LinearFactor> f = vision_factor(it->second, states)) factors.push_back(std::move(*f));
    it = tracks_.erase(it);
  }
  prior_ = marginalize(factors, 0, states, ids);
  window_.pop_front();
  window_.front().from_previous.reset();
}

}  // namespace vilslam
