// How much of an area light's disk one silhouette edge uncovers or
// covers, seen from a lit point: demos/lib/wedge_area.h says how, and its
// C twin there (the same steps, line for line) is what
// tests/test_wedge_area.c checks. WEDGE_AREA_NEAR_RECIPROCAL is its
// define.
const float WEDGE_AREA_PI = 3.14159265358979;

float wedge_area_beyond(vec2 a, vec2 b) {
    vec2 d = b - a;
    float len = length(d);
    if (len <= 0.0)
        return 0.0;
    d /= len;
    // On the line: u along it, v (constant) across it, from the centre.
    float v = d.x * a.y - d.y * a.x;
    if (v * v >= 1.0)
        return 0.0;
    float half_chord = sqrt(1.0 - v * v);
    float u1 = max(dot(a, d), -half_chord), u2 = min(dot(b, d), half_chord);
    if (u1 >= u2)
        return 0.0;
    float cross = v * (u1 - u2);
    return (atan(cross, u1 * u2 + v * v) - cross) / (2.0 * WEDGE_AREA_PI);
}

// The light's unit axis from p, and its distance (1 for a directional
// light).
float wedge_area_axis(vec3 p, vec4 light, out vec3 axis) {
    axis = light.w != 0.0 ? light.xyz - p : light.xyz;
    float distance = light.w != 0.0 ? length(axis) : 1.0;
    axis = normalize(axis);
    return distance;
}

float wedge_area_edge(vec3 p, vec4 light, float size, vec3 a, vec3 b) {
    vec3 axis;
    float distance = wedge_area_axis(p, light, axis);
    vec3 t = normalize(cross(axis, abs(axis.x) < 0.5 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    vec3 bt = cross(axis, t);
    vec3 ra = a - p, rb = b - p;
    float da = dot(ra, axis), db = dot(rb, axis);
    float near = distance / float(WEDGE_AREA_NEAR_RECIPROCAL);
    bool bounded = light.w != 0.0;
    if ((da < near && db < near) || (bounded && da > distance && db > distance))
        return 0.0;
    if (da < near) {
        ra = mix(ra, rb, (near - da) / (db - da));
        da = near;
    } else if (db < near) {
        rb = mix(ra, rb, (near - da) / (db - da));
        db = near;
    }
    if (bounded && da > distance) {
        ra = mix(ra, rb, (distance - da) / (db - da));
        da = distance;
    } else if (bounded && db > distance) {
        rb = mix(ra, rb, (distance - da) / (db - da));
        db = distance;
    }
    float scale_a = distance / (da * size), scale_b = distance / (db * size);
    return wedge_area_beyond(vec2(dot(ra, t), dot(ra, bt)) * scale_a, vec2(dot(rb, t), dot(rb, bt)) * scale_b);
}
