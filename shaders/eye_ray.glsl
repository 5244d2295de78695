// The eye ray through this pixel's centre, for the exact surface of huge
// triangles (common/gl/render.h, "Huge receivers"; the uniforms from
// render_eye_ray_uniforms): in the view's axes, reaching z = -1, from the
// projection's x and y rows; in the world's axes through the view's
// rotation alone. Nothing here is larger than what the pixel sees.
uniform mat3 u_view_rotation; // world axes -> view axes
uniform vec4 u_ray;           // 1 / projection[0][0], 1 / projection[1][1], projection[2][0], projection[2][1]
uniform vec4 u_viewport;      // x, y, width, height

vec3 eye_ray_view() {
    vec2 ndc = 2.0 * (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw - 1.0;
    return vec3((ndc + u_ray.zw) * u_ray.xy, -1.0);
}

vec3 eye_ray_world() {
    return transpose(u_view_rotation) * eye_ray_view();
}
