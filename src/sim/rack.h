#pragma once
// Warehouse furniture: pallet racks with stocked shelves, and floor clutter placed clear of the route.
#include <vector>

#include "sim/scene_builder.h"

namespace vilslam::sim {

struct RackStyle {
  int upright = 0, deck = 0;  // materials
  std::vector<int> goods;     // materials of the stored boxes
  double depth_m = 1.1;
  double height_m = 5.0;
  int levels = 3;             // decks above the floor level
};

// A rack along x from x0 to x1 with its back at y_back, extending towards +y (front_sign = +1) or -y.
void add_rack(SceneBuilder& builder, const RackStyle& style, double x0, double x1, double y_back, double front_sign);

// Random boxes, pallet stacks and barrels inside `area` (z ignored), each kept clear_m from the route.
void add_floor_clutter(SceneBuilder& builder, const Eigen::AlignedBox2d& area, int count, const std::vector<int>& materials,
                       double clear_m);

}  // namespace vilslam::sim
