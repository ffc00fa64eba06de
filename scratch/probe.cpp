// scratch: register key scan v to key scan u (both raw sweeps at rest) with the loop closer's ICP settings
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include "io/dataset.h"
#include "lidar/features.h"
#include "lidar/feature_map.h"
#include "lidar/registration.h"
#include "lidar/lidar_config.h"
using namespace vilslam;
int main(int argc, char** argv) {
  const std::string ds = argv[1];
  const TimeNs tu = std::atoll(argv[2]), tv = std::atoll(argv[3]);
  lidar::LidarConfig lc = argc > 4 ? lidar::load_lidar_config(argv[4]) : lidar::LidarConfig{};
  lc.map.edges.min_point_spacing_m = lc.map.surfaces.min_point_spacing_m = 0.05;
  lc.registration.source_edge_leaf_m = lc.registration.source_surface_leaf_m = 0.1;
  lc.registration.association.min_plane_spread_ratio = getenv("SPREAD") ? atof(getenv("SPREAD")) : 0.1;
  lc.registration.loss_scale_m = 0.05;
  if (getenv("NOREMAP")) lc.registration.remap_degenerate_directions = false;
  auto reader = open_dataset(ds);
  std::optional<LidarScan> su, sv;
  while (auto e = reader->next()) {
    if (auto* s = std::get_if<LidarScan>(&e->data)) {
      if (s->t_ns == tu) su = *s;
      if (s->t_ns == tv) sv = *s;
    }
  }
  if (!su || !sv) { std::cerr << "scan not found\n"; return 1; }
  auto fu = lidar::extract_features(*su, lc.rings, lc.features);
  auto fv = lidar::extract_features(*sv, lc.rings, lc.features);
  if (getenv("ZMAX") || getenv("ZMIN") || getenv("RMAX")) {
    const double zmax = getenv("ZMAX") ? atof(getenv("ZMAX")) : 1e9, zmin = getenv("ZMIN") ? atof(getenv("ZMIN")) : -1e9;
    const double rmax = getenv("RMAX") ? atof(getenv("RMAX")) : 1e9;
    std::vector<lidar::FeaturePoint> keep;
    for (auto& f : fv.surfaces) if (f.p_L.z() <= zmax && f.p_L.z() >= zmin && f.p_L.norm() <= rmax) keep.push_back(f);
    fv.surfaces = keep;
  }
  lidar::FeatureMap map(lc.map);
  map.insert(fu, SE3());
  std::printf("features u %zu/%zu v %zu/%zu\n", fu.edges.size(), fu.surfaces.size(), fv.edges.size(), fv.surfaces.size());
  auto r = lidar::register_scan(fv, map, SE3(), lc.registration);
  Vec6 x = r.T_W_L.log();
  std::printf("result t %.4f %.4f %.4f rot[deg] %.3f %.3f %.3f  edges %d planes %d rms %.4f\n", x(0), x(1), x(2),
              x(3) * 57.2958, x(4) * 57.2958, x(5) * 57.2958, r.num_edge_matches, r.num_surface_matches, r.rms_residual_m);
  std::cout << "eig " << r.degeneracy.eigenvalues.transpose() << "\n";
  return 0;
}
