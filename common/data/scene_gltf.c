/* scene_gltf: a glTF 2.0 file (.gltf, .glb) as a scene (scene.h, "glTF
 * scenes"), read through assimp, which the model files already use and
 * which reads glTF's cameras and KHR_lights_punctual lights. */
#include <assimp/GltfMaterial.h>
#include <assimp/cimport.h>
#include <assimp/scene.h>
#include <cglm/cglm.h>
#include <cjson/cJSON.h>
#include <ctype.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_assimp.h"
#include "path.h"
#include "scene_internal.h"
#include "texture.h"

/* Room for a suffix that makes a name one object's, this many bytes
 * with its ending. */
#define SCENE_GLTF_SUFFIX_MAX 12
/* glTF's alphaCutoff where a MASK material gives none. */
#define SCENE_GLTF_ALPHA_CUTOFF 0.5f
/* The default colour of an object whose material gives none. */
#define SCENE_GLTF_GREY 0.8f
/* A fitted camera: its field of view (degrees), the direction it looks
 * from (towards the scene's centre from the front, above and to the
 * right), how much room the bounds' sphere leaves, and its depth range
 * about that sphere. */
#define SCENE_GLTF_FIT_FOV_DEG 45.0f
static const float scene_gltf_fit_from[3] = {0.6f, 0.5f, 1.0f};
#define SCENE_GLTF_FIT_ROOM 1.1f
#define SCENE_GLTF_FIT_NEAR_SHARE 0.5f
#define SCENE_GLTF_FIT_FAR_SHARE 1.5f
/* A fitted light: a sun from above, to the side. */
static const float scene_gltf_fit_sun[3] = {-0.35f, -1.0f, -0.25f};
/* A spot's outer cone stays under a right angle (the scene's own limit). */
#define SCENE_GLTF_MAX_SPOT_DEG 89.0f

/* Node transforms as cglm's column-major matrices. */
static void scene_gltf_matrix(const struct aiMatrix4x4 *t, mat4 out) {
    const float rows[4][4] = {{t->a1, t->a2, t->a3, t->a4},
                              {t->b1, t->b2, t->b3, t->b4},
                              {t->c1, t->c2, t->c3, t->c4},
                              {t->d1, t->d2, t->d3, t->d4}};
    for (int row = 0; row < 4; row++)
        for (int column = 0; column < 4; column++)
            out[column][row] = rows[row][column];
}

/* The world transform of the node called `name` under `node` (its
 * parent's given): false where none is. */
static bool scene_gltf_find(const struct aiNode *node, mat4 parent, const char *name, mat4 out) {
    mat4 local, world;
    scene_gltf_matrix(&node->mTransformation, local);
    glm_mat4_mul(parent, local, world);
    if (strcmp(node->mName.data, name) == 0) {
        glm_mat4_copy(world, out);
        return true;
    }
    for (unsigned i = 0; i < node->mNumChildren; i++)
        if (scene_gltf_find(node->mChildren[i], world, name, out))
            return true;
    return false;
}

/* Where a camera or light stands, and the way it looks: glTF places it at
 * the origin of its node (which assimp names after it), looking down the
 * node's -Z with +Y up. assimp 5.2 also copies the node's translation into
 * the camera's or light's own position, which its node's transform would
 * then move twice: the node alone is read. Without such a node, assimp's
 * own `position`, `look` and `up` (world coordinates then). */
static void scene_gltf_place(const struct aiScene *a, const char *name, struct aiVector3D position,
                             struct aiVector3D look, struct aiVector3D up, vec3 out_position, vec3 out_look,
                             vec3 out_up) {
    mat4 world, identity = GLM_MAT4_IDENTITY_INIT;
    if (!scene_gltf_find(a->mRootNode, identity, name, world)) {
        glm_vec3_copy((vec3){position.x, position.y, position.z}, out_position);
        glm_vec3_copy((vec3){look.x, look.y, look.z}, out_look);
        glm_vec3_copy((vec3){up.x, up.y, up.z}, out_up);
        return;
    }
    glm_vec3_copy(world[3], out_position);
    glm_mat4_mulv3(world, (vec3){0, 0, -1}, 0, out_look);
    glm_mat4_mulv3(world, (vec3){0, 1, 0}, 0, out_up);
}

