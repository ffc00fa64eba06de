#pragma once
// Corridors: walls, floor and ceiling around a centre line, with sparse doors, posters and signs.
#include "sim/route.h"

namespace vilslam::sim {

struct CorridorStyle {
  double width_m = 2.0;
  double height_m = 3.0;
  int wall = 0, floor = 0, ceiling = 0;         // materials
  int door = 0, poster = 0, sign = 0, light = 0;  // decal materials
  double decals_per_10m = 2.0;                  // doors, posters and signs per 10 m of wall (both sides)
};

// A closed loop of corridors, or an open one whose two ends stay open (doorways into a hall).
void add_corridor(SceneBuilder& builder, const Polygon2& centerline, bool closed, const CorridorStyle& style);

}  // namespace vilslam::sim
