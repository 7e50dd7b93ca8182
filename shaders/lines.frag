#version 330 core
// Shared by lines.vert, nodes.vert and segments.vert: the vertex colour times a tint.
in vec4 v_color;

// Multiplies the vertex colour, e.g. to fade lines that fail the depth test.
uniform vec4 u_tint;

out vec4 frag_color;

void main() {
  frag_color = v_color * u_tint;
}
