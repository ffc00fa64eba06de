#include "sim/procedural_noise.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace vilslam::sim {
namespace {

std::uint64_t splitmix(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

int wrap(std::int64_t i, int n) {
  if ((n & (n - 1)) == 0) return static_cast<int>(i & (n - 1));
  return static_cast<int>(((i % n) + n) % n);
}

// Quintic fade 6t^5 - 15t^4 + 10t^3 (Perlin, "Improving Noise", 2002).
double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }

double lerp(double a, double b, double t) { return a + (b - a) * t; }

// Dot product of the corner's gradient (one of 16 unit directions, picked by a hash) with (dx, dy);
// (i, j) are lattice indices already wrapped into the period.
double corner_gradient(int i, int j, std::uint64_t seed, double dx, double dy) {
  static const auto directions = [] {
    std::array<std::array<double, 2>, 16> d{};
    for (int k = 0; k < 16; ++k) d[k] = {std::cos(2 * M_PI * (k + 0.5) / 16), std::sin(2 * M_PI * (k + 0.5) / 16)};
    return d;
  }();
  const auto& g = directions[hash64(seed, i, j) >> 60];
  return g[0] * dx + g[1] * dy;
}

// The lattice cell of x * cells: wrapped indices of its two corners per axis and the fraction.
struct LatticeCell {
  int i0, i1, j0, j1;
  double dx, dy;
};
LatticeCell lattice_cell(double x, double y, int cells) {
  const double X = x * cells, Y = y * cells;
  const double fx = std::floor(X), fy = std::floor(Y);
  const int i0 = wrap(static_cast<std::int64_t>(fx), cells), j0 = wrap(static_cast<std::int64_t>(fy), cells);
  return {i0, i0 + 1 == cells ? 0 : i0 + 1, j0, j0 + 1 == cells ? 0 : j0 + 1, X - fx, Y - fy};
}

}  // namespace

std::uint64_t hash64(std::uint64_t seed, std::int64_t a, std::int64_t b, std::int64_t c) {
  // Inputs spread by distinct odd multipliers, then the splitmix64 finalizer.
  const std::uint64_t h = seed * 0xD6E8FEB86659FD93ull ^ static_cast<std::uint64_t>(a) * 0x9E3779B97F4A7C15ull ^
                          static_cast<std::uint64_t>(b) * 0xC2B2AE3D27D4EB4Full ^
                          static_cast<std::uint64_t>(c) * 0x165667B19E3779F9ull;
  return splitmix(h);
}

double hash_unit(std::uint64_t seed, std::int64_t a, std::int64_t b, std::int64_t c) {
  return static_cast<double>(hash64(seed, a, b, c) >> 11) * 0x1.0p-53;
}

double gradient_noise(double x, double y, int cells, std::uint64_t seed) {
  const LatticeCell c = lattice_cell(x, y, cells);
  const double n00 = corner_gradient(c.i0, c.j0, seed, c.dx, c.dy);
  const double n10 = corner_gradient(c.i1, c.j0, seed, c.dx - 1, c.dy);
  const double n01 = corner_gradient(c.i0, c.j1, seed, c.dx, c.dy - 1);
  const double n11 = corner_gradient(c.i1, c.j1, seed, c.dx - 1, c.dy - 1);
  const double u = fade(c.dx), v = fade(c.dy);
  // 2D gradient noise spans about [-0.7, 0.7]; scale to about [-1, 1].
  return 1.4 * lerp(lerp(n00, n10, u), lerp(n01, n11, u), v);
}

double fbm(double x, double y, int cells, int octaves, std::uint64_t seed) {
  double sum = 0, amplitude = 1, norm = 0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * gradient_noise(x, y, cells << o, seed + 7919 * o);
    norm += amplitude;
    amplitude *= 0.5;
  }
  return sum / norm;
}

double lattice_noise(double x, double y, int cells, std::uint64_t seed) {
  const LatticeCell c = lattice_cell(x, y, cells);
  auto value = [seed](int i, int j) { return 2 * hash_unit(seed, i, j) - 1; };
  return lerp(lerp(value(c.i0, c.j0), value(c.i1, c.j0), c.dx), lerp(value(c.i0, c.j1), value(c.i1, c.j1), c.dx), c.dy);
}

double coverage(double signed_distance, double width) {
  const double t = std::clamp(0.5 - signed_distance / width, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

DiscHit nearest_disc(double x, double y, int cells, double density, double r_min, double r_max,
                     std::uint64_t seed) {
  const double X = x * cells, Y = y * cells;
  const auto ix = static_cast<std::int64_t>(std::floor(X)), iy = static_cast<std::int64_t>(std::floor(Y));
  // One hash per cell, split into four 16-bit uniforms: presence, centre x, centre y, radius.
  auto unit16 = [](std::uint64_t h, int k) { return static_cast<double>((h >> (16 * k)) & 0xFFFF) / 65536.0; };
  DiscHit best;
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      const std::uint64_t h = hash64(seed, wrap(ix + di, cells), wrap(iy + dj, cells));
      if (unit16(h, 0) >= density) continue;
      const double cx = ix + di + unit16(h, 1), cy = iy + dj + unit16(h, 2);
      const double radius = (r_min + (r_max - r_min) * unit16(h, 3)) * cells;
      const double d = (std::sqrt((X - cx) * (X - cx) + (Y - cy) * (Y - cy)) - radius) / cells;
      if (d < best.signed_distance) best = {d, h};
    }
  }
  return best;
}

}  // namespace vilslam::sim
