// scratch: ICP of sweeps taken at rest at the same place (truth ~ identity) under association variants
#include <cstdio>
#include <cstdlib>
#include <map>
#include <sstream>
#include "io/dataset.h"
#include "lidar/features.h"
#include "lidar/feature_map.h"
#include "lidar/registration.h"
#include "lidar/lidar_config.h"
using namespace vilslam;
int main(int argc, char** argv) {
  auto reader = open_dataset(argv[1]);
  std::vector<std::pair<TimeNs, TimeNs>> pairs;
  for (int i = 2; i < argc; i += 2) pairs.push_back({std::atoll(argv[i]), std::atoll(argv[i + 1])});
  std::map<TimeNs, LidarScan> scans;
  while (auto e = reader->next())
    if (auto* s = std::get_if<LidarScan>(&e->data))
      for (auto& p : pairs) if (s->t_ns == p.first || s->t_ns == p.second) scans[s->t_ns] = *s;
  // variant: spread, neighbours, max plane distance, map spacing, source leaf
  struct V { double spread; int k; double dist; double spacing; double leaf; };
  std::vector<V> vs = {{0.1, 5, 0.2, 0.05, 0.1}, {0.0, 5, 0.2, 0.05, 0.1}, {0.1, 10, 0.2, 0.05, 0.1},
                       {0.1, 5, 0.05, 0.05, 0.1}, {0.0, 5, 0.05, 0.05, 0.1}, {0.1, 5, 0.2, 0.2, 0.1},
                       {0.1, 8, 0.1, 0.1, 0.1}};
  for (const V& v : vs) {
    lidar::LidarConfig lc;
    lc.map.edges.min_point_spacing_m = lc.map.surfaces.min_point_spacing_m = v.spacing;
    lc.registration.source_edge_leaf_m = lc.registration.source_surface_leaf_m = v.leaf;
    lc.registration.association.min_plane_spread_ratio = v.spread;
    lc.registration.association.num_neighbors = v.k;
    lc.registration.association.max_plane_point_distance_m = v.dist;
    lc.registration.loss_scale_m = 0.05;
    std::printf("spread %.2f k %d dist %.2f spacing %.2f leaf %.2f:", v.spread, v.k, v.dist, v.spacing, v.leaf);
    for (auto& p : pairs) {
      auto fu = lidar::extract_features(scans.at(p.first), lc.rings, lc.features);
      auto fv = lidar::extract_features(scans.at(p.second), lc.rings, lc.features);
      lidar::FeatureMap map(lc.map);
      map.insert(fu, SE3());
      auto r = lidar::register_scan(fv, map, SE3(), lc.registration);
      Vec6 x = r.T_W_L.log();
      std::printf("  | %.1fcm r%.2f p%.2f y%.2f", 100 * x.head<3>().norm(), x(3) * 57.2958, x(4) * 57.2958, x(5) * 57.2958);
    }
    std::printf("\n");
  }
}
