#version 330 core
// A weight (one point of an area light: one) added (blending) to the
// light's sum wherever the caller's stencil test passes:
// common/gl/soft_visibility.h.
uniform float u_weight;

out vec4 out_visibility;

void main() {
    out_visibility = vec4(u_weight, 0.0, 0.0, 0.0);
}
