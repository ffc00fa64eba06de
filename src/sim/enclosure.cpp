#include "sim/enclosure.h"

#include <algorithm>

namespace vilslam::sim {

Enclosure add_enclosure(SceneBuilder& builder, const Eigen::AlignedBox3d& box, const Walls& materials,
                                 const std::vector<Doorway>& doorways) {
  const Vec3 lo = box.min(), hi = box.max(), size = box.sizes();
  const Vec3 ex = Vec3::UnitX(), ey = Vec3::UnitY(), ez = Vec3::UnitZ();
  Enclosure out;
  out.floor = &builder.add(Quad(lo, ex, size.x(), ey, size.y(), true), materials.floor);
  out.ceiling = &builder.add(Quad(Vec3(lo.x(), lo.y(), hi.z()), ex, size.x(), ey, size.y()), materials.ceiling);
  // Wall k runs counter-clockwise from its start corner along its direction.
  const Vec3 starts[4] = {lo, Vec3(hi.x(), lo.y(), lo.z()), Vec3(hi.x(), hi.y(), lo.z()), Vec3(lo.x(), hi.y(), lo.z())};
  const Vec3 dirs[4] = {ex, ey, -ex, -ey};
  const double lengths[4] = {size.x(), size.y(), size.x(), size.y()};
  for (int k = 0; k < 4; ++k) {
    // Doorway intervals along this wall, in the wall's own coordinate from its start corner.
    std::vector<std::pair<double, double>> gaps;
    for (const Doorway& d : doorways) {
      if (d.wall != k) continue;
      const double along = (k % 2 == 0) ? (d.center - starts[k].x()) * dirs[k].x() : (d.center - starts[k].y()) * dirs[k].y();
      gaps.emplace_back(along - 0.5 * d.width_m, along + 0.5 * d.width_m);
      const Vec3 lintel = starts[k] + gaps.back().first * dirs[k] + d.height_m * ez;
      builder.add(Quad(lintel, dirs[k], d.width_m, ez, size.z() - d.height_m), materials.wall);
    }
    std::sort(gaps.begin(), gaps.end());
    double from = 0;
    gaps.emplace_back(lengths[k], lengths[k]);
    for (const auto& [gap_start, gap_end] : gaps) {
      if (gap_start > from) {
        out.walls.push_back(&builder.add(Quad(starts[k] + from * dirs[k], dirs[k], gap_start - from, ez, size.z()), materials.wall));
      }
      from = gap_end;
    }
  }
  return out;
}

}  // namespace vilslam::sim
