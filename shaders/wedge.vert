#version 330 core
// A penumbra wedge's vertex (demos/lib/volume_wedges.h): homogeneous,
// world, w = 0 at infinity; the edge's ends, the first's w its
// multiplicity, passed on unchanged to every fragment.
layout(location = 0) in vec4 in_position;
layout(location = 1) in vec4 in_a;
layout(location = 2) in vec4 in_b;
uniform mat4 u_view_projection;
flat out vec4 v_a;
flat out vec3 v_b;

void main() {
    gl_Position = u_view_projection * in_position;
    v_a = in_a;
    v_b = in_b.xyz;
}