/* ---- objects ---- */

typedef struct scene_gltf_reader {
    const char *file;
    const struct aiScene *a;
    scene *s;
    unsigned camera;      /* the file's camera to read (--camera) */
    int *capacity;        /* of s->objects */
    mesh_removed removed; /* by every object's mesh_sanitize_quietly, said once */
    /* Per material: its base-colour texture's index in s->textures, or
     * SCENE_GLTF_UNTEXTURED, once looked up (SCENE_GLTF_UNSEEN before). */
    int *material_texture;
    unsigned without_coordinates; /* textured meshes with no texture coordinates, said once */
    /* A file a scene file includes (scene_include_gltf): its objects'
     * names begin "PREFIX/", they cast and receive as it says and, as
     * every object of a scene file, are seen from both sides. NULL: the
     * file is the scene, every object casts and receives, seen from the
     * sides its material says (scene_gltf_single_sided). */
    const char *prefix;
    bool casts, receives;
} scene_gltf_reader;

#define SCENE_GLTF_UNSEEN (-2)
#define SCENE_GLTF_UNTEXTURED (-1)

/* A name for the object of node `node` that no earlier object has. */
static void scene_gltf_name(const scene_gltf_reader *r, const struct aiNode *node, char out[SCENE_NAME_MAX]) {
    char node_name[SCENE_GLTF_NODE_NAME_MAX + 1] = "mesh", base[SCENE_NAME_MAX];
    if (node->mName.length)
        memcpy(node_name, node->mName.data, strnlen(node->mName.data, SCENE_GLTF_NODE_NAME_MAX) + 1);
    node_name[SCENE_GLTF_NODE_NAME_MAX] = '\0';
    for (char *c = node_name; *c; c++)
        if (iscntrl((unsigned char)*c))
            *c = '_';
    /* The prefix is a scene file's object name, of SCENE_NAME_MAX bytes at
     * most: what the node's name leaves of it. */
    if (r->prefix)
        snprintf(base, sizeof base, "%.*s/%s", SCENE_GLTF_PREFIX_MAX, r->prefix, node_name);
    else
        snprintf(base, sizeof base, "%s", node_name);
    snprintf(out, SCENE_NAME_MAX, "%s", base);
    const scene *s = r->s;
    for (int i = 0; i < s->object_count; i++)
        if (strcmp(s->objects[i].name, out) == 0) {
            snprintf(out, SCENE_NAME_MAX, "%.*s_%d", (int)(SCENE_NAME_MAX - SCENE_GLTF_SUFFIX_MAX), base,
                     s->object_count);
            return;
        }
}

/* ---- base-colour textures ---- */

/* The image `path` names (a material's texture: "*N" for the file's
 * embedded image N, else a file beside the glTF file) into t. */
static bool scene_gltf_image(const scene_gltf_reader *r, const char *path, texture *t) {
    char name[PATH_MAX + 64];
    if (path[0] == '*') {
        char *end;
        unsigned long n = strtoul(path + 1, &end, 10);
        snprintf(name, sizeof name, "%s: embedded image %s", r->file, path + 1);
        if (*end || n >= r->a->mNumTextures) {
            fprintf(stderr, "%s: not in the file\n", name);
            return false;
        }
        const struct aiTexture *at = r->a->mTextures[n];
        if (at->mHeight == 0) /* compressed: mWidth bytes of a PNG, JPEG... */
            return texture_from_memory(t, name, (const unsigned char *)at->pcData, at->mWidth);
        size_t count = (size_t)at->mWidth * at->mHeight;
        unsigned char *rgba = malloc(4 * count);
        if (!rgba) {
            fprintf(stderr, "%s: out of memory\n", name);
            return false;
        }
        /* aiTexel is BGRA, top row first. */
        for (unsigned y = 0; y < at->mHeight; y++)
            for (unsigned x = 0; x < at->mWidth; x++) {
                const struct aiTexel *texel = &at->pcData[(size_t)(at->mHeight - 1 - y) * at->mWidth + x];
                unsigned char *out = rgba + 4 * ((size_t)y * at->mWidth + x);
                out[0] = texel->r, out[1] = texel->g, out[2] = texel->b, out[3] = texel->a;
            }
        bool made = texture_from_pixels(t, name, (int)at->mWidth, (int)at->mHeight, rgba);
        free(rgba);
        return made;
    }
    char beside[PATH_MAX];
    if (!path_beside(r->file, path, beside, sizeof beside)) {
        fprintf(stderr, "%s: image \"%s\": path too long\n", r->file, path);
        return false;
    }
    snprintf(name, sizeof name, "%s: image %s", r->file, beside);
    return texture_load_file(t, name, beside);
}

