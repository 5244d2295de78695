#version 330 core
// The triangle's own (geometric) normal, exact per face rather than from
// screen-space derivatives, which blur across 2x2 pixel quads.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

// And its plane relative to the eye (unit normal, the eye's distance
// along it), for the exact position on huge triangles (geometry.frag).
in vec3 v_world[];
out vec3 g_world;
flat out vec3 g_face_normal;
flat out vec4 g_plane;

uniform vec3 u_eye;

void main() {
    vec3 n = cross(v_world[1] - v_world[0], v_world[2] - v_world[0]);
    float length_n = length(n);
    vec3 unit = length_n > 0.0 ? n / length_n : vec3(0.0);
    vec4 plane = vec4(unit, dot(unit, v_world[0] - u_eye));
    for (int i = 0; i < 3; i++) {
        g_world = v_world[i];
        g_face_normal = n;
        g_plane = plane;
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
