/* mesh_file: model files through assimp (mesh_load_file, mesh.h): the
 * header checks that keep assimp from reading what would crash it or
 * exhaust memory, the import, and the copy into a mesh. */
#include "mesh.h"

#include <assimp/cimport.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <ctype.h>
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "mesh_assimp.h"
#include "mesh_build.h"

/* A header word longer than this is no count or keyword of any header read
 * here. */
#define MESH_HEADER_WORD_LENGTH 63
#define MESH_HEADER_WORD_MAX (MESH_HEADER_WORD_LENGTH + 1)
#define MESH_TEXT(x) MESH_TEXT_(x)
#define MESH_TEXT_(x) #x
/* The least a record of a text format takes: one digit and a separator. */
#define MESH_MIN_TEXT_RECORD_BYTES 2

/* assimp's JoinIdenticalVertices and GenSmoothNormals rely on a spatial sort
 * that NaN or infinite positions break: unrelated vertices then get joined.
 * Files with such positions skip those steps; mesh_sanitize drops the bad
 * triangles and computes the missing normals itself. */
static bool mesh_scene_positions_finite(const struct aiScene *scene) {
    for (unsigned i = 0; i < scene->mNumMeshes; i++) {
        const struct aiMesh *am = scene->mMeshes[i];
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            const struct aiVector3D *p = &am->mVertices[v];
            if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z))
                return false;
        }
    }
    return true;
}

static unsigned mesh_count_assimp_triangles(const struct aiMesh *am) {
    unsigned count = 0;
    for (unsigned f = 0; f < am->mNumFaces; f++)
        count += am->mFaces[f].mNumIndices == 3;
    return count;
}

/* The colour a material of the file gives (see mesh_material): false for
 * assimp's stand-in and for a colour that is none. */
bool mesh_material_color(const struct aiMaterial *material, float color[3]) {
    struct aiString name;
    struct aiColor4D c;
    if (aiGetMaterialString(material, AI_MATKEY_NAME, &name) != AI_SUCCESS || name.length == 0 ||
        strcmp(name.data, AI_DEFAULT_MATERIAL_NAME) == 0)
        return false;
    if (aiGetMaterialColor(material, AI_MATKEY_BASE_COLOR, &c) != AI_SUCCESS &&
        aiGetMaterialColor(material, AI_MATKEY_COLOR_DIFFUSE, &c) != AI_SUCCESS)
        return false;
    const float rgb[3] = {c.r, c.g, c.b};
    for (int k = 0; k < 3; k++)
        if (!(isfinite(rgb[k]) && rgb[k] >= 0))
            return false;
    memcpy(color, rgb, sizeof rgb);
    return true;
}

/* The model's colour: of the materials' colours, the one that covers the
 * most triangles (mesh_material's rule). */
static bool mesh_find_material(const char *path, const struct aiScene *scene, mesh_material *out) {
    unsigned n = scene->mNumMaterials;
    unsigned long long *triangles = calloc((size_t)n + 1, sizeof *triangles); /* + 1: there may be none */
    float(*colors)[3] = calloc((size_t)n + 1, sizeof *colors);
    bool *colored = calloc((size_t)n + 1, sizeof *colored);
    bool ok = triangles && colors && colored;
    for (unsigned i = 0; ok && i < scene->mNumMeshes; i++)
        if (scene->mMeshes[i]->mMaterialIndex < n)
            triangles[scene->mMeshes[i]->mMaterialIndex] += mesh_count_assimp_triangles(scene->mMeshes[i]);
    for (unsigned i = 0; ok && i < n; i++) {
        colored[i] = mesh_material_color(scene->mMaterials[i], colors[i]);
        out->textured += aiGetMaterialTextureCount(scene->mMaterials[i], aiTextureType_BASE_COLOR) +
                             aiGetMaterialTextureCount(scene->mMaterials[i], aiTextureType_DIFFUSE) >
                         0;
    }
    unsigned long long best = 0;
    for (unsigned i = 0; ok && i < n; i++) {
        unsigned long long covered = 0;
        for (unsigned j = 0; colored[i] && j < n; j++)
            covered += colored[j] && memcmp(colors[i], colors[j], sizeof colors[i]) == 0 ? triangles[j] : 0;
        if (covered > best) {
            best = covered;
            out->has_color = true;
            memcpy(out->color, colors[i], sizeof out->color);
        }
    }
    free(triangles);
    free(colors);
    free(colored);
    return ok || mesh_fail(NULL, path, "out of memory for %u materials", n);
}

