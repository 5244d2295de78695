#version 330 core
// The scene carried into a warp's space (demos/psm.c's post-perspective
// view): world -> u_warp_space, clipped to that space's clip cube (inside
// it the warp is one-to-one; behind its eye points would fold over), then
// seen by an observer (u_view_projection) as ordinary geometry.
layout(location = 0) in vec3 in_position;

uniform mat4 u_model;
uniform mat4 u_warp_space;
uniform mat4 u_view_projection;

out vec3 v_warped;
#ifdef SHADER_NO_CLIP_DISTANCES
out vec3 v_clip_distances[2]; // the planes x, y, z = w; then = -w (common/gl/shader.h)
#else
out float gl_ClipDistance[6];
#endif

void main() {
    vec4 warped = u_warp_space * (u_model * vec4(in_position, 1.0));
#ifdef SHADER_NO_CLIP_DISTANCES
    v_clip_distances[0] = warped.w - warped.xyz;
    v_clip_distances[1] = warped.w + warped.xyz;
#else
    for (int k = 0; k < 3; k++) {
        gl_ClipDistance[2 * k] = warped.w - warped[k];
        gl_ClipDistance[2 * k + 1] = warped.w + warped[k];
    }
#endif
    v_warped = warped.xyz / warped.w;
    // Homogeneous as it is: the observer's projection divides once, by the
    // product of both w, which the clip cube keeps positive.
    gl_Position = u_view_projection * warped;
}
