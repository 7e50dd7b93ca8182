#version 330 core
// The cost image (one float per traced ray) through the turbo colour map.
in vec2 v_uv;

uniform sampler2D u_values;
uniform float u_scale_max;  // value at the top of the colour map (values above saturate)
uniform float u_alpha;

out vec4 frag_color;

// Same polynomial as nodes.vert and viz::turbo().
vec3 turbo(float x) {
  x = clamp(x, 0.0, 1.0);
  float x2 = x * x, x3 = x2 * x, x4 = x2 * x2, x5 = x4 * x;
  return clamp(vec3(
      0.13572138 + 4.61539260 * x - 42.66032258 * x2 + 132.13108234 * x3 - 152.94239396 * x4 + 59.28637943 * x5,
      0.09140261 + 2.19418839 * x + 4.84296658 * x2 - 14.18503333 * x3 + 4.27729857 * x4 + 2.82956604 * x5,
      0.10667330 + 12.64194608 * x - 60.58204836 * x2 + 110.36276771 * x3 - 89.90310912 * x4 + 27.34824973 * x5),
      0.0, 1.0);
}

void main() {
  // The image's first row is its top; texture row 0 is at v = 0 (the bottom).
  float value = texture(u_values, vec2(v_uv.x, 1.0 - v_uv.y)).r;
  frag_color = vec4(turbo(value / u_scale_max), u_alpha);
}
