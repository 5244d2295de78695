#version 330 core
// Light 0's shadow map as an inset (demos/lib/map_overlay.c), read
// from its reduction (overlay_reduce.frag): each pixel shows the nearest
// depth held in its block of texels, so that a caster narrower than a
// pixel of the inset still shows, as linear depth fitted to what the
// inset's layer holds: its nearest held depth black, its farthest
// MAP_INSET_FAR_GREY_PERCENT grey, a block that holds nothing
// white. A 2D map fills the quad; a cube map's six faces lie in two rows
// of three (+X -X +Y, then -Y +Z -Z), each as seen from the cube's centre;
// an array map's layer u_layer fills it (one quad per layer).
in vec2 v_uv;

uniform sampler2DArray u_reduced; // per block, (nearest, farthest) held; a layer per map layer (a cube's face)
uniform int u_kind;               // a map_kind: MAP_2D (0), MAP_CUBE or MAP_ARRAY
uniform int u_layer;
uniform int u_size;   // the map's texels on a side
uniform int u_factor; // the map's texels on a side of a block
uniform bool u_orthographic;
uniform float u_near;
uniform float u_far;
uniform vec2 u_held; // the nearest and the farthest depth held, as stored

out vec4 out_color;

// A perspective map (and each cube face) stores 1/z: undone, so that
// depth reads evenly.
float overlay_linear(float d) {
    return u_orthographic ? d : 2.0 * u_near * u_far / (u_far + u_near - (d * 2.0 - 1.0) * (u_far - u_near));
}

void main() {
    vec2 uv = v_uv;
    int layer = u_layer;
    if (u_kind == MAP_CUBE) {
        vec2 cell = floor(v_uv * vec2(3.0, 2.0));
        layer = int(cell.x) + 3 * (1 - int(cell.y));
        uv = fract(v_uv * vec2(3.0, 2.0));
        uv.y = 1.0 - uv.y; // a face's t runs down, seen from the centre
    }
    ivec2 texel = min(ivec2(uv * float(u_size)), ivec2(u_size - 1));
    float d = texelFetch(u_reduced, ivec3(texel / u_factor, layer), 0).r;
    if (d >= 1.0) {
        out_color = vec4(1.0);
        return;
    }
    float nearest = overlay_linear(u_held.x), span = overlay_linear(u_held.y) - nearest;
    float t = span > 0.0 ? clamp((overlay_linear(d) - nearest) / span, 0.0, 1.0) : 0.0;
    out_color = vec4(vec3(t * float(MAP_INSET_FAR_GREY_PERCENT) / 100.0), 1.0);
}
