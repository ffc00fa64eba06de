#pragma once
// The tables of an EuRoC ASL folder (shared by the EuRoC reader and the project's format, which extends it).
#include <string>
#include <vector>

#include "io/dataset_index.h"

namespace vilslam {

// imu0/data.csv: t_ns, w_RS_S xyz [rad/s], a_RS_S xyz [m/s^2].
std::vector<ImuSample> read_imu_csv(const std::string& path);

// Ground truth with EuRoC columns (t_ns, p_RS_R xyz, q_RS wxyz, v_RS_R xyz, b_w xyz, b_a xyz).
// T_S_I maps the IMU frame into the ground-truth sensor frame S: T_W_I = T_R_S T_S_I.
std::vector<GroundTruthState> read_groundtruth_csv(const std::string& path, const SE3& T_S_I);
// TUM ground truth (t [s] x y z qx qy qz qw); velocity and biases are zero.
std::vector<GroundTruthState> read_groundtruth_tum(const std::string& path, const SE3& T_S_I);

// The ground truth of a mav0 folder, the first found of: state_groundtruth_estimate0/data.csv,
// gt0/data.csv (EuRoC columns), state_groundtruth_estimate0/groundtruth.tum (TUM). The folder's
// sensor.yaml T_BS (identity when absent) places the tracked sensor S in the body: T_S_I = T_B_S^-1 T_B_I.
// Empty when there is none.
std::vector<GroundTruthState> read_euroc_groundtruth(const std::string& mav0, const SE3& T_B_I);

struct ImageRow {
  TimeNs t_ns = 0;
  std::string path;
};

// camN/data.csv (t_ns, filename) with image paths under camN/data/. A row whose file is missing is
// an InputError when missing_is_error, else skipped with a warning and listed in problems.
std::vector<ImageRow> read_camera_csv(const std::string& cam_dir, bool missing_is_error,
                                      std::vector<std::string>& problems);

// Pairs left and right rows with equal timestamps; unpaired rows are counted in problems.
std::vector<StereoEntry> pair_stereo(const std::vector<ImageRow>& left, const std::vector<ImageRow>& right,
                                     std::vector<std::string>& problems);

}  // namespace vilslam
