#include "sim/texture.h"

#include <algorithm>
#include <cmath>

#include "sim/procedural_noise.h"

namespace vilslam::sim {
namespace {

constexpr double P = kTexturePeriodM;

// A point of the tile: unit coordinates s (period 1) and the texel width in metres.
struct Sample {
  Eigen::Vector2d s;
  double texel_m;
  Eigen::Vector2d metres() const { return s * P; }
};

// A cell of an nx x ny grid over the tile: its index and the position inside it in metres.
struct Cell {
  int i, j;
  Eigen::Vector2d local_m;
  Eigen::Vector2d size_m;
};

Cell cell_of(const Eigen::Vector2d& s, int nx, int ny) {
  const double X = s.x() * nx, Y = s.y() * ny;
  const double fx = std::floor(X), fy = std::floor(Y);
  const Eigen::Vector2d size(P / nx, P / ny);
  const int i = ((static_cast<int>(fx) % nx) + nx) % nx, j = ((static_cast<int>(fy) % ny) + ny) % ny;
  return {i, j, Eigen::Vector2d((X - fx) * size.x(), (Y - fy) * size.y()), size};
}

// Signed distance from p to the axis-aligned rectangle [lo, hi] (negative inside).
double rect_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const Eigen::Vector2d c = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const Eigen::Vector2d q = (p - c).cwiseAbs() - half;
  return q.cwiseMax(0.0).norm() + std::min(std::max(q.x(), q.y()), 0.0);
}

// A random rectangle inside a cell, at least margin_m from its border: size a fraction in
// [f_min, f_max] of the cell size less the margins, per axis.
struct Rect {
  Eigen::Vector2d lo, hi;
};
Rect random_rect(const Cell& c, std::uint64_t h, double f_min, double f_max, double margin_m) {
  const Eigen::Vector2d room = c.size_m - Eigen::Vector2d::Constant(2 * margin_m);
  const Eigen::Vector2d f(f_min + (f_max - f_min) * hash_unit(h, 11), f_min + (f_max - f_min) * hash_unit(h, 12));
  const Eigen::Vector2d size = f.cwiseProduct(room);
  const Eigen::Vector2d slack = room - size;
  const Eigen::Vector2d lo(margin_m + slack.x() * hash_unit(h, 13), margin_m + slack.y() * hash_unit(h, 14));
  return {lo, lo + size};
}

// Ink coverage (0 or 1) of text-like content: lines of glyphs of height glyph_m, words separated by
// spaces, ragged line ends; each glyph is a random 3x5 bitmap. p_m is measured from the block's corner.
double text_ink(const Eigen::Vector2d& p_m, double glyph_m, double width_m, std::uint64_t seed) {
  const double pitch = 1.6 * glyph_m, char_w = 0.75 * glyph_m;
  const double line = std::floor(p_m.y() / pitch), y = p_m.y() - line * pitch;
  if (y > glyph_m || p_m.x() < 0 || p_m.y() < 0) return 0;
  const double line_end = width_m * (0.45 + 0.55 * hash_unit(seed, static_cast<std::int64_t>(line)));
  if (p_m.x() > line_end) return 0;
  const double ch = std::floor(p_m.x() / char_w), x = p_m.x() - ch * char_w;
  if (x > 0.8 * char_w) return 0;
  const std::uint64_t h = hash64(seed, static_cast<std::int64_t>(line), static_cast<std::int64_t>(ch));
  if (hash_unit(h, 1) < 0.18) return 0;  // a space between words
  const int gx = std::min(2, static_cast<int>(x / (0.8 * char_w) * 3));
  const int gy = std::min(4, static_cast<int>(y / glyph_m * 5));
  return ((h >> (gy * 3 + gx)) & 1u) ? 1.0 : 0.0;
}

double plain(const Sample& q, std::uint64_t seed) {
  return 0.75 * fbm(q.s.x(), q.s.y(), 4, 3, seed) + 0.25 * gradient_noise(q.s.x(), q.s.y(), 64, seed + 1);
}

// Formwork concrete: panels of slightly different tone, dark seams, tie holes, pits and speckle.
double concrete(const Sample& q, std::uint64_t seed) {
  const double x = q.s.x(), y = q.s.y();
  double p = 0.4 * fbm(x, y, 8, 5, seed) + 0.25 * lattice_noise(x, y, 512, seed + 1) +
             0.12 * lattice_noise(x, y, 1024, seed + 2);
  const Cell panel = cell_of(q.s, 4, 8);
  p += 0.35 * (hash_unit(seed + 3, panel.i, panel.j) - 0.5);
  const double seam_d = std::min({panel.local_m.x(), panel.size_m.x() - panel.local_m.x(), panel.local_m.y(),
                                  panel.size_m.y() - panel.local_m.y()});
  p -= 0.8 * coverage(seam_d - 0.002, q.texel_m);
  const Eigen::Vector2d hole(panel.size_m.x() * (hash_unit(seed + 4, panel.i) < 0.5 ? 0.25 : 0.75),
                            0.5 * panel.size_m.y());
  p -= 1.3 * coverage((panel.local_m - hole).norm() - 0.012, q.texel_m);
  const DiscHit pit = nearest_disc(x, y, 128, 0.35, 0.002 / P, 0.006 / P, seed + 5);
  p -= 0.9 * coverage(pit.signed_distance * P, q.texel_m);
  return p;
}

// A label: bright card with a line or two of small dark text.
double label(const Eigen::Vector2d& p_m, const Rect& r, std::uint64_t h, double texel_m, double under) {
  const double inside = coverage(rect_distance(p_m, r.lo, r.hi), texel_m);
  if (inside <= 0) return under;
  const double ink = text_ink(p_m - r.lo - Eigen::Vector2d(0.01, 0.01), 0.009 + 0.006 * hash_unit(h, 21),
                              r.hi.x() - r.lo.x() - 0.02, h);
  return under + inside * ((0.9 - 1.7 * ink) - under);
}

// Shelves of boxes: per shelf cell a box and often a smaller one in front, with outlines and labels.
// Nothing crosses a cell border (kClutterCellM), so cells can be shuffled without cutting a box.
double clutter(const Sample& q, std::uint64_t seed) {
  double p = -0.7 + 0.08 * fbm(q.s.x(), q.s.y(), 16, 2, seed);
  const Cell c = cell_of(q.s, 8, 6);
  for (int layer = 0; layer < 2; ++layer) {
    const std::uint64_t h = hash64(seed + 10 + layer, c.i, c.j);
    if (hash_unit(h, 1) > (layer == 0 ? 0.9 : 0.45)) continue;
    const Rect box = random_rect(c, h, layer == 0 ? 0.5 : 0.3, layer == 0 ? 1.0 : 0.6, 0.025);
    const double d = rect_distance(c.local_m, box.lo, box.hi);
    const double inside = coverage(d, q.texel_m);
    if (inside <= 0) continue;
    double tone = -0.6 + 1.5 * hash_unit(h, 2) + 0.15 * fbm(q.s.x(), q.s.y(), 32, 2, h);
    tone -= 0.35 * coverage(-d - 0.008, q.texel_m);  // darker outline along the edges
    if (hash_unit(h, 3) < 0.6) {
      Cell in_box = c;
      in_box.size_m = box.hi - box.lo;
      Rect card = random_rect(in_box, h + 1, 0.25, 0.5, 0.01);
      card.lo += box.lo;
      card.hi += box.lo;
      tone = label(c.local_m, card, h, q.texel_m, tone);
    }
    p += inside * (tone - p);
  }
  return p;
}

// Printed matter filling the whole surface (posters and signs are decals of this material): a
// layout of blocks (kPosterCells per period) with light or dark paper, each showing a title and text,
// a picture with a caption, or bold bars and a disc.
double poster(const Sample& q, std::uint64_t seed) {
  const Cell c = cell_of(q.s, 4, 6);
  const std::uint64_t h = hash64(seed + 20, c.i, c.j);
  const double paper = hash_unit(h, 1) < 0.5 ? 0.8 : -0.7;
  const double ink = -0.9 * paper / std::abs(paper);
  const double margin = 0.03;
  const Eigen::Vector2d& p = c.local_m;
  const double layout = hash_unit(h, 2);
  if (layout < 0.45) {
    const double title_h = 0.04 + 0.04 * hash_unit(h, 3);
    const double width = c.size_m.x() - 2 * margin;
    if (p.y() < margin + 1.3 * title_h)
      return paper + (ink - paper) * text_ink(p - Eigen::Vector2d(margin, margin), title_h, width, h + 1);
    const Eigen::Vector2d body = p - Eigen::Vector2d(margin, margin + 1.6 * title_h);
    return paper + (ink - paper) * text_ink(body, 0.012 + 0.012 * hash_unit(h, 4), width, h + 2);
  }
  if (layout < 0.8) {
    const Rect picture = random_rect(c, h, 0.6, 0.85, margin);
    const double d = rect_distance(p, picture.lo, picture.hi);
    if (d > 0) {
      const Eigen::Vector2d caption(picture.lo.x(), picture.hi.y() + 0.015);
      return paper + (ink - paper) * text_ink(p - caption, 0.015, picture.hi.x() - picture.lo.x(), h + 3);
    }
    return 0.95 * fbm(q.s.x(), q.s.y(), 32, 4, h + 4);
  }
  // Bold bars across the block and a disc (logos, signs).
  const int bar = static_cast<int>(p.y() / c.size_m.y() * 5);
  const double v = hash_unit(h, 10 + bar) < 0.5 ? paper : ink;
  const Eigen::Vector2d centre(c.size_m.x() * (0.25 + 0.5 * hash_unit(h, 5)), 0.5 * c.size_m.y());
  const double disc = coverage((p - centre).norm() - 0.12 - 0.1 * hash_unit(h, 6), q.texel_m);
  return v + disc * ((v == paper ? ink : paper) - v);
}

// Foliage: three layers of leaves of random tone over dark gaps, front layers on top.
double foliage(const Sample& q, std::uint64_t seed) {
  double p = -1.0 + 0.3 * fbm(q.s.x(), q.s.y(), 32, 2, seed);
  const int cells[3] = {16, 32, 64};
  for (int layer = 0; layer < 3; ++layer) {
    const DiscHit leaf = nearest_disc(q.s.x(), q.s.y(), cells[layer], 0.85, 0.3 / cells[layer],
                                      0.55 / cells[layer], seed + 30 + layer);
    const double c = coverage(leaf.signed_distance * P, q.texel_m);
    const double tone = -0.5 + 1.3 * hash_unit(leaf.id, 7) + 0.1 * layer;
    p += c * (tone - p);
  }
  return p;
}

// Ground: patches, fine grain, stones and thin cracks.
double ground(const Sample& q, std::uint64_t seed) {
  const double x = q.s.x(), y = q.s.y();
  double p = 0.35 * fbm(x, y, 2, 3, seed) + 0.3 * lattice_noise(x, y, 1024, seed + 1) +
             0.2 * lattice_noise(x, y, 256, seed + 2);
  const DiscHit stone = nearest_disc(x, y, 128, 0.5, 0.003 / P, 0.008 / P, seed + 3);
  p += coverage(stone.signed_distance * P, q.texel_m) * ((1.6 * hash_unit(stone.id, 7) - 0.8) - p);
  const double ridge = std::abs(gradient_noise(x, y, 6, seed + 4)) * P / 6;  // ~ metres to the crack line
  if (fbm(x, y, 4, 2, seed + 5) > 0.15) p -= 0.9 * coverage(ridge - 0.0015, q.texel_m);
  return p;
}

double pattern(const Material& m, const Sample& q) {
  switch (m.kind) {
    case Material::Kind::kPlain: return plain(q, m.seed);
    case Material::Kind::kConcrete: return concrete(q, m.seed);
    case Material::Kind::kClutter: return clutter(q, m.seed);
    case Material::Kind::kPoster: return poster(q, m.seed);
    case Material::Kind::kFoliage: return foliage(q, m.seed);
    case Material::Kind::kGround: return ground(q, m.seed);
  }
  return 0;
}

// Amplitude of the macro variation per unit of material contrast.
double macro_factor(Material::Kind kind) {
  switch (kind) {
    case Material::Kind::kPlain: return 1.0;
    case Material::Kind::kPoster: return 0.1;
    case Material::Kind::kClutter: return 0.2;
    default: return 0.5;
  }
}

}  // namespace