/* The base-colour texture material m names (glTF's baseColorTexture,
 * which assimp gives as both base colour and diffuse): its image's path
 * and wrap modes; false where it names none. */
static bool scene_gltf_texture_of(const struct aiMaterial *material, struct aiString *path, texture_wrap wrap[2]) {
    enum aiTextureMapMode modes[2] = {aiTextureMapMode_Wrap, aiTextureMapMode_Wrap};
    if (aiGetMaterialTexture(material, aiTextureType_BASE_COLOR, 0, path, NULL, NULL, NULL, NULL, modes, NULL) !=
            aiReturn_SUCCESS &&
        aiGetMaterialTexture(material, aiTextureType_DIFFUSE, 0, path, NULL, NULL, NULL, NULL, modes, NULL) !=
            aiReturn_SUCCESS)
        return false;
    for (int k = 0; k < 2; k++)
        wrap[k] = modes[k] == aiTextureMapMode_Mirror  ? TEXTURE_MIRRORED_REPEAT
                  : modes[k] == aiTextureMapMode_Clamp ? TEXTURE_CLAMP_TO_EDGE
                                                       : TEXTURE_REPEAT;
    return true;
}

/* Material m's base-colour texture, loaded on its first use, an image and
 * sampler that several materials name once; *index its place in the
 * scene's textures or SCENE_GLTF_UNTEXTURED. False after a line where its
 * image does not load. */
static bool scene_gltf_texture(scene_gltf_reader *r, unsigned m, int *index) {
    if (r->material_texture[m] != SCENE_GLTF_UNSEEN) {
        *index = r->material_texture[m];
        return true;
    }
    struct aiString path, other;
    texture_wrap wrap[2], other_wrap[2];
    *index = r->material_texture[m] = SCENE_GLTF_UNTEXTURED;
    if (!scene_gltf_texture_of(r->a->mMaterials[m], &path, wrap))
        return true;
    for (unsigned k = 0; k < r->a->mNumMaterials; k++)
        if (r->material_texture[k] >= 0 && scene_gltf_texture_of(r->a->mMaterials[k], &other, other_wrap) &&
            strcmp(other.data, path.data) == 0 && memcmp(wrap, other_wrap, sizeof wrap) == 0) {
            *index = r->material_texture[m] = r->material_texture[k];
            return true;
        }
    scene *s = r->s;
    texture *t = &s->textures[s->texture_count];
    if (!scene_gltf_image(r, path.data, t))
        return false;
    memcpy(t->wrap, wrap, sizeof t->wrap);
    *index = r->material_texture[m] = s->texture_count++;
    return true;
}

/* The material's alphaMode: MASK makes o a cut-out (scene_object), of
 * alphaCutoff (glTF's default 0.5) and the base colour's alpha; BLEND a
 * translucent caster of that alpha. */
