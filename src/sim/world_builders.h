#pragma once
// The scenario generators: each fills a SceneBuilder with geometry, materials and a closed route of
// about length_m.
#include "sim/scene_builder.h"

namespace vilslam::sim {

void build_highbay(SceneBuilder& builder, double length_m);
void build_loop(SceneBuilder& builder, double length_m);
void build_hallway(SceneBuilder& builder, double length_m);
void build_tunnel(SceneBuilder& builder, double length_m);
void build_outdoor(SceneBuilder& builder, double length_m);
void build_room(SceneBuilder& builder, double length_m);

}  // namespace vilslam::sim
