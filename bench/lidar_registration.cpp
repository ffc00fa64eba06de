// LiDAR mapping cost per scan on the shared real pair (Velodyne HDL-32E, ~69k points): LOAM feature
// extraction of the new scan plus its scan-to-map registration against the previous scan's feature map.
// The VLP-16-sized case keeps every other ring (16 rings, ~35k points).
// Run: ./build/bin/bench_lidar_registration --benchmark_repetitions=10 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <string>

#include "io/cloud_io.h"
#include "io/scan_file.h"
#include "lidar/lidar_config.h"

namespace {

using namespace vilslam;

struct Case {
  LidarScan source, target;
  lidar::LidarConfig config;
};

lidar::RingConfig hdl32e() {
  lidar::RingConfig rings;
  rings.num_rings = 32;
  rings.min_elevation_deg = -30.67;
  rings.max_elevation_deg = 10.67;
  return rings;
}

// Keeps the even rings of an HDL-32E scan: a 16-ring scan with the ring field set.
LidarScan even_rings(const LidarScan& scan) {
  LidarScan out;
  out.has_ring = true;
  const lidar::Rings rings = lidar::assign_rings(scan, hdl32e());
  for (std::size_t r = 0; r < rings.size(); r += 2) {
    for (const std::uint32_t i : rings[r]) {
      LidarPoint p = scan.points[i];
      p.ring = static_cast<std::uint16_t>(r / 2);
      out.points.push_back(p);
    }
  }
  return out;
}

const Case* load_case(bool vlp16_sized) {
  const std::string dir = std::string(VILSLAM_SHARED_DATA) + "/lidar/small_gicp/";
  static Case cases[2];
  static bool loaded = false;
  if (!loaded) {
    for (int k = 0; k < 2; ++k) {
      cases[k].source = scan_from_cloud(read_cloud(dir + "source.ply"));
      cases[k].target = scan_from_cloud(read_cloud(dir + "target.ply"));
      cases[k].config.rings = hdl32e();
    }
    cases[1].source = even_rings(cases[1].source);
    cases[1].target = even_rings(cases[1].target);
    cases[1].config.rings.num_rings = 16;
    loaded = true;
  }
  return &cases[vlp16_sized ? 1 : 0];
}

void BM_FeatureExtraction(benchmark::State& state) {
  const Case* c = load_case(state.range(0) == 1);
  const lidar::FeatureConfig features = lidar::features_for_registration(c->config);
  for (auto _ : state) {
    benchmark::DoNotOptimize(lidar::extract_features(c->source, c->config.rings, features));
  }
  state.counters["points"] = static_cast<double>(c->source.points.size());
}

void BM_ExtractAndRegister(benchmark::State& state) {
  const Case* c = load_case(state.range(0) == 1);
  const lidar::FeatureConfig feature_config = lidar::features_for_registration(c->config);
  lidar::FeatureMap map(c->config.map);
  map.insert(lidar::extract_features(c->target, c->config.rings, feature_config), SE3());
  lidar::RegistrationResult result;
  for (auto _ : state) {
    const lidar::FeatureScan features = lidar::extract_features(c->source, c->config.rings, feature_config);
    result = lidar::register_scan(features, map, SE3(), c->config.registration);
    benchmark::DoNotOptimize(result);
  }
  state.counters["points"] = static_cast<double>(c->source.points.size());
  state.counters["features"] = result.num_edge_features + result.num_surface_features;
  state.counters["outer_iterations"] = result.outer_iterations;
  state.counters["tx_m"] = result.T_W_L.translation().x();
}

// Argument 0: the full HDL-32E scans; 1: VLP-16-sized (even rings only).
BENCHMARK(BM_FeatureExtraction)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK(BM_ExtractAndRegister)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

}  // namespace