static void scene_gltf_alpha(const struct aiMaterial *material, scene_object *o) {
    struct aiString mode;
    if (aiGetMaterialString(material, AI_MATKEY_GLTF_ALPHAMODE, &mode) != AI_SUCCESS)
        return;
    bool mask = strcmp(mode.data, "MASK") == 0, blend = strcmp(mode.data, "BLEND") == 0;
    if (!mask && !blend)
        return;
    struct aiColor4D base = {1, 1, 1, 1};
    float cutoff = SCENE_GLTF_ALPHA_CUTOFF;
    aiGetMaterialColor(material, AI_MATKEY_BASE_COLOR, &base);
    aiGetMaterialFloatArray(material, AI_MATKEY_GLTF_ALPHACUTOFF, &cutoff, NULL);
    o->base_alpha = isfinite(base.a) ? fminf(fmaxf(base.a, 0), 1) : 1;
    o->translucent = blend;
    if (mask)
        o->alpha_cutoff = isfinite(cutoff) ? fmaxf(cutoff, 0) : SCENE_GLTF_ALPHA_CUTOFF;
}

/* Whether the material is single-sided: glTF's doubleSided false, its
 * default (assimp's two-sided key, 0 where the file gives none). */
static bool scene_gltf_single_sided(const struct aiMaterial *material) {
    int two_sided = 0;
    aiGetMaterialInteger(material, AI_MATKEY_TWOSIDED, &two_sided);
    return !two_sided;
}

/* Mesh i of the file as an object placed by `world`. A mirroring
 * transform goes into the mesh, as a scene file's negative scale does
 * (scene_object's model keeps a positive determinant). */
