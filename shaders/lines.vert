#version 330 core
// Thin coloured line segments in world space (the scene's bounds, highlighted nodes): plain
// vertex lists with a colour. Structure nodes use nodes.vert, thick lines segments.vert.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec4 a_color;

uniform mat4 u_view;
uniform mat4 u_projection;
// Pulls lines towards the camera by this fraction of clip-space w, so a box edge lying on
// a mesh face is not lost in z-fighting. 0 disables it.
uniform float u_depth_bias;

out vec4 v_color;

void main() {
  v_color = a_color;
  gl_Position = u_projection * u_view * vec4(a_position, 1.0);
  gl_Position.z -= u_depth_bias * gl_Position.w;
}