/* Merges the triangles of `count` assimp meshes; points and lines are
 * dropped, with the vertices only they use. */
static bool mesh_copy_assimp_triangles(mesh *m, const char *path, struct aiMesh *const *meshes, unsigned count) {
    size_t vertex_count = 0, triangle_count = 0;
    for (unsigned i = 0; i < count; i++) {
        unsigned triangles = mesh_count_assimp_triangles(meshes[i]);
        triangle_count += triangles;
        if (triangles)
            vertex_count += meshes[i]->mNumVertices;
    }
    if (triangle_count == 0)
        return mesh_fail(m, path, "no triangles");
    if (!mesh_alloc(m, path, vertex_count, 3 * triangle_count))
        return false;
    for (unsigned i = 0; i < count; i++) {
        const struct aiMesh *am = meshes[i];
        if (!mesh_count_assimp_triangles(am))
            continue;
        uint32_t first = m->vertex_count;
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            const struct aiVector3D *p = &am->mVertices[v];
            /* A zero normal marks it missing: mesh_sanitize computes one. */
            const struct aiVector3D n = am->mNormals ? am->mNormals[v] : (struct aiVector3D){0, 0, 0};
            uint32_t pushed =
                mesh_push_vertex(m, (const float[3]){p->x, p->y, p->z}, (const float[3]){n.x, n.y, n.z});
            if (am->mTextureCoords[0]) {
                m->vertices[pushed].uv[0] = am->mTextureCoords[0][v].x;
                m->vertices[pushed].uv[1] = am->mTextureCoords[0][v].y;
            }
        }
        for (unsigned f = 0; f < am->mNumFaces; f++) {
            const struct aiFace *face = &am->mFaces[f];
            if (face->mNumIndices != 3)
                continue;
            uint32_t corner[3];
            for (int k = 0; k < 3; k++) {
                /* An index past this mesh's vertices becomes one past all of
                 * them, so mesh_sanitize drops the triangle. */
                corner[k] = face->mIndices[k] < am->mNumVertices ? first + face->mIndices[k] : UINT32_MAX;
            }
            mesh_push_triangle(m, corner[0], corner[1], corner[2]);
        }
    }
    return true;
}

/* assimp 5.2's OBJ reader miscounts the faces of a line statement ("l")
 * with a single vertex, then writes past its face array (found by fuzzing;
 * the OBJ reader's overflows were fixed upstream after Debian 12's 5.2.4).
 * Such files are refused before assimp reads them. Returns the offending
 * line's number, or 0. */
static long mesh_obj_single_vertex_line(const char *path) {
    const char *extension = strrchr(path, '.');
    FILE *f = extension && strcasecmp(extension, ".obj") == 0 ? fopen(path, "r") : NULL;
    if (!f)
        return 0;
    char *text = NULL;
    size_t capacity = 0;
    long number = 0, found = 0;
    while (!found && getline(&text, &capacity, f) != -1) {
        number++;
        const char *statement = text + strspn(text, " \t");
        bool is_line = statement[0] == 'l' && (statement[1] == '\0' || isspace((unsigned char)statement[1]));
        char second_vertex[2];
        if (is_line && sscanf(statement + 1, "%*s %1s", second_vertex) != 1)
            found = number;
    }
    free(text);
    fclose(f);
    return found;
}

/* What a header announces, against what the file can hold. */
typedef struct mesh_claim {
    char what[160];               /* "8 vertices and 6 faces" */
    unsigned long long min_bytes; /* the least the announced records take (saturating) */
    long long available;          /* bytes after the header */
} mesh_claim;

/* Adds `count` records of at least `bytes` each, saturating: a count can
 * be any 20-digit number. */
static void mesh_claim_add(mesh_claim *c, unsigned long long count, unsigned long long bytes) {
    if (bytes && count > (ULLONG_MAX - c->min_bytes) / bytes) {
        c->min_bytes = ULLONG_MAX;
    } else {
        c->min_bytes += count * bytes;
    }
}