static bool scene_gltf_object(scene_gltf_reader *r, const struct aiNode *node, unsigned i, mat4 world) {
    const struct aiMesh *am = r->a->mMeshes[i];
    if (!am->mNumFaces || !(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
        return true; /* points and lines: nothing to shade */
    if (!scene_reserve_object(r->s, r->capacity, r->file))
        return false;
    /* The material's texture first: what fails there leaves no mesh. */
    bool material = am->mMaterialIndex < r->a->mNumMaterials;
    int texture = SCENE_GLTF_UNTEXTURED;
    if (material && !scene_gltf_texture(r, am->mMaterialIndex, &texture))
        return false;
    scene_object *o = &r->s->objects[r->s->object_count];
    *o = (scene_object){.mesh_kind = SCENE_MESH_MODEL,
                        .color = {SCENE_GLTF_GREY, SCENE_GLTF_GREY, SCENE_GLTF_GREY},
                        .casts = r->casts,
                        .receives = r->receives};
    scene_gltf_name(r, node, o->name);
    char where[PATH_MAX + SCENE_NAME_MAX + 16];
    snprintf(where, sizeof where, "%s: node \"%s\"", r->file, o->name);
    if (!mesh_from_assimp(&o->mesh, where, am, &r->removed))
        return false;
    if (material) {
        mesh_material_color(r->a->mMaterials[am->mMaterialIndex], o->color);
        scene_gltf_alpha(r->a->mMaterials[am->mMaterialIndex], o);
    }
    o->single_sided = !r->prefix && (!material || scene_gltf_single_sided(r->a->mMaterials[am->mMaterialIndex]));
    if (texture >= 0 && !am->mTextureCoords[0])
        r->without_coordinates++;
    else if (texture >= 0)
        o->base_color = &r->s->textures[texture];
    scene_object_place(o, world);
    r->s->object_count++;
    return true;
}

static bool scene_gltf_objects(scene_gltf_reader *r, const struct aiNode *node, mat4 parent) {
    mat4 local, world;
    scene_gltf_matrix(&node->mTransformation, local);
    glm_mat4_mul(parent, local, world);
    for (unsigned k = 0; k < node->mNumMeshes; k++)
        if (node->mMeshes[k] < r->a->mNumMeshes && !scene_gltf_object(r, node, node->mMeshes[k], world))
            return false;
    for (unsigned i = 0; i < node->mNumChildren; i++)
        if (!scene_gltf_objects(r, node->mChildren[i], world))
            return false;
    return true;
}

/* ---- the camera ---- */

/* The sphere about every object's world bounds: its centre and radius
 * (every object of a glTF scene receives, so the receivers' bounds are
 * all of them). */
static float scene_gltf_sphere(const scene *s, vec3 centre) {
    vec3 lo, hi;
    scene_receivers_bounds(s, lo, hi);
    glm_vec3_center(lo, hi, centre);
    return fmaxf(0.5f * glm_vec3_distance(lo, hi), FLT_MIN);
}

/* A camera that sees the bounds' sphere whole, from scene_gltf_fit_from. */
static void scene_gltf_fit_camera(const scene *s, scene_camera *c) {
    vec3 centre, from;
    float radius = scene_gltf_sphere(s, centre);
    float distance = SCENE_GLTF_FIT_ROOM * radius / sinf(glm_rad(0.5f * SCENE_GLTF_FIT_FOV_DEG));
    glm_vec3_normalize_to((float *)scene_gltf_fit_from, from);
    *c = (scene_camera){.up = {0, 1, 0},
                        .fov_deg = SCENE_GLTF_FIT_FOV_DEG,
                        .near_plane = SCENE_GLTF_FIT_NEAR_SHARE * (distance - radius),
                        .far_plane = SCENE_GLTF_FIT_FAR_SHARE * (distance + radius)};
    glm_vec3_copy(centre, c->target);
    glm_vec3_copy(centre, c->position);
    glm_vec3_muladds(from, distance, c->position);
}

/* Camera `index` of the file, where its node places it. assimp 5.2's glTF
 * reader stores yfov times the aspect ratio as the horizontal field of
 * view, and 0 for an orthographic camera, which is taken as a fitted
 * one's field of view (said once). */
static bool scene_gltf_camera(const scene_gltf_reader *r, unsigned index, scene_camera *c) {
    const struct aiCamera *ac = r->a->mCameras[index];
    vec3 look;
    scene_gltf_place(r->a, ac->mName.data, ac->mPosition, ac->mLookAt, ac->mUp, c->position, look, c->up);
    float aspect = ac->mAspect > 0 ? ac->mAspect : 1;
    c->fov_deg = glm_deg(ac->mHorizontalFOV / aspect);
    if (!(ac->mHorizontalFOV > 0)) {
        fprintf(stderr, "%s: camera %u is orthographic: taken as a perspective camera of %g degrees\n", r->file,
                index, SCENE_GLTF_FIT_FOV_DEG);
        c->fov_deg = SCENE_GLTF_FIT_FOV_DEG;
    }
    c->near_plane = ac->mClipPlaneNear;
    c->far_plane = ac->mClipPlaneFar;
    if (!glm_vec3_norm2(look) || !isfinite(glm_vec3_norm2(look)) || !(c->fov_deg > 0 && c->fov_deg < 180) ||
        !(c->near_plane > 0 && c->far_plane > c->near_plane && isfinite(c->far_plane))) {
        fprintf(stderr, "%s: camera %u: no view (direction, field of view or depth range): not read\n", r->file,
                index);
        return false;
    }
    /* The target: where the view passes the scene's centre (its bounds
     * radius ahead where the centre lies behind), so that the origin
     * chosen from it (scene_choose_origin) stays the world's for a
     * camera near the scene. */
    vec3 centre, to_centre;
    float radius = scene_gltf_sphere(r->s, centre);
    glm_vec3_sub(centre, c->position, to_centre);
    glm_vec3_normalize(look);
    float ahead = glm_vec3_dot(to_centre, look);
    glm_vec3_copy(c->position, c->target);
    glm_vec3_muladds(look, ahead > 0 ? ahead : radius, c->target);
    vec3 side;
    glm_vec3_cross(look, c->up, side);
    if (!(glm_vec3_norm2(side) > 0))
        glm_vec3_copy((vec3){0, 1, 0}, c->up);
    return true;
}

/* ---- lights ---- */

/* assimp 5.2 drops KHR_lights_punctual's "range", so the file's own JSON
 * document is read for it: a .gltf's text, or a .glb's first chunk
 * (little-endian: its header's magic, version and length, then each
 * chunk's length and type). */
#define SCENE_GLTF_MAX_DOCUMENT_BYTES (256u << 20)
#define SCENE_GLTF_GLB_MAGIC 0x46546c67u /* "glTF" */
#define SCENE_GLTF_GLB_JSON 0x4e4f534au  /* "JSON" */
#define SCENE_GLTF_GLB_HEADER_BYTES 20   /* the file's header and the first chunk's */

static uint32_t scene_gltf_u32(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* The file's JSON document, or NULL after a line. */
static cJSON *scene_gltf_document(const char *path) {
    FILE *f = fopen(path, "rb");
    unsigned char header[SCENE_GLTF_GLB_HEADER_BYTES];
    if (!f) {
        fprintf(stderr, "%s: cannot open to read its lights' ranges\n", path);
        return NULL;
    }
    size_t got = fread(header, 1, sizeof header, f);
    bool binary = got >= 4 && scene_gltf_u32(header) == SCENE_GLTF_GLB_MAGIC;
    size_t length = 0;
    if (binary) {
        length = got == sizeof header && scene_gltf_u32(header + 16) == SCENE_GLTF_GLB_JSON
                     ? scene_gltf_u32(header + 12)
                     : SIZE_MAX;
    } else if (fseek(f, 0, SEEK_END) == 0) {
        long size = ftell(f);
        length = size >= 0 ? (size_t)size : SIZE_MAX;
        rewind(f);
    }
    char *text = length <= SCENE_GLTF_MAX_DOCUMENT_BYTES ? malloc(length + 1) : NULL;
    bool read = text && fread(text, 1, length, f) == length;
    fclose(f);
    cJSON *document = read ? cJSON_ParseWithLength(text, length) : NULL;
    free(text);
    if (!document)
        fprintf(stderr, "%s: its JSON document (%zu bytes) does not read as JSON: no lights' ranges\n", path, length);
    return document;
}

/* The range the file gives the light of the node assimp names `name`
 * (an unnamed node "nodes_K"): 0 where it gives none, a number not above
 * 0 said and taken as none (the light reaches everywhere). */
static float scene_gltf_light_range(const char *file, const cJSON *document, const char *name) {
    const cJSON *nodes = cJSON_GetObjectItemCaseSensitive(document, "nodes");
    const cJSON *lights = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(document, "extensions"),
                                         "KHR_lights_punctual"),
        "lights");
    int k = 0;
    for (const cJSON *node = nodes ? nodes->child : NULL; node; node = node->next, k++) {
        const cJSON *node_name = cJSON_GetObjectItemCaseSensitive(node, "name");
        char id[32];
        snprintf(id, sizeof id, "nodes_%d", k);
        if (strcmp(cJSON_IsString(node_name) && node_name->valuestring[0] ? node_name->valuestring : id, name) != 0)
            continue;
        const cJSON *light = cJSON_GetObjectItemCaseSensitive(
            cJSON_GetObjectItemCaseSensitive(cJSON_GetObjectItemCaseSensitive(node, "extensions"),
                                             "KHR_lights_punctual"),
            "light");
        const cJSON *range =
            cJSON_IsNumber(light)
                ? cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(lights, light->valueint), "range")
                : NULL;
        if (!range)
            return 0;
        if (cJSON_IsNumber(range) && isfinite(range->valuedouble) && range->valuedouble > 0 &&
            range->valuedouble <= FLT_MAX)
            return (float)range->valuedouble;
        fprintf(stderr, "%s: the light of node \"%s\": its range is not a number above 0: it reaches everywhere\n",
                file, name);
        return 0;
    }
    return 0;
}

