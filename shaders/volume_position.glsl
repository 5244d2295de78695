// Where a shadow-volume vertex lands on screen. A vertex on the mesh
// (w = 1) goes through exactly the expression of lit.vert, so a cap lies
// at the very depth of the surface it covers (depth test GL_LESS then
// counts it as behind that surface, never in front); a vertex at infinity
// (w = 0) is a direction, which the model matrix turns without moving.
uniform mat4 u_model;
uniform mat4 u_view_projection;

vec4 volume_position(vec4 p) {
    if (p.w == 1.0) {
        vec4 world = u_model * vec4(p.xyz, 1.0);
        return u_view_projection * world;
    }
    return u_view_projection * (u_model * vec4(p.xyz, 0.0));
}
