#version 330 core
// A 2D shadow map shown as linear depth: near black, far white. The map is
// read with a plain sampler, so its compare mode is off while this draws.
in vec2 v_uv;

uniform sampler2D u_map;
uniform bool u_orthographic;
uniform float u_near;
uniform float u_far;

out vec4 out_color;

void main() {
    float d = texture(u_map, v_uv).r;
    // A perspective map stores 1/z; undo it so depth reads evenly.
    float z = u_orthographic ? d
                             : (2.0 * u_near * u_far / (u_far + u_near - (d * 2.0 - 1.0) * (u_far - u_near)) - u_near) /
                                   (u_far - u_near);
    out_color = vec4(vec3(z), 1.0);
}
