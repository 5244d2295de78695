#version 330 core
// ZP+'s near-plane count (demos/lib/volume_near.h): a caster's triangle
// projected from the light onto the camera's near plane, where it covers
// the pixels whose eye ray starts behind it as seen from the light. Only
// the part between the light and the plane shadows the plane: past the
// light, w < 0 clips it; behind the plane, volume.frag discards it
// (VOLUME_NEAR_COUNT). The depth is any inside the clip volume: the count
// takes no depth test.
layout(location = 0) in vec3 in_position;

uniform mat4 u_model;
uniform mat4 u_near_projection; // world -> the near plane, from the light, -> clip
uniform vec4 u_near_plane;      // world, positive on the light's side

out float v_light_side;

void main() {
    vec4 world = u_model * vec4(in_position, 1.0);
    v_light_side = dot(u_near_plane, world);
    vec4 clip = u_near_projection * world;
    gl_Position = vec4(clip.xy, 0.5 * clip.w, clip.w);
}
