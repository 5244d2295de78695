#version 330 core
// One point of an area light, added (blending) to its sum wherever the
// caller's stencil test says the point reaches the pixel:
// common/gl/soft_visibility.h.
out vec4 out_visibility;

void main() {
    out_visibility = vec4(1.0, 0.0, 0.0, 0.0);
}
