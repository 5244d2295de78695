// A shadow map's depths as stored, one texel at a time, for the passes
// that walk a map's texels (the moment blur's first pass,
// shadow_moments.frag; the inset's reduction, overlay_reduce.frag): the
// map is on the sampler of its kind (a map_kind), read with compare
// mode off and nearest. Every caller passes its kind as a constant, so the
// other kinds' reads are dropped.
uniform sampler2D u_source_2d;         // a 2D map's depths (the moment blur reads its moments here too)
uniform samplerCube u_source_cube;     // a cube map's depths
uniform sampler2DArray u_source_array; // an array map's depths

// The direction from a cube's centre through the centre of texel `texel`
// of face `face` (GL's table of faces, inverted).
vec3 map_texel_cube_direction(ivec2 texel, int face, int size) {
    vec2 st = (vec2(texel) + 0.5) * 2.0 / float(size) - 1.0;
    if (face == MAP_FACE_POSITIVE_X) return vec3(1.0, -st.y, -st.x);
    if (face == MAP_FACE_NEGATIVE_X) return vec3(-1.0, -st.y, st.x);
    if (face == MAP_FACE_POSITIVE_Y) return vec3(st.x, 1.0, st.y);
    if (face == MAP_FACE_NEGATIVE_Y) return vec3(st.x, -1.0, -st.y);
    if (face == MAP_FACE_POSITIVE_Z) return vec3(st.x, -st.y, 1.0);
    return vec3(-st.x, -st.y, -1.0);
}

// Texels on a side of the map of kind `kind`.
int map_texel_size(int kind) {
    if (kind == MAP_CUBE) return textureSize(u_source_cube, 0).x;
    if (kind == MAP_ARRAY) return textureSize(u_source_array, 0).x;
    return textureSize(u_source_2d, 0).x;
}

// The depth stored at texel `texel` of layer `layer` (a cube's face).
float map_texel_depth(int kind, ivec2 texel, int layer) {
    if (kind == MAP_CUBE)
        return texture(u_source_cube, map_texel_cube_direction(texel, layer, map_texel_size(kind))).r;
    if (kind == MAP_ARRAY) return texelFetch(u_source_array, ivec3(texel, layer), 0).r;
    return texelFetch(u_source_2d, texel, 0).r;
}