/* The next whitespace-separated word, past '#' comments to the end of
 * their line (OFF); false at the end of the file. */
static bool mesh_header_word(FILE *f, char word[MESH_HEADER_WORD_MAX]) {
    while (fscanf(f, " %" MESH_TEXT(MESH_HEADER_WORD_LENGTH) "s", word) == 1) {
        if (word[0] != '#')
            return true;
        int c;
        while ((c = fgetc(f)) != EOF && c != '\n')
            continue;
    }
    return false;
}

static bool mesh_header_count(FILE *f, unsigned long long *count) {
    char word[MESH_HEADER_WORD_MAX], *end;
    if (!mesh_header_word(f, word) || !isdigit((unsigned char)word[0]))
        return false;
    errno = 0;
    *count = strtoull(word, &end, 10);
    return *end == '\0' && errno == 0;
}

/* [ST][C][N][4][n]OFF, the keyword of an OFF file. */
static bool mesh_is_off_keyword(const char *word) {
    size_t length = strlen(word);
    return length >= 3 && strcmp(word + length - 3, "OFF") == 0 && strspn(word, "STCN4n") == length - 3;
}

/* An OFF file: the keyword (optional in the format, so a file named .off
 * may start with the counts), with nOFF the dimension, then the vertex and
 * face counts; every vertex and face is a line of at least a digit and a
 * line end. False when the header is not OFF's or not whole (assimp then
 * says what is wrong). */
static bool mesh_read_off_claim(FILE *f, bool named_off, mesh_claim *c) {
    char word[MESH_HEADER_WORD_MAX];
    unsigned long long dimension, vertices, faces;
    if (!mesh_header_word(f, word))
        return false;
    bool keyword = mesh_is_off_keyword(word);
    if (keyword && strchr(word, 'n') && !mesh_header_count(f, &dimension))
        return false;
    if (keyword) {
        if (!mesh_header_count(f, &vertices))
            return false;
    } else {
        char *end;
        errno = 0;
        vertices = strtoull(word, &end, 10);
        if (!named_off || !isdigit((unsigned char)word[0]) || *end != '\0' || errno != 0)
            return false;
    }
    if (!mesh_header_count(f, &faces))
        return false;
    snprintf(c->what, sizeof c->what, "%llu vertices and %llu faces", vertices, faces);
    mesh_claim_add(c, vertices, MESH_MIN_TEXT_RECORD_BYTES);
    mesh_claim_add(c, faces, MESH_MIN_TEXT_RECORD_BYTES);
    return true;
}

/* A PLY header: "element NAME COUNT" lines, each followed by its
 * "property" lines, up to "end_header". An element of an ASCII file is a
 * line of at least a digit and a line end; of a binary one, at least a
 * byte per property. */
static bool mesh_read_ply_claim(FILE *f, mesh_claim *c) {
    char word[MESH_HEADER_WORD_MAX], name[MESH_HEADER_WORD_MAX] = "";
    unsigned long long count = 0, properties = 0;
    bool ascii = false;
    size_t used = 0;
    if (!mesh_header_word(f, word) || strcmp(word, "ply") != 0)
        return false;
    for (;;) {
        if (!mesh_header_word(f, word))
            return false;
        bool last = strcmp(word, "end_header") == 0, element = strcmp(word, "element") == 0;
        if ((last || element) && count) {
            /* The element before this line is complete. */
            mesh_claim_add(c, count, ascii ? (properties ? MESH_MIN_TEXT_RECORD_BYTES : 0) : properties);
            int n =
                snprintf(c->what + used, sizeof c->what - used, "%s%llu %s", used ? ", " : "elements (", count, name);
            used = n > 0 && (size_t)n < sizeof c->what - used ? used + (size_t)n : used;
        }
        if (last)
            break;
        if (element) {
            properties = 0;
            if (!mesh_header_word(f, name) || !mesh_header_count(f, &count))
                return false;
            continue;
        }
        if (strcmp(word, "format") == 0) {
            if (!mesh_header_word(f, word))
                return false;
            ascii = strcmp(word, "ascii") == 0;
        }
        properties += strcmp(word, "property") == 0;
        int ch; /* the rest of the line: types, names, versions, comments */
        while ((ch = fgetc(f)) != EOF && ch != '\n')
            continue;
    }
    if (used == 0) {
        snprintf(c->what, sizeof c->what, "no elements");
    } else if (used + 1 < sizeof c->what) {
        strcpy(c->what + used, ")");
    }
    int ch;
    while ((ch = fgetc(f)) != EOF && ch != '\n')
        continue;
    return true;
}