/* Light `index` of the file into l, where its node places it (false:
 * not a punctual light). Its colour is the file's (assimp's: times its
 * intensity), scaled later. */
static bool scene_gltf_light(const scene_gltf_reader *r, unsigned index, scene_light *l) {
    const struct aiLight *al = r->a->mLights[index];
    *l = (scene_light){.color = {al->mColorDiffuse.r, al->mColorDiffuse.g, al->mColorDiffuse.b}, .intensity = 1};
    vec3 up;
    scene_gltf_place(r->a, al->mName.data, al->mPosition, al->mDirection, al->mUp, l->position, l->direction, up);
    glm_vec3_normalize(l->direction);
    switch (al->mType) {
    case aiLightSource_DIRECTIONAL: l->type = SCENE_LIGHT_DIRECTIONAL; break;
    case aiLightSource_POINT: l->type = SCENE_LIGHT_POINT; break;
    case aiLightSource_SPOT:
        l->type = SCENE_LIGHT_SPOT;
        l->outer_angle_deg = fminf(glm_deg(al->mAngleOuterCone), SCENE_GLTF_MAX_SPOT_DEG);
        l->inner_angle_deg = fminf(glm_deg(al->mAngleInnerCone), l->outer_angle_deg);
        break;
    default:
        fprintf(stderr, "%s: light %u is not a punctual light (type %d): left out\n", r->file, index, al->mType);
        return false;
    }
    return true;
}

