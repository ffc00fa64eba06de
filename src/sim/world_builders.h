#pragma once
// The scenario generators: each fills a SceneBuilder with geometry, materials and a closed route of
// about length_m.
#include <optional>

#include <Eigen/Geometry>

#include "sim/scene_builder.h"

namespace vilslam::sim {

void build_highbay(SceneBuilder& builder, double length_m);
void build_loop(SceneBuilder& builder, double length_m);
void build_hallway(SceneBuilder& builder, double length_m);
void build_tunnel(SceneBuilder& builder, double length_m);
void build_outdoor(SceneBuilder& builder, double length_m);
// flight_W: the body positions' bounds of a recorded flight the room must hold (grown around it when it
// leaves the Vicon room's box).
void build_room(SceneBuilder& builder, double length_m, const std::optional<Eigen::AlignedBox3d>& flight_W);

}  // namespace vilslam::sim
