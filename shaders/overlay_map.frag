#version 330 core
// Light 0's shadow map shown as linear depth: near black, far white. A 2D
// map fills the quad; a cube map's six faces lie in two rows of three
// (+X -X +Y, then -Y +Z -Z); an array map's layer u_layer fills it (one
// quad per layer). The map is read with a plain sampler, so its compare
// mode is off while this draws.
in vec2 v_uv;

uniform sampler2D u_map;
uniform samplerCube u_cube_map;
uniform sampler2DArray u_array_map;
uniform int u_kind; // a shadow_map_kind: SHADOW_MAP_2D (0), SHADOW_MAP_CUBE or SHADOW_MAP_ARRAY
uniform int u_layer;
uniform bool u_orthographic;
uniform float u_near;
uniform float u_far;

out vec4 out_color;

// The direction through face coordinates st (-1..1) of cube face `face`,
// by the table of the GL specification (cube map face selection); faces are
// numbered in GL's order, SHADOW_MAP_FACE_* in C.
vec3 overlay_cube_direction(int face, vec2 st) {
    if (face == SHADOW_MAP_FACE_POSITIVE_X) return vec3(1.0, -st.y, -st.x);
    if (face == SHADOW_MAP_FACE_NEGATIVE_X) return vec3(-1.0, -st.y, st.x);
    if (face == SHADOW_MAP_FACE_POSITIVE_Y) return vec3(st.x, 1.0, st.y);
    if (face == SHADOW_MAP_FACE_NEGATIVE_Y) return vec3(st.x, -1.0, -st.y);
    if (face == SHADOW_MAP_FACE_POSITIVE_Z) return vec3(st.x, -st.y, 1.0);
    return vec3(-st.x, -st.y, -1.0); // SHADOW_MAP_FACE_NEGATIVE_Z
}

void main() {
    float d;
    if (u_kind == SHADOW_MAP_CUBE) {
        vec2 cell = floor(v_uv * vec2(3.0, 2.0));
        int face = int(cell.x) + 3 * (1 - int(cell.y));
        vec2 st = fract(v_uv * vec2(3.0, 2.0)) * 2.0 - 1.0;
        d = texture(u_cube_map, overlay_cube_direction(face, vec2(st.x, -st.y))).r;
    } else if (u_kind == SHADOW_MAP_ARRAY) {
        d = texture(u_array_map, vec3(v_uv, float(u_layer))).r;
    } else {
        d = texture(u_map, v_uv).r;
    }
    // A perspective map (and each cube face) stores 1/z; undo it so depth
    // reads evenly.
    float z = u_orthographic ? d
                             : (2.0 * u_near * u_far / (u_far + u_near - (d * 2.0 - 1.0) * (u_far - u_near)) - u_near) /
                                   (u_far - u_near);
    out_color = vec4(vec3(z), 1.0);
}
