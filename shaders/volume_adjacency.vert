#version 330 core
#include "volume_position.glsl"
// For the silhouette geometry shader: object-space positions for its tests,
// and each vertex on screen computed here, in a vertex shader like
// lit.vert's, so the caps it passes on lie at exactly the surface's depth.
layout(location = 0) in vec3 in_position;

out vec3 v_object;
invariant gl_Position;

void main() {
    v_object = in_position;
    gl_Position = volume_position(vec4(in_position, 1.0));
}
