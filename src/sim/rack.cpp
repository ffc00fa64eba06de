#include "sim/rack.h"

#include <algorithm>
#include <cmath>

#include "sim/route.h"

namespace vilslam::sim {
namespace {

constexpr double kBay = 2.7;
constexpr double kUpright = 0.09;
constexpr double kDeck = 0.08;

// Boxes standing side by side on a shelf from x0 to x1 at height z, between y0 and y1, under z_top.
void stock_shelf(SceneBuilder& builder, const RackStyle& style, double x0, double x1, double y0, double y1, double z,
                 double z_top) {
  Rng& rng = builder.rng();
  if (rng.chance(0.15)) return;
  double x = x0 + rng.uniform(0.05, 0.3);
  while (true) {
    const double w = rng.uniform(0.5, 1.2);
    if (x + w > x1 - 0.05) break;
    const double d = std::min(rng.uniform(0.6, 1.0), y1 - y0 - 0.05);
    const double h = rng.uniform(0.3, std::max(0.35, z_top - z - 0.15));
    const double y_mid = 0.5 * (y0 + y1) + rng.uniform(-0.03, 0.03);
    builder.add(Box::axis_aligned(Vec3(x, y_mid - 0.5 * d, z), Vec3(x + w, y_mid + 0.5 * d, z + h)), rng.pick(style.goods));
    x += w + rng.uniform(0.05, 0.4);
  }
}

}  // namespace

void add_rack(SceneBuilder& builder, const RackStyle& style, double x0, double x1, double y_back, double front_sign) {
  const int bays = std::max(1, static_cast<int>(std::lround((x1 - x0) / kBay)));
  const double bay = (x1 - x0) / bays;
  const double y_front = y_back + front_sign * style.depth_m;
  const double y_lo = std::min(y_back, y_front), y_hi = std::max(y_back, y_front);
  for (int i = 0; i <= bays; ++i) {
    const double x = x0 + i * bay;
    for (const double y : {y_lo, y_hi - kUpright}) {
      builder.add(Box::axis_aligned(Vec3(x, y, 0), Vec3(x + kUpright, y + kUpright, style.height_m)), style.upright);
    }
  }
  const double level_gap = style.height_m / (style.levels + 1);
  for (int i = 0; i < bays; ++i) {
    const double bx0 = x0 + i * bay + kUpright, bx1 = x0 + (i + 1) * bay;
    for (int level = 0; level <= style.levels; ++level) {
      const double z = level * level_gap;
      if (level > 0) {
        builder.add(Box::axis_aligned(Vec3(bx0, y_lo, z - kDeck), Vec3(bx1, y_hi, z)), style.deck);
      }
      stock_shelf(builder, style, bx0, bx1, y_lo, y_hi, z, z + level_gap - kDeck);
    }
  }
}

void add_floor_clutter(SceneBuilder& builder, const Eigen::AlignedBox2d& area, int count, const std::vector<int>& materials,
                       double clear_m) {
  Rng& rng = builder.rng();
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d c(rng.uniform(area.min().x(), area.max().x()), rng.uniform(area.min().y(), area.max().y()));
    const int material = rng.pick(materials);
    if (rng.chance(0.3)) {
      const double r = rng.uniform(0.25, 0.35);
      const Cylinder barrel(c, 0.0, rng.uniform(0.8, 1.0), r);
      if (route_clearance(builder.route(), barrel) >= clear_m) builder.add(barrel, material);
      continue;
    }
    // A pallet stack: a pallet and one to three boxes, turned at random.
    const Mat3 R = Eigen::AngleAxisd(rng.uniform(0, M_PI), Vec3::UnitZ()).toRotationMatrix();
    const Vec3 half(rng.uniform(0.4, 0.7), rng.uniform(0.4, 0.6), 0.07);
    const Box envelope(Vec3(c.x(), c.y(), 1.15), R, Vec3(half.x(), half.y(), 1.15));  // the tallest stack
    if (route_clearance(builder.route(), envelope) < clear_m) continue;
    builder.add(Box(Vec3(c.x(), c.y(), 0.07), R, half), material);
    double z = 0.14;
    const int layers = rng.integer(1, 3);
    for (int l = 0; l < layers; ++l) {
      const double h = rng.uniform(0.3, 0.7);
      const Vec3 box_half(half.x() * rng.uniform(0.7, 1.0), half.y() * rng.uniform(0.7, 1.0), 0.5 * h);
      builder.add(Box(Vec3(c.x(), c.y(), z + 0.5 * h), R, box_half), rng.pick(materials));
      z += h;
    }
  }
}

}  // namespace vilslam::sim
