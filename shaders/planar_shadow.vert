#version 330 core
// A caster squashed onto the receiver plane along the light's rays
// (demos/planar.c). The clip distances keep only the part of the caster
// that lies between the plane and the light: what is below the plane or
// beyond the light would project onto the plane as an "anti-shadow".
// The switch is a uniform rather than glDisable(GL_CLIP_DISTANCEi), which
// some drivers (Mesa 22's llvmpipe) ignore once the shader writes them.
layout(location = 0) in vec3 in_position;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat4 u_shadow; // world point -> its shadow on the plane (homogeneous)
uniform vec4 u_plane;  // receiver plane, unit normal, oriented towards the light
uniform bool u_reject; // false: keep anti-shadows, for the lecture

out float gl_ClipDistance[2];

void main() {
    vec4 world = u_model * vec4(in_position, 1.0);
    vec4 flattened = u_shadow * world;
    gl_ClipDistance[0] = u_reject ? dot(u_plane, world) : 1.0; // above the plane
    gl_ClipDistance[1] = u_reject ? flattened.w : 1.0;         // nearer the plane than the light
    gl_Position = u_view_projection * flattened;
}