/* assimp 5.2's OFF reader allocates the arrays its header claims (counts
 * wrapped to 32 bits) with new[], whose constructors touch every byte,
 * before it reads one vertex, and hands back a scene of that many
 * vertices, nearly all zero: OutOfMemory.off (309 bytes) claims
 * 353535235358 vertices, 1347917086 after wrapping, 16 GB that the kernel
 * grants and then kills the process for; a claim that fits in memory is
 * post-processed at length (250 M vertices from a 180-byte file: many
 * seconds and gigabytes, then a picture of a cube). Its PLY reader allocates
 * for the claimed elements likewise (std::bad_alloc under a 4 GB address
 * space for 2 G vertices in 200 bytes). No
 * import property bounds it, and it happens inside aiImportFile, so the
 * claims are checked against the file's size here first. Returns false
 * after the error. */
static bool mesh_check_header_claims(mesh *m, const char *path, long long size) {
    const char *extension = strrchr(path, '.');
    bool named_off = extension && strcasecmp(extension, ".off") == 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return true; /* assimp says why */
    mesh_claim claim = {.available = 0};
    const char *format = "OFF";
    bool claimed = mesh_read_off_claim(f, named_off, &claim);
    if (!claimed) {
        format = "PLY";
        claim = (mesh_claim){.available = 0};
        rewind(f);
        claimed = mesh_read_ply_claim(f, &claim);
    }
    long position = ftell(f);
    fclose(f);
    if (!claimed || position < 0)
        return true;
    claim.available = size - position;
    /* The last record may end without a line end. */
    if (claim.min_bytes <= (unsigned long long)claim.available + 1)
        return true;
    return mesh_fail(m, path,
                     "%s header claims %s: at least %llu bytes, but the file holds %lld after the "
                     "header (refused before assimp allocates for them)",
                     format, claim.what, claim.min_bytes, claim.available);
}

/* The triangles and vertices of the imported scene (triangulated, node
 * transforms applied: instances are copies by now), within the limits:
 * checked before the post-processing that welds and smooths and before our
 * arrays, which take time and memory in proportion. */
static bool mesh_check_counts(mesh *m, const char *path, const struct aiScene *scene) {
    unsigned long long vertices = 0, triangles = 0;
    for (unsigned i = 0; i < scene->mNumMeshes; i++) {
        vertices += scene->mMeshes[i]->mNumVertices;
        triangles += mesh_count_assimp_triangles(scene->mMeshes[i]);
    }
    if (triangles <= MESH_MAX_TRIANGLES && vertices <= MESH_MAX_VERTICES)
        return true;
    return mesh_fail(m, path,
                     "%llu triangles and %llu vertices, over the limit of %d triangles and %d vertices "
                     "a model may have",
                     triangles, vertices, MESH_MAX_TRIANGLES, MESH_MAX_VERTICES);
}

/* The determinant of a node's own transform (its 3x3 part), in double. */
static double mesh_node_determinant(const struct aiMatrix4x4 *t) {
    return (double)t->a1 * ((double)t->b2 * t->c3 - (double)t->b3 * t->c2) -
           (double)t->a2 * ((double)t->b1 * t->c3 - (double)t->b3 * t->c1) +
           (double)t->a3 * ((double)t->b1 * t->c2 - (double)t->b2 * t->c1);
}

/* Some mesh lies under a mirroring transform: an odd number of the nodes
 * from the root to its own have a negative determinant (the determinant of
 * the composed transform is their product, so the signs are all it takes). */
static bool mesh_node_mirrors(const struct aiNode *node, bool mirrored_above) {
    bool mirrored = mirrored_above != (mesh_node_determinant(&node->mTransformation) < 0);
    if (mirrored && node->mNumMeshes)
        return true;
    for (unsigned i = 0; i < node->mNumChildren; i++)
        if (mesh_node_mirrors(node->mChildren[i], mirrored))
            return true;
    return false;
}

