#version 330 core
// The exact depth of a triangle huge seen from the eye, for the shadow
// volumes' counting (demos/lib/volume_receivers.h): where the eye ray
// through this pixel's centre meets the triangle's plane, instead of the
// rasterizer's interpolation from corners far away. Everything is
// relative to the eye, in the world's axes or the view's.
#include "eye_ray.glsl"
uniform sampler2D u_planes; // triangle t's at (t % width, t / width): unit normal, the eye's distance along it
uniform mat4 u_projection;      // the raster's: standard or reversed depth (common/gl/depth.h)
uniform bool u_zero_to_one;     // reversed depth's clip control: window depth is clip z / w

void main() {
    int width = textureSize(u_planes, 0).x;
    vec4 plane = texelFetch(u_planes, ivec2(gl_PrimitiveID % width, gl_PrimitiveID / width), 0);
    vec3 ray = eye_ray_view();
    float t = plane.w / dot(plane.xyz, transpose(u_view_rotation) * ray);
    if (!(t > 0.0) || isinf(t)) { // edge-on, or a triangle with no normal: what the rasterizer has
        gl_FragDepth = gl_FragCoord.z;
        return;
    }
    vec4 clip = u_projection * vec4(t * ray, 1.0);
    float depth_ndc = clip.z / clip.w;
    gl_FragDepth = u_zero_to_one ? gl_DepthRange.near + gl_DepthRange.diff * depth_ndc
                                 : 0.5 * (gl_DepthRange.diff * depth_ndc + gl_DepthRange.near + gl_DepthRange.far);
}
