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

vec3 volume_to_light(vec3 p) {
    return u_light.xyz - u_light.w * p;
}

// The CPU's weight (mesh_point_facing, and the rule's weight of a
// back-facing triangle): 1 facing the light, -1 facing away (0 on a closed
// mesh), 0 edge-on.
int volume_weight(vec3 a, vec3 b, vec3 c) {
    vec3 n = cross(b - a, c - a);
    float along = dot(n, volume_to_light(a));
    float reach = length(volume_to_light(a)) + length(volume_to_light(b)) + length(volume_to_light(c));
    if (abs(along) <= length(n) * reach / float(MESH_POINT_EDGE_ON_RECIPROCAL))
        return 0;
    return along > 0.0 ? 1 : u_topology == VOLUME_SILHOUETTE_CLOSED ? 0 : -1;
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
    // Weight 0 (edge-on, or a closed mesh's back-facing triangle, whose
    // light-facing prisms already cover its shadow): no prism.
    int weight = volume_weight(p[0], p[2], p[4]);
    if (weight == 0)
        return;
    bool faces = weight > 0;
    for (int i = 0; i < 6; i += 2) {
        int next = (i + 2) % 6;
        bool border = u_topology == VOLUME_SILHOUETTE_OPEN && p[i + 1] == p[(i + 4) % 6];
        if (!border && volume_weight(p[i], p[i + 1], p[next]) == weight)
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
