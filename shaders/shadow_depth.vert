#version 330 core
// Depth from the light (demos/lib/map.c), and the projective technique's
// casters; the texture coordinates for a cut-out object's fragments
// (depth.frag).
//
// With MAP_DEPTH_CLAMP_EMULATED (a cube's depth pass where the GL has no
// depth clamp) the light's clip z and w go to depth.frag, which writes the
// depth itself, and the position's z is 0, inside the near and far planes:
// a caster before the near plane is drawn at the near depth, as depth
// clamp draws it, instead of clipped.
layout(location = 0) in vec3 in_position;
layout(location = 2) in vec2 in_uv;

uniform mat4 u_model;
uniform mat4 u_view_projection; // the light's

out vec2 v_uv;
#ifdef MAP_DEPTH_CLAMP_EMULATED
out vec2 v_clip_depth; // the light's clip z and w
#endif

void main() {
    v_uv = in_uv;
    gl_Position = u_view_projection * (u_model * vec4(in_position, 1.0));
#ifdef MAP_DEPTH_CLAMP_EMULATED
    v_clip_depth = gl_Position.zw;
    gl_Position.z = 0.0;
#endif
}
