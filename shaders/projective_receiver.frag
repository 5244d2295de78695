#version 330 core
// The receivers' pass of demos/projective.c: the casters' black-and-white
// image from the light, projected onto each receiver pixel (its world
// position through the light's view-projection, divided by w: the
// eye-linear texture coordinates of the fixed-function pipeline). The
// fragment survives, and marks the stencil, where the image is black;
// it is discarded where the image is white or where the point lies no
// farther from the light than the nearest caster (the back-projection
// cut, u_cut), which no caster can shadow.
in vec3 v_position;

uniform mat4 u_light_view_projection;
uniform sampler2D u_projected;
uniform vec4 u_depth_plane; // depth from the light: dot(xyz, p) + w
uniform float u_nearest;    // the casters' nearest depth
uniform bool u_cut;

void main() {
    if (u_cut && dot(u_depth_plane.xyz, v_position) + u_depth_plane.w <= u_nearest)
        discard;
    vec4 clip = u_light_view_projection * vec4(v_position, 1.0);
    if (clip.w == 0.0)
        discard;
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    if (texture(u_projected, uv).r * 100.0 >= float(PROJECTIVE_LIT_PERCENT))
        discard;
}
