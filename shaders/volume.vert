#version 330 core
#include "volume_position.glsl"
// Shadow-volume geometry built on the CPU (demos/lib/volume_mesh.c), in
// object space: w = 1 on the mesh, w = 0 swept to infinity.
layout(location = 0) in vec4 in_position;
invariant gl_Position;

void main() {
    gl_Position = volume_position(in_position);
}
