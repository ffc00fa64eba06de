// Procedural textures and their mip tiles: contrast per material, determinism, periodicity, filtering.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sim/material_textures.h"
#include "sim/mip_tile.h"
#include "sim/texture.h"

namespace vilslam::sim {
namespace {

using Kind = Material::Kind;

// Standard deviation of the albedo sampled every 1 cm over one texture period.
double albedo_std(const Material& m) {
  double sum = 0, sum2 = 0;
  int n = 0;
  for (double v = 0; v < kTexturePeriodM; v += 0.01) {
    for (double u = 0; u < kTexturePeriodM; u += 0.03) {
      const double a = texture_albedo(m, {u, v}, 0.004);
      sum += a;
      sum2 += a * a;
      ++n;
    }
  }
  const double mean = sum / n;
  return std::sqrt(sum2 / n - mean * mean);
}

TEST(Texture, ContrastFollowsMaterialAndKind) {
  const double plain = albedo_std({Kind::kPlain, 0.7f, 0.03f, 1});
  EXPECT_LT(plain, 0.02) << "plain walls must be nearly uniform";
  for (Kind kind : {Kind::kConcrete, Kind::kClutter, Kind::kPoster, Kind::kFoliage, Kind::kGround}) {
    const double low = albedo_std({kind, 0.5f, 0.1f, 3});
    const double high = albedo_std({kind, 0.5f, 0.2f, 3});
    SCOPED_TRACE(static_cast<int>(kind));
    EXPECT_NEAR(high / low, 2.0, 0.15) << "texture amplitude must scale with Material::contrast";
    EXPECT_GT(albedo_std({kind, 0.5f, 0.3f, 3}), 5 * plain);
  }
}

TEST(Texture, PlainWallHasNoSharpGradients) {
  const Material plain{Kind::kPlain, 0.7f, 0.03f, 5};
  const Material concrete{Kind::kConcrete, 0.5f, 0.25f, 5};
  double max_plain = 0, max_concrete = 0;
  for (double v = 0; v < 2; v += 0.005) {
    for (double u = 0; u < 2; u += 0.005) {
      auto step = [&](const Material& m) {
        return std::abs(double(texture_albedo(m, {u + 0.005, v}, 0.005)) - texture_albedo(m, {u, v}, 0.005));
      };
      max_plain = std::max(max_plain, step(plain));
      max_concrete = std::max(max_concrete, step(concrete));
    }
  }
  EXPECT_LT(max_plain * 255, 2.0) << "a 5 mm step on a plain wall changes less than 2 grey levels";
  EXPECT_GT(max_concrete * 255, 40.0) << "concrete has seams, holes and pits";
}

TEST(Texture, DeterministicAndPeriodic) {
  for (int k = 0; k < 6; ++k) {
    const Material m{static_cast<Kind>(k), 0.5f, 0.3f, 42};
    for (int i = 0; i < 200; ++i) {
      const Eigen::Vector2d uv(0.0137 * i - 1.3, 0.0291 * i + 0.4);
      const float a = texture_albedo(m, uv, 0.004);
      EXPECT_EQ(a, texture_albedo(m, uv, 0.004));
      EXPECT_NEAR(a, texture_albedo(m, uv + Eigen::Vector2d(kTexturePeriodM, -2 * kTexturePeriodM), 0.004), 1e-5);
    }
    EXPECT_NE(texture_albedo(m, {0.3, 0.7}, 0.004) + texture_albedo(m, {1.1, 2.3}, 0.004),
              texture_albedo({m.kind, 0.5f, 0.3f, 43}, {0.3, 0.7}, 0.004) +
                  texture_albedo({m.kind, 0.5f, 0.3f, 43}, {1.1, 2.3}, 0.004))
        << "the seed changes the content";
  }
}

TEST(MipTile, PyramidKeepsMeanAndFiltersDetail) {
  const Material m{Kind::kConcrete, 0.5f, 0.3f, 9};
  const MipTile tile(256, kTexturePeriodM, [&m](double u, double v, double t) { return texture_albedo(m, {u, v}, t); });
  ASSERT_EQ(tile.num_levels(), 9);
  double mean0 = 0;
  for (float a : tile.level(0)) mean0 += a;
  mean0 /= tile.level(0).size();
  EXPECT_NEAR(tile.level(8)[0], mean0, 1e-5);
  // Texel centres return the stored value; a footprint of the whole tile returns the mean.
  const double texel = kTexturePeriodM / 256;
  EXPECT_FLOAT_EQ(tile.sample(10.5 * texel, 3.5 * texel, 0.0), tile.level(0)[3 * 256 + 10]);
  EXPECT_NEAR(tile.sample(1.234, 0.567, kTexturePeriodM), mean0, 1e-5);
  // Larger footprints give smoother lookups (less aliasing).
  auto spread = [&](double footprint) {
    double s = 0, s2 = 0;
    for (int i = 0; i < 500; ++i) {
      const double a = tile.sample(0.173 * i, 0.311 * i, footprint);
      s += a;
      s2 += a * a;
    }
    return std::sqrt(s2 / 500 - (s / 500) * (s / 500));
  };
  EXPECT_LT(spread(0.5), 0.5 * spread(0.01));
}

TEST(MaterialTextures, ShuffledCellsBreakPeriodicityDeterministically) {
  const std::vector<Material> materials{{Kind::kConcrete, 0.5f, 0.3f, 1}, {Kind::kPoster, 0.6f, 0.4f, 2}};
  const TextureOptions small{256, 64};
  const MaterialTextures a(materials, small), b(materials, small);
  int differs = 0;
  for (int i = 0; i < 400; ++i) {
    const Eigen::Vector2d uv(0.0371 * i, 0.0173 * i + 0.2);
    for (int m = 0; m < 2; ++m) {
      EXPECT_EQ(a.albedo(m, uv, 0.01), b.albedo(m, uv, 0.01));
      differs += std::abs(a.albedo(m, uv, 0.01) - a.albedo(m, uv + Eigen::Vector2d(kTexturePeriodM, 0), 0.01)) > 0.02;
    }
  }
  EXPECT_GT(differs, 200) << "one texture period further the content must differ";
  EXPECT_EQ(material_textures(materials).get(), material_textures(materials).get()) << "built once";
}

}  // namespace
}  // namespace vilslam::sim
