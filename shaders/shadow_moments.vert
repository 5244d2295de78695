#version 330 core
// The moment blur's passes (shadow_moments.frag): one triangle over the
// whole target, from the vertex's index (no vertex buffer).
void main() {
    vec2 corner = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)) - 1.0;
    gl_Position = vec4(corner, 0.0, 1.0);
}
