#version 330 core
// Structure nodes, instanced: one unit shape (cube edges, three circles, a square, or in 2D
// one circle in z = 0) per node, placed by per-instance attributes. The depth / leaf filter
// runs here, so changing it uploads nothing: a filtered-out instance collapses to a point
// outside the clip volume, which the rasteriser discards.
layout(location = 0) in vec3 a_unit;   // unit shape vertex
layout(location = 2) in vec3 a_lo;     // box min, sphere / circle centre, or plane rectangle min
layout(location = 3) in vec3 a_hi;     // box max, (radius, radius, radius), or plane max
layout(location = 4) in vec4 a_info;   // depth, leaf (0/1), triangle count, split axis

uniform mat4 u_view;
uniform mat4 u_projection;
uniform int u_shape;        // 0 box, 1 sphere, 2 split plane, 3 circle (a sphere in 2D)
uniform int u_color_mode;   // 0 by depth, 1 by triangle count, 2 flat
uniform float u_depth_min;
uniform float u_depth_max;
uniform int u_leaves_only;
uniform int u_hide_empty;
uniform float u_max_depth;
uniform float u_max_prims;
uniform vec4 u_flat_color;
uniform float u_alpha;
uniform float u_depth_bias;

out vec4 v_color;

// The current colour map (viz::colormap), as kColormapSamples samples set by the renderer
// and interpolated linearly, so the GPU shows the CPU's colours.
uniform vec3 u_palette[17];
vec3 palette(float x) {
  float f = clamp(x, 0.0, 1.0) * 16.0;
  int i = min(int(f), 15);
  return mix(u_palette[i], u_palette[i + 1], f - float(i));
}

void main() {
  float depth = a_info.x;
  bool leaf = a_info.y > 0.5;
  float prims = a_info.z;
  bool hidden = depth < u_depth_min - 0.5 || depth > u_depth_max + 0.5 || (u_leaves_only == 1 && !leaf) ||
                (u_hide_empty == 1 && leaf && prims < 0.5);
  if (hidden) {
    v_color = vec4(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  vec3 p;
  if (u_shape == 1 || u_shape == 3) {
    p = a_lo + a_hi.x * a_unit;
  } else if (u_shape == 2) {
    int axis = int(a_info.w + 0.5);
    int u = (axis + 1) % 3;
    int v = (axis + 2) % 3;
    p = a_lo;
    p[u] = mix(a_lo[u], a_hi[u], a_unit.x);
    p[v] = mix(a_lo[v], a_hi[v], a_unit.y);
  } else {
    p = mix(a_lo, a_hi, a_unit);
  }

  vec3 rgb;
  if (u_color_mode == 0) {
    // Skip the map's darkest end: it vanishes on the dark background.
    rgb = palette(0.12 + 0.86 * depth / u_max_depth);
  } else if (u_color_mode == 1) {
    rgb = prims < 0.5 ? vec3(0.42, 0.45, 0.52) : palette(0.15 + 0.85 * log(1.0 + prims) / log(1.0 + u_max_prims));
  } else {
    rgb = u_flat_color.rgb;
  }
  v_color = vec4(rgb, u_alpha * (u_color_mode == 2 ? u_flat_color.a : 1.0));
  gl_Position = u_projection * u_view * vec4(p, 1.0);
  gl_Position.z -= u_depth_bias * gl_Position.w;
}