ShuffleCell shuffle_cell(Material::Kind kind) {
  switch (kind) {
    case Material::Kind::kPlain: return {1, 1, 0.0};
    case Material::Kind::kConcrete: return {4, 4, 0.04};   // two formwork panels per cell
    case Material::Kind::kClutter: return {4, 3, 0.04};    // 2 x 2 shelf cells
    case Material::Kind::kPoster: return {4, 6, 0.01};     // one layout block
    case Material::Kind::kFoliage: return {4, 4, 0.12};
    case Material::Kind::kGround: return {4, 4, 0.3};
  }
  return {};
}

float texture_albedo(const Material& material, const Eigen::Vector2d& uv_m, double texel_m) {
  const Eigen::Vector2d s(uv_m.x() / P - std::floor(uv_m.x() / P), uv_m.y() / P - std::floor(uv_m.y() / P));
  const double p = pattern(material, Sample{s, std::max(texel_m, 1e-4)});
  return static_cast<float>(std::clamp(material.base_grey + material.contrast * p, 0.0, 1.0));
}

float texture_macro_gain(const Material& material, const Eigen::Vector2d& uv_m) {
  const Eigen::Vector2d s = uv_m / kMacroPeriodM;
  const double a = std::min(0.2, macro_factor(material.kind) * material.contrast);
  return static_cast<float>(1.0 + a * fbm(s.x(), s.y(), 4, 3, material.seed + 99));
}

}  // namespace vilslam::sim
