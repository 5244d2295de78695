#version 330 core
// The pixels the camera pass marked for rays (demos/lib/map_rays.c), read
// at the fragment's pixel: the caller's stencil takes them where this does
// not discard.
uniform sampler2D u_marks;

void main() {
    if (texelFetch(u_marks, ivec2(gl_FragCoord.xy), 0).r == 0.0)
        discard;
}
