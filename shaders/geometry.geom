#version 330 core
// The triangle's own (geometric) normal, exact per face rather than from
// screen-space derivatives, which blur across 2x2 pixel quads.
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;

in vec3 v_world[];
out vec3 g_world;
flat out vec3 g_face_normal;

void main() {
    vec3 n = cross(v_world[1] - v_world[0], v_world[2] - v_world[0]);
    for (int i = 0; i < 3; i++) {
        g_world = v_world[i];
        g_face_normal = n;
        gl_Position = gl_in[i].gl_Position;
        EmitVertex();
    }
    EndPrimitive();
}
