#version 330 core
// Volumes only count in the stencil (colour writes off); the lecture
// overlays draw them in u_color.
uniform vec4 u_color;

out vec4 out_color;

void main() {
    out_color = u_color;
}
