#version 330 core
// Thick line segments: each instance is a quad around the segment's screen-space image,
// a_width pixels wide (core-profile GL has no wide lines). The segment is clipped to the
// near plane first, so a ray starting at the camera still draws.
layout(location = 0) in vec2 a_corner;  // x: 0 = end a, 1 = end b; y: side -1 / +1
layout(location = 2) in vec3 a_a;
layout(location = 3) in vec3 a_b;
layout(location = 4) in vec4 a_color;
layout(location = 5) in float a_width;  // pixels

uniform mat4 u_view;
uniform mat4 u_projection;
uniform vec2 u_viewport;
uniform float u_depth_bias;

out vec4 v_color;

void main() {
  mat4 vp = u_projection * u_view;
  vec4 ca = vp * vec4(a_a, 1.0);
  vec4 cb = vp * vec4(a_b, 1.0);
  // Near plane in clip space: z >= -w.
  float da = ca.z + ca.w;
  float db = cb.z + cb.w;
  if (da < 0.0 && db < 0.0) {
    v_color = vec4(0.0);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    return;
  }
  if (da < 0.0) ca = mix(ca, cb, da / (da - db));
  if (db < 0.0) cb = mix(cb, ca, db / (db - da));
  vec2 half_viewport = 0.5 * u_viewport;
  vec2 sa = ca.xy / ca.w * half_viewport;
  vec2 sb = cb.xy / cb.w * half_viewport;
  vec2 dir = sb - sa;
  float len = length(dir);
  dir = len > 1e-6 ? dir / len : vec2(1.0, 0.0);
  vec2 normal = vec2(-dir.y, dir.x);
  bool at_b = a_corner.x > 0.5;
  vec4 c = at_b ? cb : ca;
  // Square caps (half a width past each end) so box edges meet without notches.
  vec2 offset = normal * a_corner.y * 0.5 * a_width + dir * (at_b ? 0.5 : -0.5) * a_width;
  c.xy += offset / half_viewport * c.w;
  c.z -= u_depth_bias * c.w;
  v_color = a_color;
  gl_Position = c;
}
