// How much of an area light's disk one silhouette edge uncovers or
// covers, seen from a lit point: demos/lib/wedge_area.h says how, and its
// C twin there (the same steps, line for line) is what
// tests/test_wedge_area.c checks. WEDGE_AREA_NEAR_RECIPROCAL is its
// define.
const float WEDGE_AREA_PI = 3.14159265358979;

float wedge_area_beyond(vec2 a, vec2 b) {
    vec2 d = b - a;
    float qa = dot(d, d), qb = dot(a, d), qc = dot(a, a) - 1.0;
    float disc = qb * qb - qa * qc;
    if (qa <= 0.0 || disc <= 0.0)
        return 0.0;
    float root = sqrt(disc);
    float t1 = max((-qb - root) / qa, 0.0), t2 = min((-qb + root) / qa, 1.0);
    if (t1 >= t2)
        return 0.0;
    vec2 p1 = a + t1 * d, p2 = a + t2 * d;
    float cross = p1.x * p2.y - p1.y * p2.x;
    float angle = atan(cross, dot(p1, p2));
    return (angle - cross) / (2.0 * WEDGE_AREA_PI);
}

float wedge_area_edge(vec3 p, vec4 light, float size, vec3 a, vec3 b) {
    vec3 axis = light.w != 0.0 ? light.xyz - p : light.xyz;
    float distance = light.w != 0.0 ? length(axis) : 1.0;
    axis = normalize(axis);
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
