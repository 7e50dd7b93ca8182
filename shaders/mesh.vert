#version 330 core
// Scene triangles and highlighted triangles. The fragment shader derives the face normal
// from the world-space position, so no normals are stored per vertex.
layout(location = 0) in vec3 a_position;
// Per-vertex colour for highlight batches. The scene mesh leaves this attribute array
// disabled and the renderer sets the constant value instead (glVertexAttrib4f).
layout(location = 1) in vec4 a_color;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_world_position;
out vec4 v_color;

void main() {
  v_world_position = a_position;
  v_color = a_color;
  gl_Position = u_projection * u_view * vec4(a_position, 1.0);
}
