#pragma once
// A rectangular hall seen from inside: floor, ceiling and four walls as quads, with optional doorways.
#include <vector>

#include "sim/scene_builder.h"

namespace vilslam::sim {

struct Doorway {
  int wall = 0;          // 0: y = min, 1: x = max, 2: y = max, 3: x = min
  double center = 0;     // position along the wall (x or y in the world)
  double width_m = 2.0;
  double height_m = 3.0;
};

struct Walls {
  int floor = 0, ceiling = 0, wall = 0;  // materials
};

struct Enclosure {
  Quad* floor = nullptr;      // uv = (x, y) - min
  Quad* ceiling = nullptr;
  std::vector<Quad*> walls;   // one per wall k when it has no doorway (uv: along the wall, height)
};

// Adds the hall [min, max] with its doorways.
Enclosure add_enclosure(SceneBuilder& builder, const Eigen::AlignedBox3d& box, const Walls& materials,
                                 const std::vector<Doorway>& doorways = {});

}  // namespace vilslam::sim
