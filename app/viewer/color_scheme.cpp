#include "color_scheme.h"

#include <algorithm>
#include <cmath>

namespace viz {
namespace {

ColorScheme g_scheme;

glm::vec3 hex(unsigned rgb) {
  return glm::vec3(static_cast<float>((rgb >> 16) & 255u), static_cast<float>((rgb >> 8) & 255u),
                   static_cast<float>(rgb & 255u)) /
         255.0f;
}

// Nine evenly spaced stops of matplotlib's viridis (van der Walt & Smith 2015) and cividis
// (Nuñez, Anderton & Renslow 2018), interpolated linearly between.
constexpr unsigned kViridis[9] = {0x440154, 0x472D7B, 0x3B528B, 0x2C728E, 0x21918C,
                                  0x28AE80, 0x5EC962, 0xADDC30, 0xFDE725};
constexpr unsigned kCividis[9] = {0x00224E, 0x123570, 0x3B496C, 0x575D6D, 0x707173,
                                  0x8A8779, 0xA59C74, 0xC3B369, 0xFEE838};

glm::vec3 from_stops(const unsigned (&stops)[9], float t) {
  const float f = std::clamp(t, 0.0f, 1.0f) * 8.0f;
  const int i = std::min(static_cast<int>(f), 7);
  return glm::mix(hex(stops[i]), hex(stops[i + 1]), f - static_cast<float>(i));
}

}  // namespace

const ColorScheme& color_scheme() { return g_scheme; }
void set_color_scheme(const ColorScheme& scheme) { g_scheme = scheme; }

glm::vec3 turbo(float t) {
  const float x = std::clamp(t, 0.0f, 1.0f);
  const float x2 = x * x, x3 = x2 * x, x4 = x2 * x2, x5 = x4 * x;
  const float r = 0.13572138f + 4.61539260f * x - 42.66032258f * x2 + 132.13108234f * x3 - 152.94239396f * x4 +
                  59.28637943f * x5;
  const float g = 0.09140261f + 2.19418839f * x + 4.84296658f * x2 - 14.18503333f * x3 + 4.27729857f * x4 +
                  2.82956604f * x5;
  const float b = 0.10667330f + 12.64194608f * x - 60.58204836f * x2 + 110.36276771f * x3 - 89.90310912f * x4 +
                  27.34824973f * x5;
  return glm::clamp(glm::vec3(r, g, b), glm::vec3(0.0f), glm::vec3(1.0f));
}

glm::vec3 colormap(Colormap map, float t) {
  switch (map) {
    case Colormap::Viridis: return from_stops(kViridis, t);
    case Colormap::Cividis: return from_stops(kCividis, t);
    case Colormap::Turbo: return turbo(t);
  }
  return turbo(t);
}

const char* colormap_name(Colormap map) {
  switch (map) {
    case Colormap::Viridis: return "viridis";
    case Colormap::Cividis: return "cividis";
    case Colormap::Turbo: return "turbo";
  }
  return "?";
}

bool parse_colormap(const std::string& name, Colormap* out) {
  for (Colormap m : {Colormap::Viridis, Colormap::Cividis, Colormap::Turbo}) {
    if (name == colormap_name(m)) {
      *out = m;
      return true;
    }
  }
  return false;
}

std::array<glm::vec3, kColormapSamples> colormap_samples(Colormap map) {
  std::array<glm::vec3, kColormapSamples> s;
  for (int i = 0; i < kColormapSamples; ++i) s[i] = colormap(map, static_cast<float>(i) / (kColormapSamples - 1));
  return s;
}

glm::vec3 diverging(float t) {
  // Blue (Okabe & Ito's) through a light grey to orange, lightness falling off to both ends.
  const glm::vec3 blue(0.0f, 0.45f, 0.70f), mid(0.93f, 0.93f, 0.90f), orange(0.90f, 0.55f, 0.0f);
  const float x = std::clamp(t, 0.0f, 1.0f);
  return x < 0.5f ? glm::mix(blue, mid, x * 2.0f) : glm::mix(mid, orange, (x - 0.5f) * 2.0f);
}

std::array<glm::vec3, kColormapSamples> diverging_samples() {
  std::array<glm::vec3, kColormapSamples> s;
  for (int i = 0; i < kColormapSamples; ++i) s[i] = diverging(static_cast<float>(i) / (kColormapSamples - 1));
  return s;
}

// Okabe & Ito's colour-blind-safe blue and orange (lightened for a dark background), or the
// classic green / red.
glm::vec3 hit_rgb() { return g_scheme.cvd_safe_hits ? glm::vec3(0.34f, 0.70f, 0.95f) : glm::vec3(0.30f, 0.95f, 0.40f); }
glm::vec3 miss_rgb() { return g_scheme.cvd_safe_hits ? glm::vec3(0.95f, 0.62f, 0.05f) : glm::vec3(1.0f, 0.35f, 0.38f); }

}  // namespace viz
