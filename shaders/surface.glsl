// A surface's base colour (linear RGB): the object's colour times its
// base-colour texture's at the fragment's texture coordinates, decoded from
// sRGB by the GL, trilinear from the levels common/data/texture.h makes,
// wrapped by its modes; the reference (common/measure/raytrace.c) samples the same
// levels by the same rule. An object without a texture reads a white
// texel: its colour exactly.
uniform vec3 u_albedo;
uniform sampler2D u_base_color; // on render.h's RENDER_BASE_COLOR_UNIT
uniform float u_base_alpha;     // a cut-out object's: its base colour's alpha
uniform float u_alpha_cutoff;   // a cut-out object's (glTF's alphaMode MASK)

in vec2 v_uv;

// The fragment's base colour: set first in main (surface_begin), where the
// texture's level of detail has its derivatives.
vec3 surface_albedo;

void surface_begin() { surface_albedo = u_albedo * texture(u_base_color, v_uv).rgb; }

// Whether a cut-out object has no surface here (the programs compiled with
// SURFACE_CUT_OUT discard there: common/gl/render.h): its alpha read at
// level 0, bilinear, whatever the distance (the cut-out's shape is the
// texture's own), below the cutoff; scene_object_cut_out is the same rule.
bool surface_cut_out() { return u_base_alpha * textureLod(u_base_color, v_uv, 0.0).a < u_alpha_cutoff; }

// The share of each channel a translucent object (glTF's alphaMode BLEND)
// lets through here, (1 - a) + a C: C its base colour, a its alpha, the
// texture read at level 0 as for cut-outs; scene_object_transmittance is
// the same rule.
vec3 surface_transmittance() {
    vec4 texel = textureLod(u_base_color, v_uv, 0.0);
    float a = u_base_alpha * texel.a;
    return 1.0 - a + a * u_albedo * texel.rgb;
}
