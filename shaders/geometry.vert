#version 330 core
// What every pixel sees, for dumps (common/gl/capture.c): world position in,
// the face normal is made per triangle in geometry.geom.
layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;

uniform mat4 u_model;
uniform mat4 u_view_projection;

out vec3 v_world;
out vec2 v_corner_uv; // for a cut-out object's fragments (geometry.frag)
invariant gl_Position;

void main() {
    vec4 world = u_model * vec4(in_position, 1.0);
    v_world = world.xyz;
    v_corner_uv = in_uv;
    gl_Position = u_view_projection * world;
}
