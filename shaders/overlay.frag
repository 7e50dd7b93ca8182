#version 330 core
// The cost image (one float per traced ray) through the current colour map.
in vec2 v_uv;

uniform sampler2D u_values;
uniform float u_scale_min;  // value at the bottom of the colour map (values below saturate)
uniform float u_scale_max;  // value at the top of the colour map (values above saturate)
uniform float u_alpha;

out vec4 frag_color;

// The current colour map (viz::colormap), as kColormapSamples samples set by the renderer
// and interpolated linearly, so the GPU shows the CPU's colours.
uniform vec3 u_palette[17];
vec3 palette(float x) {
  float f = clamp(x, 0.0, 1.0) * 16.0;
  int i = min(int(f), 15);
  return mix(u_palette[i], u_palette[i + 1], f - float(i));
}

void main() {
  // The image's first row is its top; texture row 0 is at v = 0 (the bottom).
  float value = texture(u_values, vec2(v_uv.x, 1.0 - v_uv.y)).r;
  frag_color = vec4(palette((value - u_scale_min) / max(u_scale_max - u_scale_min, 1e-6)), u_alpha);
}
