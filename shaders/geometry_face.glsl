// A triangle's own (geometric) normal from its world corners, exact per
// face rather than from screen-space derivatives, which blur across 2x2
// pixel quads; and its plane relative to the eye (unit normal, the eye's
// distance along it), for the exact position on huge triangles
// (geometry.frag).
void geometry_face(vec3 w0, vec3 w1, vec3 w2, vec3 eye, out vec3 n, out vec4 plane) {
    n = cross(w1 - w0, w2 - w0);
    float length_n = length(n);
    vec3 unit = length_n > 0.0 ? n / length_n : vec3(0.0);
    plane = vec4(unit, dot(unit, w0 - eye));
}
