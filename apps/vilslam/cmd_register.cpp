// `vilslam register`: LOAM-feature scan-to-map registration of one scan (source) onto another (target).
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "common/error.h"
#include "io/cloud_io.h"
#include "lidar/lidar_config.h"
#include "vilslam/command.h"

namespace {

using namespace vilslam;

struct Options {
  std::string source, target, json, init, config;
  int rings = 0;
  double min_elevation_deg = 0.0, max_elevation_deg = 0.0;
};

Mat4 read_matrix(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "cannot open file");
  Mat4 T;
  for (int i = 0; i < 16; ++i) {
    if (!(in >> T(i / 4, i % 4))) throw InputError(path, "expected 16 numbers (a 4x4 matrix, row by row)");
  }
  if (!T.allFinite() || !T.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1)) ||
      so3::orthonormality_error(T.topLeftCorner<3, 3>()) > 1e-4) {
    throw InputError(path, "not a rigid transform");
  }
  return T;
}

std::string matrix_text(const Mat4& T) {
  std::ostringstream out;
  out << std::setprecision(9);
  for (int r = 0; r < 4; ++r) out << "  " << T(r, 0) << " " << T(r, 1) << " " << T(r, 2) << " " << T(r, 3) << "\n";
  return out.str();
}

std::string vector_json(const Vec6& v) {
  std::ostringstream out;
  out << std::setprecision(9) << "[";
  for (int i = 0; i < 6; ++i) out << (i ? ", " : "") << v(i);
  return out.str() + "]";
}

std::string result_json(const lidar::RegistrationResult& r) {
  const Mat4 T = r.T_W_L.matrix();
  std::ostringstream rest;
  rest << std::setprecision(9) << "{\n  \"T_target_source\": [";
  for (int row = 0; row < 4; ++row) {
    rest << (row ? ", [" : "[") << T(row, 0) << ", " << T(row, 1) << ", " << T(row, 2) << ", " << T(row, 3) << "]";
  }
  rest << "],\n";
  rest << "  \"converged\": " << (r.converged ? "true" : "false")
       << ",\n  \"outer_iterations\": " << r.outer_iterations << ",\n  \"edge_features\": " << r.num_edge_features
       << ",\n  \"surface_features\": " << r.num_surface_features << ",\n  \"edge_matches\": " << r.num_edge_matches
       << ",\n  \"surface_matches\": " << r.num_surface_matches << ",\n  \"matched_fraction\": " << r.matched_fraction
       << ",\n  \"inlier_fraction\": " << r.inlier_fraction << ",\n  \"rms_residual_m\": " << r.rms_residual_m
       << ",\n  \"degeneracy\": {\n    \"eigenvalues\": " << vector_json(r.degeneracy.eigenvalues)
       << ",\n    \"min_max_ratio\": " << r.degeneracy.min_max_ratio << ",\n    \"degenerate_directions\": [";
  for (std::size_t i = 0; i < r.degeneracy.degenerate_directions.size(); ++i) {
    rest << (i ? ", " : "") << vector_json(r.degeneracy.degenerate_directions[i]);
  }
  rest << "]\n  }\n}\n";
  return rest.str();
}

void write_text_atomically(const std::string& path, const std::string& text) {
  const std::string temp = path + ".tmp";
  {
    std::ofstream out(temp, std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
      std::filesystem::remove(temp);
      throw InputError(path, "cannot write file");
    }
  }
  std::filesystem::rename(temp, path);
}

int run(const Options& o) {
  lidar::LidarConfig config = o.config.empty() ? lidar::LidarConfig{} : lidar::load_lidar_config(o.config);
  if (o.rings > 0) {
    config.rings.num_rings = o.rings;
    config.rings.min_elevation_deg = o.min_elevation_deg;
    config.rings.max_elevation_deg = o.max_elevation_deg;
  }
  const SE3 T_init = o.init.empty() ? SE3() : SE3(read_matrix(o.init));
  const auto features_of = [&](const std::string& path) {
    return lidar::extract_features(lidar::to_scan(read_cloud(path)), config.rings, config.features);
  };
  const lidar::FeatureScan target = features_of(o.target);
  const lidar::FeatureScan source = features_of(o.source);
  lidar::FeatureMap map(config.map);
  map.insert(target, SE3());
  const lidar::RegistrationResult r = lidar::register_scan(source, map, T_init, config.registration);

  std::cout << "T_target_source:\n" << matrix_text(r.T_W_L.matrix());
  std::cout << std::setprecision(6) << "converged: " << (r.converged ? "yes" : "no") << " after "
            << r.outer_iterations << " outer iterations\n"
            << "features: " << r.num_edge_features << " edges, " << r.num_surface_features << " surfaces; matched "
            << r.num_edge_matches << " edges, " << r.num_surface_matches << " surfaces (" << r.matched_fraction
            << ")\n"
            << "rms residual: " << r.rms_residual_m << " m, inlier fraction: " << r.inlier_fraction << "\n"
            << "degeneracy: eigenvalues " << r.degeneracy.eigenvalues.transpose() << ", min/max "
            << r.degeneracy.min_max_ratio << ", " << r.degeneracy.degenerate_directions.size()
            << " degenerate direction(s)\n";
  for (const Vec6& d : r.degeneracy.degenerate_directions) std::cout << "  [rho; phi] " << d.transpose() << "\n";
  if (!o.json.empty()) write_text_atomically(o.json, result_json(r));
  return 0;
}

vilslam::cli::Command reg("register", "Register a LiDAR scan (source) to another (target) with LOAM features",
                          [](CLI::App& app) {
                            auto o = std::make_shared<Options>();
                            app.add_option("--source", o->source, "scan to align (.pcd, .ply, .bin)")->required();
                            app.add_option("--target", o->target, "scan that forms the map")->required();
                            app.add_option("--json", o->json, "write the result as JSON here");
                            app.add_option("--init", o->init, "initial T_target_source (4x4 text file)");
                            app.add_option("--config", o->config, "LiDAR mapping YAML (lidar::LidarConfig)");
                            auto* rings = app.add_option("--rings", o->rings, "rings when derived from elevation");
                            app.add_option("--min-elevation-deg", o->min_elevation_deg)->needs(rings);
                            app.add_option("--max-elevation-deg", o->max_elevation_deg)->needs(rings);
                            return [o]() { return run(*o); };
                          });

}  // namespace
