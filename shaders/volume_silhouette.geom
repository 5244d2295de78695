#version 330 core
#include "volume_position.glsl"
// Silhouettes on the GPU for a closed mesh (GL_TRIANGLES_ADJACENCY: corners
// 0, 2, 4; across each edge i -> i+2, vertex i+1 of the neighbour): a
// light-facing triangle whose neighbour faces away sweeps that edge to
// infinity, the sides of the volume (z-fail's caps come from the CPU path,
// see demos/volumes.c for why). Back-facing triangles emit nothing:
// the light-facing prisms of a closed mesh already cover its shadow (see
// demos/lib/volume_mesh.h). Same facing test and same orientation as the
// CPU path; vertices on the mesh come placed from the vertex shader (see
// there).
layout(triangles_adjacency) in;
layout(triangle_strip, max_vertices = 12) out;

in vec3 v_object[];
uniform vec4 u_light; // object space, homogeneous
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
    if (!volume_faces_light(p[0], p[2], p[4]))
        return;
    for (int i = 0; i < 6; i += 2) {
        vec3 a = p[i], b = p[(i + 2) % 6];
        if (volume_faces_light(a, p[i + 1], b))
            continue;
        // The side of a -> b, facing out of the prism: b, a, a far, b far.
        volume_emit_corner((i + 2) % 6);
        volume_emit_corner(i);
        volume_emit(volume_far(b));
        volume_emit(volume_far(a));
        EndPrimitive();
    }
}