/* aiProcess_PreTransformVertices bakes each node's transform into its
 * meshes but, merging them by material, keeps the winding of a mirrored
 * one: its triangles turn clockwise seen from outside (inside out). With
 * AI_CONFIG_PP_PTV_KEEP_HIERARCHY the step instead transforms each
 * instance on its own (copies for a mesh used by nodes of differing
 * transforms) and reverses the winding where the determinant is negative;
 * it merges nothing, so meshes are welded and smoothed each on its own.
 * So that every other file loads exactly as it always has, that mode is
 * for files with a mirrored instance only, found by reading the file as it
 * stands first (its read errors are the import's own). An import without
 * the step (a node graph kept) reads the file once. */
static const struct aiScene *mesh_import(const char *path, unsigned flags) {
    if (!(flags & aiProcess_PreTransformVertices))
        return aiImportFile(path, flags);
    const struct aiScene *read = aiImportFile(path, 0);
    if (!read)
        return NULL;
    bool mirrored = mesh_node_mirrors(read->mRootNode, false);
    aiReleaseImport(read);
    struct aiPropertyStore *properties = aiCreatePropertyStore();
    aiSetImportPropertyInteger(properties, AI_CONFIG_PP_PTV_KEEP_HIERARCHY, mirrored);
    const struct aiScene *scene = aiImportFileExWithProperties(path, flags, NULL, properties);
    aiReleasePropertyStore(properties);
    return scene;
}

/* The file imported (flags: assimp's steps, then welded and smoothed), or
 * NULL after "PATH: problem" (m emptied, when given). */
static const struct aiScene *mesh_import_checked(mesh *m, const char *path, unsigned flags) {
    /* assimp reports a directory as an unknown format, or as an empty OBJ:
     * say what it is instead. */
    struct stat info;
    if (stat(path, &info) != 0)
        return mesh_fail(m, path, "cannot open: %s", strerror(errno)), NULL;
    if (!S_ISREG(info.st_mode))
        return mesh_fail(m, path, "not a regular file"), NULL;
    long bad_line = mesh_obj_single_vertex_line(path);
    if (bad_line) {
        mesh_fail(m, path,
                  "line %ld: a line statement needs 2 or more vertices "
                  "(refused: assimp 5.2 overflows a buffer on it)",
                  bad_line);
        return NULL;
    }
    if (!mesh_check_header_claims(m, path, (long long)info.st_size))
        return NULL;

    /* The counts are checked after these steps, not before them from a raw
     * import: a step that fails inside the import is an error, while one
     * failing in aiApplyPostProcessing crashes assimp 5.2 in the Importer's
     * destructor (AC/nosurfaces.ac of assimp-testmodels). */
    const struct aiScene *scene = mesh_import(path, flags);
    if (scene && !mesh_check_counts(m, path, scene)) {
        aiReleaseImport(scene);
        return NULL;
    }
    if (scene && mesh_scene_positions_finite(scene)) {
        scene = aiApplyPostProcessing(scene, aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals);
    }
    if (!scene) {
        const char *why = aiGetErrorString();
        mesh_fail(m, path, "%s", why && *why ? why : "assimp could not import it");
    }
    return scene;
}

bool mesh_load_file(mesh *m, const char *path, mesh_material *material) {
    *m = (mesh){0};
    if (material)
        *material = (mesh_material){0};
    const struct aiScene *scene =
        mesh_import_checked(m, path, aiProcess_Triangulate | aiProcess_PreTransformVertices | aiProcess_SortByPType);
    if (!scene)
        return false;
    bool copied = (!material || mesh_find_material(path, scene, material)) &&
                  mesh_copy_assimp_triangles(m, path, scene->mMeshes, scene->mNumMeshes);
    aiReleaseImport(scene);
    return copied && mesh_sanitize(m, path);
}

const struct aiScene *mesh_import_graph(const char *path) {
    return mesh_import_checked(NULL, path, aiProcess_Triangulate | aiProcess_SortByPType);
}

bool mesh_from_assimp(mesh *m, const char *name, const struct aiMesh *am, mesh_removed *removed) {
    *m = (mesh){0};
    struct aiMesh *one[] = {(struct aiMesh *)am};
    return mesh_copy_assimp_triangles(m, name, one, 1) && mesh_sanitize_quietly(m, name, removed);
}
