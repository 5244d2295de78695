#version 330 core
// Scene geometry in world space. gl_Position is invariant so that passes
// which redraw a surface with depth test GL_EQUAL hit exactly the same depth.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;

out vec3 v_position;
out vec3 v_normal;
out vec2 v_uv;
invariant gl_Position;
#ifdef LIT_PROJECTED
// demos/projective.c's receiver pass: the point in the light's image,
// eye-linear texture coordinates in [0, w] to divide per fragment
// (linear in world space, so interpolated exactly), and its depth from
// the light along u_depth_plane.
uniform mat4 u_light_texture;
uniform vec4 u_depth_plane;
out vec4 v_projected;
out float v_light_depth;
#endif

void main() {
    vec4 world = u_model * vec4(in_position, 1.0);
    v_position = world.xyz;
    v_normal = u_normal_matrix * in_normal;
    v_uv = in_uv;
    gl_Position = u_view_projection * world;
#ifdef LIT_PROJECTED
    v_projected = u_light_texture * world;
    v_light_depth = dot(u_depth_plane.xyz, world.xyz) + u_depth_plane.w;
#endif
}
