#version 330 core
// Depth only: the shadow maps' depth pass (shadow_depth.vert) and the
// camera's depth pre-pass (lit.vert, common/gl/render.h) write nothing
// else, so the fragment stage is empty.
void main() {
}
