#version 330 core
// Flat shading without stored normals: the screen-space derivatives of the position span
// the triangle's plane, so their cross product is the face normal. That costs no memory
// per vertex and suits triangle soups, whose winding is arbitrary.
in vec3 v_world_position;
in vec4 v_color;

uniform vec3 u_eye;   // camera position in world space
// Multiplies the vertex colour: the mesh's base colour, or a fade for highlights.
uniform vec4 u_tint;

out vec4 frag_color;

void main() {
  vec3 normal = normalize(cross(dFdx(v_world_position), dFdy(v_world_position)));
  vec3 to_eye = normalize(u_eye - v_world_position);
  // Two-sided lighting: always light the side facing the viewer.
  if (dot(normal, to_eye) < 0.0) normal = -normal;

  // A fixed "sun" (high, from +X+Z) separates faces by orientation, as on a physical
  // model; a headlight keeps whatever the camera sees lit; a sky term on world up
  // lifts faces turned away from both, so nothing goes black on a projector.
  const vec3 sun_dir = normalize(vec3(0.45, 0.85, 0.3));
  float sun = max(dot(normal, sun_dir), 0.0);
  float headlight = max(dot(normal, to_eye), 0.0);
  float sky = 0.5 + 0.5 * normal.y;
  float light = 0.10 + 0.16 * sky + 0.46 * sun + 0.32 * headlight;

  vec4 base = v_color * u_tint;
  frag_color = vec4(base.rgb * light, base.a);
}