/* The file's lights, the first SCENE_MAX_LIGHTS (the rest said once),
 * with their ranges, their colours scaled so that the brightest channel of any is 1: the
 * lighting model has no falloff, so glTF's physical intensities keep only
 * their ratios. */
static void scene_gltf_lights(const scene_gltf_reader *r) {
    scene *s = r->s;
    float brightest = 0;
    cJSON *document = r->a->mNumLights ? scene_gltf_document(r->file) : NULL;
    for (unsigned i = 0; i < r->a->mNumLights && s->light_count < SCENE_MAX_LIGHTS; i++) {
        scene_light *l = &s->lights[s->light_count];
        if (!scene_gltf_light(r, i, l))
            continue;
        if (l->type != SCENE_LIGHT_DIRECTIONAL && document)
            l->range = scene_gltf_light_range(r->file, document, r->a->mLights[i]->mName.data);
        brightest = fmaxf(brightest, glm_vec3_max(l->color));
        s->light_count++;
    }
    cJSON_Delete(document);
    if (r->a->mNumLights > SCENE_MAX_LIGHTS)
        fprintf(stderr, "%s: %u lights: the first %d taken\n", r->file, r->a->mNumLights, SCENE_MAX_LIGHTS);
    for (int l = 0; l < s->light_count && brightest > 0; l++)
        glm_vec3_scale(s->lights[l].color, 1 / brightest, s->lights[l].color);
}

/* ---- the scene ---- */

/* Everything relative to the origin scene_choose_origin picks from the
 * camera. */
static void scene_gltf_rebase(scene *s) {
    scene_choose_origin(&s->camera, s->origin);
    for (int k = 0; k < 3; k++) {
        s->camera.position[k] = (float)(s->camera.position[k] - s->origin[k]);
        s->camera.target[k] = (float)(s->camera.target[k] - s->origin[k]);
        for (int l = 0; l < s->light_count; l++)
            s->lights[l].position[k] = (float)(s->lights[l].position[k] - s->origin[k]);
        for (int i = 0; i < s->object_count; i++)
            s->objects[i].model[3][k] = (float)(s->objects[i].model[3][k] - s->origin[k]);
    }
}

/* The file's objects, placed by `model`, after those s has; what was
 * left out or drawn otherwise said once. */
static bool scene_gltf_read_objects(scene_gltf_reader *r, mat4 model) {
    int before = r->s->object_count;
    if (!scene_gltf_objects(r, r->a->mRootNode, model))
        return false;
    if (r->s->object_count == before) {
        fprintf(stderr, "%s: no triangles in any node's mesh\n", r->file);
        return false;
    }
    if (r->removed.degenerate + r->removed.non_finite > 0)
        fprintf(stderr, "warning: %s: removed %u degenerate and %u non-finite triangles from its meshes\n", r->file,
                r->removed.degenerate, r->removed.non_finite);
    if (r->without_coordinates)
        fprintf(stderr, "%s: %u textured meshes have no texture coordinates: their base colour alone\n", r->file,
                r->without_coordinates);
    return true;
}

