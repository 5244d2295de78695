// Shared lighting model: Lambert diffuse plus a constant ambient term, the
// same model the ray-traced reference evaluates, so that pictures compare.
// The lights live in uniform blocks, one per light group, that
// common/gl/render.c fills once per frame for every program.
//
// Visibility mode (lights_count.y = K >= 0) turns any technique's picture
// into its own shadow decision for light K, without the technique knowing:
// light K contributes exactly 1 wherever it can reach (inside a spot's outer
// cone and the light's range), every other light and the ambient term 0, so whatever the technique
// does to shadow light K leaves its visibility in the red channel (see
// common/gl/capture.c).
//
// The block holds one group of the scene's lights, SHADER_PASS_LIGHTS of
// them in their slots (common/gl/render.h, "Light groups"), and K is
// light K's slot, or SHADER_PASS_LIGHTS in a group without it. The
// constant comes from C (common/gl/shader.h), injected by the shader
// loader; the block's layout is checked in common/gl/render.c.
layout(std140) uniform Lights {
    vec4 lights_ambient;                      // rgb
    ivec4 lights_count;                       // x: count, y: visibility mode slot or -1
    vec4 lights_position[SHADER_PASS_LIGHTS];  // xyz; w = 1 positional, 0 directional
    vec4 lights_direction[SHADER_PASS_LIGHTS]; // xyz: the way the light travels
    vec4 lights_color[SHADER_PASS_LIGHTS];     // rgb: colour times intensity
    vec4 lights_reach[SHADER_PASS_LIGHTS];     // x: cos(outer), y: cos(inner) (a point light has x < -1);
                                             // z: range, 0 unlimited
};

// Unit vector from the surface point towards light i.
vec3 lighting_to_light(int i, vec3 position) {
    vec4 l = lights_position[i];
    return l.w == 0.0 ? -lights_direction[i].xyz : normalize(l.xyz - position);
}

// How much of light i reaches a point at `distance` from it: the window of
// scene_light_range_window (common/data/scene.h), (1 - (d / r)^4)^2 inside
// the range r and 0 beyond, smooth and exactly 0 at r; 1 without a range.
float lighting_range_window(int i, float distance) {
    float range = lights_reach[i].z;
    if (range <= 0.0)
        return 1.0;
    float x = distance / range, w = max(1.0 - x * x * x * x, 0.0);
    return w * w;
}

// What light i would add at this point if nothing blocked it: the shadow
// techniques decide visibility, this decides everything else.
vec3 lighting_unshadowed(int i, vec3 position, vec3 normal, vec3 albedo) {
    vec3 to_light = lighting_to_light(i, position);
    float cos_axis = dot(-to_light, lights_direction[i].xyz);
    // A directional light has no range (lights_reach.z = 0): 1 everywhere.
    float window = lighting_range_window(i, distance(lights_position[i].xyz, position));
    if (lights_count.y >= 0)
        return vec3(i == lights_count.y && cos_axis > lights_reach[i].x && window > 0.0 ? 1.0 : 0.0);
    float spot = smoothstep(lights_reach[i].x, lights_reach[i].y, cos_axis);
    return albedo * lights_color[i].rgb * max(dot(normal, to_light), 0.0) * spot * window;
}

vec3 lighting_ambient(vec3 albedo) {
    return lights_count.y >= 0 ? vec3(0.0) : albedo * lights_ambient.rgb;
}
