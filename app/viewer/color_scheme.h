#pragma once
// GL-free: the viewer's colours that carry meaning -- the colour map of depths, triangle
// counts and the heat map, and the hit / miss pair of triangle tests -- with choices that stay
// readable under colour-vision deficiency. The defaults are the safe ones: viridis (perceptually
// uniform, readable in greyscale and by deuteranopes and protanopes) and a blue / orange pair
// for hit / miss (red / green is the pair most often confused). The module owns the current
// choice; every tool reads it here, so one switch recolours nodes, heat map, tree and text.
#include <array>
#include <string>

#include <glm/glm.hpp>

namespace viz {

enum class Colormap { Viridis, Cividis, Turbo };

struct ColorScheme {
  Colormap map = Colormap::Viridis;
  bool cvd_safe_hits = true;  ///< hit / miss in blue / orange; false: green / red
};

/// The current scheme and the setter (the Display section, `colors` in scripts).
const ColorScheme& color_scheme();
void set_color_scheme(const ColorScheme& scheme);

/// The colour map at t in [0, 1] (clamped).
glm::vec3 colormap(Colormap map, float t);
/// The current scheme's colour map.
inline glm::vec3 colormap(float t) { return colormap(color_scheme().map, t); }
/// "viridis", "cividis", "turbo".
const char* colormap_name(Colormap map);
/// Parses a name; false (and `out` unchanged) if unknown.
bool parse_colormap(const std::string& name, Colormap* out);

/// Evenly spaced samples of the map (t = i / (kColormapSamples - 1)): the shaders interpolate
/// them, so the GPU's colours are the CPU's.
inline constexpr int kColormapSamples = 17;
std::array<glm::vec3, kColormapSamples> colormap_samples(Colormap map);

/// The difference view's diverging map: t = 0 blue (the first structure costs less), 0.5
/// near white (the same), 1 orange (it costs more); blue / orange stays apart for
/// colour-blind viewers.
glm::vec3 diverging(float t);
std::array<glm::vec3, kColormapSamples> diverging_samples();

/// A triangle test that hits / misses, in the current scheme.
glm::vec3 hit_rgb();
glm::vec3 miss_rgb();

/// The "turbo" map (Mikhailov 2019), polynomial fit; not CVD-safe, kept for its contrast.
glm::vec3 turbo(float t);

}  // namespace viz
