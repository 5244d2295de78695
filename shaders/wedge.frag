#version 330 core
// A penumbra wedge's pixel (demos/lib/volume_wedges.h): the point the
// depth buffer holds there, and the share of the light's disk the wedge's
// edge uncovers (or covers) seen from it, added into the visibility.
#include "wedge_area.glsl"
#include "wedge_point.glsl"
flat in vec4 v_a; // the edge's first end, its multiplicity as w
flat in vec3 v_b;
uniform vec4 u_light; // homogeneous; a direction unit
uniform float u_size; // the disk's radius, or tan(angular radius)
uniform vec3 u_eye;
out vec4 out_visibility;

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (wedge_point_depth(pixel) == u_far_depth)
        discard;
    vec3 p = wedge_point(pixel);
    // Lifted towards the light by a share of its distance from the eye, as
    // the depth buffer resolves it: off the surface's own silhouette edges.
    vec3 towards = normalize(u_light.w != 0.0 ? u_light.xyz - p : u_light.xyz);
    p += towards * (distance(p, u_eye) / float(VOLUME_WEDGES_LIFT_RECIPROCAL));
    out_visibility = vec4(v_a.w * wedge_area_edge(p, u_light, u_size, v_a.xyz, v_b), 0.0, 0.0, 0.0);
}
