// The world point a pixel of the frame's depth shows (a copy of the
// depth buffer: demos/lib/volume_wedges.c), for the penumbra wedges'
// passes.
uniform sampler2D u_depth;
uniform mat4 u_inverse_view_projection;
uniform vec2 u_depth_to_ndc; // window depth -> NDC z: scale, offset
uniform float u_far_depth;   // nothing drawn there

float wedge_point_depth(ivec2 pixel) {
    return texelFetch(u_depth, clamp(pixel, ivec2(0), textureSize(u_depth, 0) - 1), 0).r;
}

vec3 wedge_point(ivec2 pixel) {
    vec2 ndc = 2.0 * (vec2(pixel) + 0.5) / vec2(textureSize(u_depth, 0)) - 1.0;
    vec4 world = u_inverse_view_projection * vec4(ndc, wedge_point_depth(pixel) * u_depth_to_ndc.x + u_depth_to_ndc.y, 1.0);
    return world.xyz / world.w;
}
