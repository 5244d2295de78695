// The texel-size overlay's colours (shaders/map_light.glsl) and its
// legend's bar (overlay_heat_legend.frag, demos/lib/map_overlay.c):
// one ramp for both, so the legend shows the picture's colours.
// The texel-size overlay's heat map runs over log2 of a texel's size in
// pixels from -2 (a quarter pixel) to 5 (32 pixels): shifted by OFFSET and
// divided by RANGE it is 0..1, one pixel at OFFSET / RANGE. The area floor
// keeps a map seen edge-on (no area) finite. Colours: blue below a pixel,
// green at one, red above; shaded by the picture's luminance (Rec. 601's
// weights, rounded) times GAIN, from DARKEST up to DARKEST + SHADE, so the
// scene stays readable under it.
const float MAP_HEAT_MIN_AREA = 1e-12;
// The ends, log2 of a texel's size in pixels, from C (map.h).
const float MAP_HEAT_LOG2_OFFSET = -float(MAP_HEAT_LOG2_MIN);
const float MAP_HEAT_LOG2_RANGE = float(MAP_HEAT_LOG2_MAX - MAP_HEAT_LOG2_MIN);
const vec3 MAP_HEAT_SMALL = vec3(0.1, 0.2, 1.0);
const vec3 MAP_HEAT_ONE_PIXEL = vec3(0.1, 0.9, 0.2);
const vec3 MAP_HEAT_LARGE = vec3(1.0, 0.1, 0.05);
const vec3 MAP_HEAT_LUMINANCE = vec3(0.3, 0.6, 0.1);
const float MAP_HEAT_GAIN = 2.0;
const float MAP_HEAT_DARKEST = 0.4;
const float MAP_HEAT_SHADE = 0.6;

// The heat colour `heat` over the picture's colour c, shaded by c's
// luminance, so that the scene's shading still reads under it.
vec3 texel_heat_shade(vec3 heat, vec3 c) {
    float shade = min(dot(c, MAP_HEAT_LUMINANCE) * MAP_HEAT_GAIN, 1.0);
    return heat * (MAP_HEAT_DARKEST + MAP_HEAT_SHADE * shade);
}

// The heat colour of a texel log2_pixels (log2 of its size in pixels) big.
vec3 texel_heat_color(float log2_pixels) {
    float t = clamp((log2_pixels + MAP_HEAT_LOG2_OFFSET) / MAP_HEAT_LOG2_RANGE, 0.0, 1.0);
    float one_pixel = MAP_HEAT_LOG2_OFFSET / MAP_HEAT_LOG2_RANGE;
    return t < one_pixel ? mix(MAP_HEAT_SMALL, MAP_HEAT_ONE_PIXEL, t / one_pixel)
                         : mix(MAP_HEAT_ONE_PIXEL, MAP_HEAT_LARGE, (t - one_pixel) / (1.0 - one_pixel));
}
