#version 330 core
// Only the naive path (stencil off) writes colour: it multiplies what is
// there by one half per layer, which is what makes overlaps double-dark.
out vec4 out_color;

void main() {
    out_color = vec4(0.5);
}
