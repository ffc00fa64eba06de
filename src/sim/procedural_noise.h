#pragma once
// Building blocks of the procedural textures: a counter-based hash and periodic noise on the unit
// square (every function here is periodic with period 1 in x and y, so a texture tile wraps seamlessly).
#include <cstdint>

namespace vilslam::sim {

// Counter-based 64-bit hash (splitmix64 finalizer applied to a mix of the inputs).
std::uint64_t hash64(std::uint64_t seed, std::int64_t a, std::int64_t b = 0, std::int64_t c = 0);
// Uniform in [0, 1) from a hash.
double hash_unit(std::uint64_t seed, std::int64_t a, std::int64_t b = 0, std::int64_t c = 0);

// Periodic gradient (Perlin) noise with `cells` lattice cells per unit; values about in [-1, 1].
double gradient_noise(double x, double y, int cells, std::uint64_t seed);
// Fractal sum of `octaves` gradient noises, cells doubling and amplitude halving per octave,
// normalized to about [-1, 1].
double fbm(double x, double y, int cells, int octaves, std::uint64_t seed);
// Bilinearly interpolated white noise on a `cells` lattice (fine grain, speckle), in [-1, 1].
double lattice_noise(double x, double y, int cells, std::uint64_t seed);

// Soft step 0 -> 1 as d goes from +w/2 to -w/2 (coverage of a region whose signed distance is d).
double coverage(double signed_distance, double width);

// Nearest of the random discs thrown into a cells x cells grid (one per cell with probability
// `density`, radius r_min..r_max in unit-square units): its signed distance and its hash id.
struct DiscHit {
  double signed_distance = 1e9;  // < 0 inside the disc
  std::uint64_t id = 0;
};
DiscHit nearest_disc(double x, double y, int cells, double density, double r_min, double r_max,
                     std::uint64_t seed);

}  // namespace vilslam::sim
