// The colour scheme: the safe maps rise in lightness from end to end (so they read in
// greyscale and without red-green discrimination), the shaders' samples are the CPU's map,
// names parse, and the hit / miss pair is told apart by lightness and blue-yellow, not by
// red-green alone.
#include <gtest/gtest.h>

#include <cmath>

#include "color_scheme.h"

namespace viz {
namespace {

/// Relative luminance (Rec. 709 weights on the sRGB values, enough for an ordering).
float luma(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

TEST(ColorScheme, SafeMapsRiseInLightnessFromEndToEnd) {
  for (Colormap m : {Colormap::Viridis, Colormap::Cividis}) {
    SCOPED_TRACE(colormap_name(m));
    float last = -1.0f;
    for (int i = 0; i <= 64; ++i) {
      const float l = luma(colormap(m, static_cast<float>(i) / 64.0f));
      EXPECT_GT(l, last) << "t = " << i / 64.0;
      last = l;
    }
    EXPECT_GT(luma(colormap(m, 1.0f)) - luma(colormap(m, 0.0f)), 0.6f) << "dark to light";
  }
  // Turbo is not monotonic: why it is not the default.
  const float mid = luma(turbo(0.55f)), top = luma(turbo(1.0f));
  EXPECT_GT(mid, top);
}

TEST(ColorScheme, ShaderSamplesAreTheMapAndDefaultsAreSafe) {
  const ColorScheme defaults;
  EXPECT_EQ(defaults.map, Colormap::Viridis);
  EXPECT_TRUE(defaults.cvd_safe_hits);
  for (Colormap m : {Colormap::Viridis, Colormap::Cividis, Colormap::Turbo}) {
    const auto s = colormap_samples(m);
    for (int i = 0; i < kColormapSamples; ++i) {
      const glm::vec3 c = colormap(m, static_cast<float>(i) / (kColormapSamples - 1));
      EXPECT_EQ(s[i], c);
    }
    Colormap parsed = Colormap::Turbo;
    EXPECT_TRUE(parse_colormap(colormap_name(m), &parsed));
    EXPECT_EQ(parsed, m);
  }
  Colormap unchanged = Colormap::Cividis;
  EXPECT_FALSE(parse_colormap("jet", &unchanged));
  EXPECT_EQ(unchanged, Colormap::Cividis);
  // Clamped outside [0, 1].
  EXPECT_EQ(colormap(Colormap::Viridis, -1.0f), colormap(Colormap::Viridis, 0.0f));
  EXPECT_EQ(colormap(Colormap::Viridis, 2.0f), colormap(Colormap::Viridis, 1.0f));
}

TEST(ColorScheme, HitMissPairDiffersOnTheBlueYellowAxis) {
  const ColorScheme saved = color_scheme();
  set_color_scheme(ColorScheme{});
  const glm::vec3 hit = hit_rgb(), miss = miss_rgb();
  // Blue against orange: what deuteranopes and protanopes still see (red-green is lost).
  const float by_hit = hit.b - 0.5f * (hit.r + hit.g), by_miss = miss.b - 0.5f * (miss.r + miss.g);
  EXPECT_GT(by_hit - by_miss, 0.5f);
  ColorScheme classic;
  classic.cvd_safe_hits = false;
  set_color_scheme(classic);
  EXPECT_GT(hit_rgb().g, hit_rgb().r) << "green";
  EXPECT_GT(miss_rgb().r, miss_rgb().g) << "red";
  set_color_scheme(saved);
}

}  // namespace
}  // namespace viz
