#version 330 core
// One sample's share of an area light's visibility, added (blending)
// wherever the caller's stencil test says the sample's point reaches the
// pixel: common/gl/soft_visibility.h.
uniform float u_weight;

out vec4 out_visibility;

void main() {
    out_visibility = vec4(u_weight, 0.0, 0.0, 0.0);
}
