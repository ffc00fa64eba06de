#pragma once
// Procedural surface content of each Material kind, as a real scene would show it: nearly uniform
// painted walls, concrete with formwork seams, tie holes and speckle, shelves of boxes with labels,
// posters with text, foliage, ground with stones and cracks.
#include <Eigen/Core>

#include "sim/world.h"

namespace vilslam::sim {

// The detail texture repeats with this period in u and v (one precomputed tile).
constexpr double kTexturePeriodM = 4.096;
// The large-scale brightness variation repeats with this period, incommensurate with the detail one.
constexpr double kMacroPeriodM = 17.3;

// The renderer breaks the tile's periodicity by shifting whole cells of the tile by random multiples of
// the cell size and cross-fading over blend_m at cell borders. Cells are chosen per kind so that no
// discrete object (panel, box, poster) crosses a cell border.
struct ShuffleCell {
  int cells_u = 1, cells_v = 1;  // cells per texture period
  double blend_m = 0.1;
};
ShuffleCell shuffle_cell(Material::Kind kind);

// Albedo in [0, 1] of `material` at surface coordinates uv (metres): base_grey + contrast * pattern,
// periodic with kTexturePeriodM. texel_m is the size of the area the value stands for (edges of discrete
// content are smoothed over it). A pure function of its arguments.
float texture_albedo(const Material& material, const Eigen::Vector2d& uv_m, double texel_m);

// Slowly varying brightness factor around 1 (stains, uneven paint and light), periodic with
// kMacroPeriodM; its amplitude grows with the material's contrast.
float texture_macro_gain(const Material& material, const Eigen::Vector2d& uv_m);

}  // namespace vilslam::sim
