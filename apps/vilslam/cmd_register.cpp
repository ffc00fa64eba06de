// `vilslam register`: LOAM-feature scan-to-map registration of one scan (source) onto another (target).
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "common/error.h"
#include "common/json_writer.h"
#include "io/cloud_io.h"
#include "io/scan_file.h"
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

void write_vector(JsonWriter& json, const Vec6& v) {
  json.begin_array();
  for (int i = 0; i < 6; ++i) json.value(v(i));
  json.end_array();
}

void write_json(const std::string& path, const lidar::RegistrationResult& r) {
  JsonWriter json;
  json.begin_object().key("T_target_source").begin_array();
  const Mat4 T = r.T_W_L.matrix();
  for (int row = 0; row < 4; ++row) {
    json.begin_array();
    for (int col = 0; col < 4; ++col) json.value(T(row, col));
    json.end_array();
  }
  json.end_array();
  json.key("converged").value(r.converged).key("outer_iterations").value(r.outer_iterations);
  json.key("edge_features").value(r.num_edge_features).key("surface_features").value(r.num_surface_features);
  json.key("edge_matches").value(r.num_edge_matches).key("surface_matches").value(r.num_surface_matches);
  json.key("matched_fraction").value(r.matched_fraction).key("inlier_fraction").value(r.inlier_fraction);
  json.key("rms_residual_m").value(r.rms_residual_m);
  json.key("degeneracy").begin_object().key("eigenvalues");
  write_vector(json, r.degeneracy.eigenvalues);
  json.key("min_max_ratio").value(r.degeneracy.min_max_ratio).key("degenerate_directions").begin_array();
  for (const Vec6& d : r.degeneracy.degenerate_directions) write_vector(json, d);
  json.end_array().end_object().end_object();
  json.save(path);
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
    return lidar::extract_features(scan_from_cloud(read_cloud(path)), config.rings,
                                   lidar::features_for_registration(config));
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
  if (!o.json.empty()) write_json(o.json, r);
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
