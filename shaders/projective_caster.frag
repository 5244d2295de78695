#version 330 core
// The casters black on the white projective texture (demos/projective.c),
// drawn through the light's frustum by shadow_depth.vert.
out vec4 out_shade;

void main() {
    out_shade = vec4(0.0);
}
