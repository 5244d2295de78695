#version 330 core
// A caster squashed onto the receiver plane along the light's rays
// (demos/planar.c). The clip distances keep only the part of the caster
// that lies between the plane and the light: what is below the plane or
// beyond the light would project onto the plane as an "anti-shadow".
// The switch is a uniform rather than glDisable(GL_CLIP_DISTANCEi), which
// some drivers (Mesa 22's llvmpipe) ignore once the shader writes them.
// Without clip distances (common/gl/shader.h) the fragment stage discards
// what they would clip. The texture coordinates are for a cut-out caster's
// fragments (planar_shadow.frag).
layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat4 u_shadow; // world point -> its shadow on the plane (homogeneous)
uniform vec4 u_plane;  // receiver plane, unit normal, oriented towards the light
uniform bool u_reject; // false: keep anti-shadows, for the lecture

out vec2 v_uv;

#ifdef SHADER_NO_CLIP_DISTANCES
out vec2 v_clip_distances;
#else
out float gl_ClipDistance[2];
#endif

void main() {
    v_uv = in_uv;
    vec4 world = u_model * vec4(in_position, 1.0);
    vec4 flattened = u_shadow * world;
    // Above the plane, nearer the plane than the light.
    vec2 clip_distances = u_reject ? vec2(dot(u_plane, world), flattened.w) : vec2(1.0);
#ifdef SHADER_NO_CLIP_DISTANCES
    v_clip_distances = clip_distances;
#else
    gl_ClipDistance[0] = clip_distances.x;
    gl_ClipDistance[1] = clip_distances.y;
#endif
    gl_Position = u_view_projection * flattened;
}
