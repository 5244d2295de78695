#version 330 core
#include "volume_position.glsl"
// Silhouettes on the GPU (GL_TRIANGLES_ADJACENCY: corners 0, 2, 4; across
// each edge i -> i+2, vertex i+1 of the neighbour, or on a border the
// triangle's own third vertex): the sides of the volume, swept to
// infinity, by the rule of demos/lib/volume_silhouette.h (z-fail's caps
// come from the CPU path, see there for why). Same facing test and same
// orientation as the CPU path; vertices on the mesh come placed from the
// vertex shader (see there).
layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 12) out;

in vec3 v_object[];
uniform vec4 u_light; // object space, homogeneous
uniform int u_topology; // VOLUME_SILHOUETTE_CLOSED or VOLUME_SILHOUETTE_OPEN
invariant gl_Position;

bool volume_faces_light(vec3 a, vec3 b, vec3 c) {
    return dot(cross(b - a, c - a), u_light.xyz - u_light.w * a) > 0.0;
}

vec4 volume_far(vec3 p) {
    return vec4(p * u_light.w - u_light.xyz, 0.0);
}

void volume_emit(vec4 p) {
    gl_Position = volume_position(p);
    EmitVertex();
}

// A vertex on the mesh, placed by the vertex shader.
void volume_emit_corner(int i) {
    gl_Position = gl_in[i].gl_Position;
    EmitVertex();
}

void main() {
    vec3 p[6];
    for (int i = 0; i < 6; i++)
        p[i] = v_object[i];
    bool faces = volume_faces_light(p[0], p[2], p[4]);
    // A closed mesh's back-facing triangles weigh 0: its light-facing
    // prisms already cover its shadow.
    if (!faces && u_topology == VOLUME_SILHOUETTE_CLOSED)
        return;
    for (int i = 0; i < 6; i += 2) {
        int next = (i + 2) % 6;
        bool border = u_topology == VOLUME_SILHOUETTE_OPEN && p[i + 1] == p[(i + 4) % 6];
        if (!border && volume_faces_light(p[i], p[i + 1], p[next]) == faces)
            continue;
        // The side of a -> b, facing out of the prism: b, a, a far, b far;
        // a back-facing triangle's prism runs the other way round.
        int a = faces ? i : next, b = faces ? next : i;
        volume_emit_corner(b);
        volume_emit_corner(a);
        volume_emit(volume_far(p[b]));
        volume_emit(volume_far(p[a]));
        EndPrimitive();
    }
}
