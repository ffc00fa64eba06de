#pragma once
// Closed routes: a polygon with rounded corners, resampled evenly (first == last), and the
// rectilinear loops that corridors and streets follow.
#include <vector>

#include <Eigen/Core>

#include "common/lie.h"
#include "sim/scene_builder.h"

namespace vilslam::sim {

using Polygon2 = std::vector<Eigen::Vector2d>;

// The closed polygon (corners in order, not repeated) with every corner replaced by a circular arc
// of radius_m, sampled every ~step_m at height z; first == last.
std::vector<Vec3> rounded_loop(const Polygon2& corners, double radius_m, double step_m, double z);

// The same closed polygon starting mid-way along its longest edge, where it gets a collinear corner
// (rounded_loop keeps it as a plain waypoint): a route that starts and ends on a straight stretch.
Polygon2 start_mid_longest_edge(const Polygon2& corners);

// Length of the rounded loop: perimeter minus, per corner of turning angle a, 2 r tan(a/2) - r a.
double rounded_loop_length(const Polygon2& corners, double radius_m);

// Scales the polygon about the origin so that its rounded loop has length_m.
void scale_to_length(Polygon2* corners, double radius_m, double length_m);

// Another route through the same world (map reuse: docs/simulator.md, "Another route"): the closed route
// started start_fraction of its length along (in [0, 1)) and shifted lateral_m to the left of the direction
// of travel (horizontally; to the right when negative). Both 0: the route unchanged.
std::vector<Vec3> varied_route(const std::vector<Vec3>& route_W, double start_fraction, double lateral_m);

// Length of a polyline.
double polyline_length(const std::vector<Vec3>& points);

// Smallest distance from the route's waypoints to the shape (waypoints are ~0.5 m apart).
double route_clearance(const std::vector<Vec3>& route_W, const Shape& shape);

// A rectilinear counter-clockwise loop in [0, width] x [0, depth]: the rectangle with up to
// `max_notches` random rectangular corner notches. Its perimeter is always 2 (width + depth).
Polygon2 rectilinear_loop(Rng& rng, double width, double depth, int max_notches, double min_notch);

}  // namespace vilslam::sim
