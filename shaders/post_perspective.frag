#version 330 core
// Flat shading of the warped scene, from the slope of its warped position:
// normals do not survive a projective warp, faces do.
in vec3 v_warped;
#ifdef SHADER_NO_CLIP_DISTANCES
in vec3 v_clip_distances[2];
#endif

uniform vec3 u_albedo;

out vec4 out_color;

void main() {
#ifdef SHADER_NO_CLIP_DISTANCES
    if (any(lessThan(min(v_clip_distances[0], v_clip_distances[1]), vec3(0.0))))
        discard;
#endif
    vec3 n = normalize(cross(dFdx(v_warped), dFdy(v_warped)));
    float shade = 0.35 + 0.65 * abs(dot(n, normalize(vec3(0.4, 0.8, -0.45))));
    out_color = vec4(u_albedo * shade, 1.0);
}
