#version 330 core
// A count of shadow volumes in a float target (demos/lib/volume_wide.h),
// read at the fragment's pixel: written back into the stencil (the caller
// replaces it where this does not discard), or with VOLUME_WIDE_OVERLAY
// drawn as colour by class.
uniform sampler2D u_count;
#ifdef VOLUME_WIDE_OVERLAY
uniform vec3 u_ramp[VOLUME_WIDE_OVERLAY_STEPS];
uniform float u_alpha;
#else
uniform int u_select; // 1, 2: that count; VOLUME_WIDE_OTHER: any other but 0
#endif

out vec4 out_color;

void main() {
    float count = texelFetch(u_count, ivec2(gl_FragCoord.xy), 0).r;
    if (count == 0.0)
        discard;
#ifdef VOLUME_WIDE_OVERLAY
    // 1, 2 and 3 their own; 4 to 255 (and negative) one; 256 or more the last.
    float size = abs(count);
    int step = size > float(VOLUME_COUNT_BOUND_STENCIL_MAX) ? VOLUME_WIDE_OVERLAY_STEPS - 1
             : count > 0.0 && count < float(VOLUME_WIDE_OVERLAY_STEPS - 1) ? int(count) - 1
                                                                   : VOLUME_WIDE_OVERLAY_STEPS - 2;
    out_color = vec4(u_ramp[step], u_alpha);
#else
    bool chosen = u_select == VOLUME_WIDE_OTHER ? count != 1.0 && count != 2.0 : count == float(u_select);
    if (!chosen)
        discard;
    out_color = vec4(0.0);
#endif
}