static bool scene_gltf_read(scene_gltf_reader *r) {
    scene *s = r->s;
    mat4 identity = GLM_MAT4_IDENTITY_INIT;
    if (!scene_gltf_read_objects(r, identity))
        return false;
    glm_vec3_fill(s->ambient, SCENE_DEFAULT_AMBIENT);
    if (r->a->mNumCameras == 0 || !scene_gltf_camera(r, r->camera, &s->camera)) {
        fprintf(stderr, "%s: no camera: one fitted to the scene's bounds\n", r->file);
        scene_gltf_fit_camera(s, &s->camera);
    }
    scene_gltf_lights(r);
    if (s->light_count == 0) {
        fprintf(stderr, "%s: no light: a sun from above added\n", r->file);
        s->lights[s->light_count++] =
            (scene_light){.type = SCENE_LIGHT_DIRECTIONAL,
                          .direction = {scene_gltf_fit_sun[0], scene_gltf_fit_sun[1], scene_gltf_fit_sun[2]},
                          .color = {1, 1, 1},
                          .intensity = 1};
        glm_vec3_normalize(s->lights[0].direction);
    }
    scene_gltf_rebase(s);
    return true;
}

/* Whether the file has camera `camera`, said where it has not. Camera 0
 * of a file without cameras is the fitted one. */
static bool scene_gltf_has_camera(const char *path, const struct aiScene *a, int camera) {
    if (camera == 0 || (unsigned)camera < a->mNumCameras)
        return true;
    if (a->mNumCameras == 0)
        fprintf(stderr, "%s: --camera %d: the file has no camera (camera 0 is fitted to its bounds)\n", path, camera);
    else if (a->mNumCameras == 1)
        fprintf(stderr, "%s: --camera %d: the file has camera 0 only\n", path, camera);
    else
        fprintf(stderr, "%s: --camera %d: the file has cameras 0 to %u\n", path, camera, a->mNumCameras - 1);
    return false;
}

/* Room in s->textures for a texture per material of the file (what it
 * may add: scene_reserve_textures), and r's table of them; false after a
 * line. */
static bool scene_gltf_reader_begin(scene_gltf_reader *r) {
    scene *s = r->s;
    unsigned materials = r->a->mNumMaterials;
    r->material_texture = malloc((materials + 1) * sizeof *r->material_texture);
    if (!r->material_texture) {
        fprintf(stderr, "%s: out of memory for %u materials\n", r->file, materials);
        return false;
    }
    if (!scene_reserve_textures(s, (size_t)materials + 1, r->file)) {
        free(r->material_texture);
        r->material_texture = NULL;
        return false;
    }
    for (unsigned m = 0; m < materials; m++)
        r->material_texture[m] = SCENE_GLTF_UNSEEN;
    return true;
}

/* Reads r's imported file, whole (placed NULL: nodes, cameras, lights) or
 * its objects placed by `placed` (an include), and releases the import. */
static bool scene_gltf_import(scene_gltf_reader *r, mat4 placed) {
    bool read = scene_gltf_reader_begin(r) && r->a->mRootNode &&
                (placed ? scene_gltf_read_objects(r, placed) : scene_gltf_read(r));
    free(r->material_texture);
    if (!r->a->mRootNode)
        fprintf(stderr, "%s: no node\n", r->file);
    aiReleaseImport(r->a);
    return read;
}

bool scene_load_gltf(scene *s, const char *path, int camera) {
    *s = (scene){0};
    const struct aiScene *a = mesh_import_graph(path);
    if (!a)
        return false;
    if (!scene_gltf_has_camera(path, a, camera)) {
        aiReleaseImport(a);
        return false;
    }
    int capacity = 0;
    scene_gltf_reader r = {.file = path,
                           .a = a,
                           .s = s,
                           .camera = (unsigned)camera,
                           .capacity = &capacity,
                           .casts = true,
                           .receives = true};
    bool read = scene_gltf_import(&r, NULL);
    if (!read)
        scene_free(s);
    return read;
}

bool scene_include_gltf(scene *s, int *capacity, const char *path, const float model[4][4], const char *prefix,
                        bool casts, bool receives) {
    const struct aiScene *a = mesh_import_graph(path);
    if (!a)
        return false;
    scene_gltf_reader r = {
        .file = path, .a = a, .s = s, .capacity = capacity, .prefix = prefix, .casts = casts, .receives = receives};
    mat4 placed;
    memcpy(placed, model, sizeof placed);
    return scene_gltf_import(&r, placed);
}
