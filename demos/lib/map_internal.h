/* map_internal: what the files of the shadow-map library (map.c,
 * map_cull.c, map_fit.c, map_moments.c, map_overlay.c) share beyond the
 * public map.h: the renderer's programs and caches, the constants the
 * shaders take as defines, and the helpers between its passes. The tests
 * include it to check those parts on their own.
 */
#ifndef MAP_INTERNAL_H
#define MAP_INTERNAL_H

#include "map.h"

/* The texel-size heat map's ends, log2 of a texel's size in pixels: blue
 * at a quarter pixel and below, green at one, red at 32 and more. The
 * shaders (texel_heat.glsl) and the legend take them from here. */
#define MAP_HEAT_LOG2_MIN (-2)
#define MAP_HEAT_LOG2_MAX 5
/* The penumbra overlay's ends, log2 of the penumbra radius PCSS estimated
 * (world units): the texel-size ramp moved to start at 1/64 unit (blue),
 * green at 1/16, red at 2 and more. */
#define MAP_PENUMBRA_LOG2_MIN (-6)
#define MAP_PENUMBRA_LOG2_MAX (MAP_PENUMBRA_LOG2_MIN + MAP_HEAT_LOG2_MAX - MAP_HEAT_LOG2_MIN)

/* The shape of the camera pass's kernel (the shaders' u_filter). The
 * C/GLSL contract: the kernel shapes, texel kinds and cube faces are C
 * enums passed to the shaders as defines (common/gl/shader.h); the shaders
 * compare with their names. */
typedef enum map_kernel {
    MAP_KERNEL_SINGLE,  /* one test: nearest or bilinear by the texture's filter */
    MAP_KERNEL_GRID,    /* N x N bilinear tests a texel apart (u_kernel: N) */
    MAP_KERNEL_POISSON, /* the rotated Poisson disc (u_kernel: its scale in texels) */
    MAP_KERNEL_TENT,    /* an N x N tent from ((N + 1)/2)^2 bilinear tests (u_kernel: N) */
} map_kernel;
/* The Poisson disc's scale: its unit circle is this many texels across,
 * the scale that misclassifies least on the standard scenes. Its points
 * reach radius 1.234 of that circle, so the taps span 3.7 texels (see
 * shaders/map.glsl). */
#define MAP_POISSON_SCALE_TEXELS 3

/* Soft shadows. An area light (radius > 0) with --soft pcss, the default,
 * is filtered by percentage-closer soft shadows instead of the kernel
 * (shaders/map_soft.glsl: a blocker search, the penumbra by similar
 * triangles, a filter of its width), its taps on the receiver's plane; the
 * blocker search reads the map's depths on unit MAP_DEPTH_UNITS +
 * light through r->depth_sampler (compare mode off). Its bit of the key's
 * soft_lights compiles that code in: a light of radius 0 runs the code it
 * always did. The blocker search's and the filter's taps, and the most
 * radius of either disc in texels, which caster culling allows for
 * (map_read_reach); the least is the hard default's disc's,
 * MAP_POISSON_SCALE_TEXELS / 2. */
#define MAP_SOFT_SEARCH_TAPS 16
#define MAP_SOFT_FILTER_TAPS 32
#define MAP_SOFT_MAX_TEXELS 48

/* What light i is in the camera pass (the shaders'
 * MAP_LIGHT_KIND_<i>): off, on without a map (nothing it reaches
 * receives: added unshadowed), with a 2D map, a cube map, an array map,
 * or a cube map's faces in the atlas (map.h, "Atlas"). */
typedef enum map_light_kind {
    MAP_LIGHT_OFF,
    MAP_LIGHT_UNSHADOWED,
    MAP_LIGHT_2D,
    MAP_LIGHT_CUBE,
    MAP_LIGHT_ARRAY,
    MAP_LIGHT_TILES
} map_light_kind;
/* Light i's kind, and its map's map_texel_kind, in bits
 * MAP_LIGHT_KIND_BITS i and up of a key's kinds and texel_kinds. */
#define MAP_LIGHT_KIND_BITS 3
_Static_assert(SHADER_PASS_LIGHTS *MAP_LIGHT_KIND_BITS <= 32, "a combination of kinds fits an unsigned");
/* The camera programs kept: the keys a run goes through (lights coming
 * into reach, a point light's warp falling back to a cube, the kernels a
 * lecturer or the benchmark tries) are compiled once each, the oldest
 * dropped beyond this many. */
#define MAP_CAMERA_PROGRAMS 16
/* Texture units, light i being slot i of the pass's light group
 * (render.h, "Light groups"): light i's map, of any kind, on unit i; the samplers a
 * program holds but does not read (an array's elements below the last one
 * used stay active) on one unit per sampler type after those, the
 * comparisons' at MAP_IDLE_UNITS + t, the depths' at
 * MAP_IDLE_UNITS + MAP_SAMPLER_TYPES + t: samplers of two
 * types on one unit would fail every draw. */
#define MAP_IDLE_UNITS SHADER_PASS_LIGHTS
/* A soft light's map is also read as depth (compare mode off, by
 * r->depth_sampler): light i's on unit MAP_DEPTH_UNITS + i, after
 * the idle units of the comparison and the depth samplers' types and the
 * base colour's (render.h's RENDER_BASE_COLOR_UNIT); a
 * moment filter's light reads its moments there (the same sampler
 * types). GL 3.3 promises 16 units, which hold the first light's depth
 * unit only: a light whose depth unit the GL lacks
 * (r->texture_units) is drawn hard (a moment filter's with one bilinear
 * test), and says so. */
#define MAP_SAMPLER_TYPES 3
_Static_assert(RENDER_BASE_COLOR_UNIT == MAP_IDLE_UNITS + 2 * MAP_SAMPLER_TYPES,
               "the base colour's unit follows the idle ones");
#define MAP_DEPTH_UNITS (RENDER_BASE_COLOR_UNIT + 1)
/* Light i's transmittance map (map.h, "Translucent casters") on unit
 * MAP_TRANSMIT_UNITS + i, after every light's depth unit; its sampler
 * types are the depths', whose idle units the unused elements share. A
 * light whose unit the GL lacks casts its translucent casters' whole
 * shadow, and says so. */
#define MAP_TRANSMIT_UNITS (MAP_DEPTH_UNITS + SHADER_PASS_LIGHTS)
/* The casters' hierarchy for the rays (a sampler2D) shares the idle unit
 * of the 2D maps' depths (sampler2D too, never read there): no unit
 * beyond GL 3.3's 16 is needed. */
#define MAP_RAY_UNIT (MAP_IDLE_UNITS + MAP_SAMPLER_TYPES)

/* What a camera program is compiled for (shaders/map.frag's
 * MAP_LIGHT_KIND_<i>, MAP_TEXEL_KIND_<i> and
 * MAP_PASS_*): whatever chooses code rather than a number, so
 * that a program holds only the code it runs. As uniforms every pixel
 * would run every choice's code: llvmpipe runs both sides of a branch,
 * masked. All unsigned: keys compare with memcmp. */
typedef struct map_camera_key {
    unsigned kinds, texel_kinds; /* per light (MAP_LIGHT_KIND_BITS) */
    unsigned shape, kernel;      /* map_kernel, N or the disc's scale */
    unsigned soft_lights;        /* bit i: light i is soft (map_soft.glsl) */
    unsigned moments;            /* map_moments of the filter */
    unsigned moment_lights;      /* bit i: light i reads its moment map */
    unsigned early_out, receiver_plane, show_texels, show_texel_size, show_cascades, show_penumbra;
    unsigned rays, show_unsure; /* map_rays; the unsure overlay */
    unsigned ray_records;       /* the rays read cut-out or translucent surfaces (BVH_RECORDS) */
    unsigned ray_buffer;        /* the casters are in a texture buffer (BVH_TEXTURE_BUFFER) */
    unsigned ray_counts;        /* each pixel's rays into the counts' target */
    unsigned mark_rays;         /* the pixels rays decide marked, not traced */
    unsigned bounds_lights;     /* bit i: light i read by its depth bounds (a marking pass) */
    unsigned transmit_lights;   /* bit i: light i reads its transmittance map */
} map_camera_key;

/* A texture the frame's size, attached beside its colour for the
 * receivers' passes (map_rays.c); failed (said once): never again. */
typedef struct map_second_target {
    unsigned texture, framebuffer; /* the framebuffer: the read-back's */
    int size[2];
    bool failed;
} map_second_target;

/* The camera pass's program (lit.vert with map.frag) for one key,
 * and its uniforms: the pass's, then each light's (-1 where its kind has
 * none). */
typedef struct map_camera_program {
    render_program program;
    map_camera_key key;
    int constant_bias, normal_offset, depth_bias, closed_outside, view_depth, cascade_blend, ray_samples, frame;
    int eye, exact_surface; /* the rays' start (shaders/map.frag, map_ray_origin) */
    int translucent;        /* the receiver is a translucent caster (shaders/map.glsl, map_transmitted) */
    int ambient;            /* the pass draws the ambient term (map_shade_receivers) */
    struct {
        int map_size, light_matrix, light_inverse, light_size, light_area, texel_scale, near_plane, far_plane,
            cascade_count;
        int cascade_scale, cascade_offset; /* the light's first layer's element */
        int tiles;                         /* its faces' tiles (u_tiles), in the atlas */
    } lights[SHADER_PASS_LIGHTS];
    int atlas_size; /* the atlas's texels on a side */
} map_camera_program;

/* overlay.vert with overlay_lines.frag: world-space lines in one colour. */
typedef struct map_lines_program {
    render_program program;
    int color;
} map_lines_program;

/* overlay.vert with overlay_map.frag: a map's reduction as an inset of
 * linear depth. */
typedef struct map_inset_program {
    render_program program;
    int reduced, kind, layer, size, factor, orthographic, near_plane, far_plane, held;
} map_inset_program;

/* overlay.vert with overlay_reduce.frag, for a map of one kind: the
 * inset's reduction, loaded when an inset first needs it. */
typedef struct map_reduce_program {
    render_program program;
    int factor, layer;
} map_reduce_program;

/* overlay.vert with overlay_heat_legend.frag: the texel-size legend's bar. */
typedef struct map_legend_program {
    render_program program;
    int log2_range;
} map_legend_program;

/* Vertices in the overlay buffer: a frustum's 12 edges take 24 line
 * ends; the legend's panel, ticks and labels, two triangles a rectangle
 * (its three labels: about 70 of stb_easy_font's quads); the buffer holds
 * the larger. */
#define MAP_OVERLAY_VERTICES 24
#define MAP_LEGEND_VERTICES 1200

/* A moment blur pass (shaders/shadow_moments.frag) and its uniforms. */
typedef struct map_blur_program {
    unsigned id;
    int radius, axis, layer;
} map_blur_program;

/* What a light's map was rendered with (the cache's key): all ints, so
 * that it compares with memcmp. */
typedef struct map_depth_key {
    unsigned texture;
    int size, depth, filter, no_slope_bias;
    float slope_factor, slope_units;
} map_depth_key;

/* What each layer of a light's map holds (map.h, "Caching"). */
typedef struct map_cache {
    map_depth_key key;
    bool valid[MAP_MAX_LAYERS];
    mat4 layer_view_projection[MAP_MAX_LAYERS];
    float blur_texels[MAP_MAX_LAYERS];
    bool *drawn[MAP_MAX_LAYERS]; /* per object: drawn into the layer */
} map_cache;

/* The uniforms of a program that redoes glPolygonOffset
 * (shaders/depth_offset.glsl): -1 where it lacks one (the units and the
 * format's, but where it clamps the depth itself). */
typedef struct map_offset_uniforms {
    int slope_factor, offset_units, depth_float;
} map_offset_uniforms;

/* A technique's maps and their GL objects. */
struct map_renderer {
    render_programs depth;
    /* A cube's depth pass where the GL has no depth clamp: the programs
     * that write the clamped depth themselves (MAP_DEPTH_CLAMP_EMULATED,
     * shadow_depth.vert), else ids 0, and per pass (render_programs_pass)
     * their polygon offset's uniforms. */
    render_programs depth_clamped;
    map_offset_uniforms clamped_offset[RENDER_PROGRAMS_MAX_PASSES];
    map_camera_program camera[MAP_CAMERA_PROGRAMS];
    int camera_count, camera_oldest;
    map_lines_program lines;
    map_inset_program inset;
    map_legend_program legend;
    unsigned framebuffer, overlay_vao, overlay_buffer;
    /* The moment maps' passes: per moment kind the depths' moments from
     * each kind of map, and the box along an axis; their framebuffer
     * (loaded as needed). */
    map_blur_program blur_depth[MAP_MOMENTS_MSM + 1][MAP_ARRAY + 1], blur_moments;
    unsigned blur_framebuffer;
    /* The empty vertex array of viewport_triangle.vert's passes: the
     * moments' blur, the rays' marks. */
    unsigned screen_vao;
    /* The map inset's reduction (map_overlay.c) of light 0's map:
     * per kind its program; an RG32F array texture, a layer per map layer
     * and inset_blocks texels on a side (blocks of inset_factor texels on
     * a side), and its framebuffer; each layer's nearest and farthest held
     * depth. Current until the depth pass renders a layer of light 0's
     * map (made again only then: a cached map is not reduced again);
     * failed (said once): no inset is drawn. */
    map_reduce_program reduce[MAP_ARRAY + 1];
    unsigned inset_texture, inset_framebuffer;
    int inset_blocks, inset_layers, inset_factor;
    float inset_held[MAP_MAX_LAYERS][2];
    bool inset_current, inset_failed;
    bool blur_failed;               /* said once: moment filters read one bilinear depth test */
    unsigned depth_sampler;         /* a map read as depth: compare mode off, nearest */
    int texture_units;              /* GL_MAX_TEXTURE_IMAGE_UNITS */
    int max_texture_size;           /* GL_MAX_TEXTURE_SIZE */
    scene_light_set soft_warned;    /* bit i: light i's treatment said on stderr */
    scene_light_set moments_warned; /* bit i: light i's lack of a moment unit said on stderr */
    map_light maps[SCENE_MAX_LIGHTS];
    map_cache caches[SCENE_MAX_LIGHTS];
    int object_count;             /* the scene's, at init: the sets' size */
    bool *needed[MAP_MAX_LAYERS]; /* this frame's casters of each layer of one light */
    /* Per light and layer: no receiver reads it this frame (its planned
     * reads are empty), so it is not drawn (map.h, "Caching"). */
    bool unread[SCENE_MAX_LIGHTS][MAP_MAX_LAYERS];
    float (*receiver_boxes)[2][3]; /* one light's visible receivers' boxes within its range */
    bool *unmapped;                /* per object: drawn by the camera pass's lit programs, not its maps */
    light_mask *masks;             /* one light's layers' masks of the visible pixels */
    bool *closed;                  /* per object: a caster whose mesh is closed */
    /* Where the camera sees receivers (warp_samples; -1: not cast yet this
     * frame), and those light sample_light is measured at
     * (warp_samples_lit): map_light_samples; the receivers' boxes it casts
     * to (picture_box_count of them), and reach_hits, the grid cast over
     * one light's reach on screen alone, to the reach_boxes seen there. */
    float (*picture_boxes)[2][3], (*reach_boxes)[2][3];
    int picture_box_count;
    warp_sample hits[WARP_SAMPLE_COUNT], samples[WARP_SAMPLE_COUNT], reach_hits[WARP_SAMPLE_COUNT];
    int hit_count, sample_count, sample_light;
    bool reach_sampled; /* sample_light's are reach_hits' */
    int grazing_count;  /* of sample_light's: the hits left out as edge-on to it */
    /* This frame's, from map_begin on: the target the camera pass
     * draws into, and which lights have a map. */
    int target_framebuffer, viewport[4];
    bool fitted[SCENE_MAX_LIGHTS];
    /* The budget (map.h, "Budget"): per light, the fit its whole map was
     * last drawn with (while drawn[l]) and the frames it has waited since
     * its map was due; the lights waiting this frame, each with the
     * casters of each layer it planned (MAP_MAX_LAYERS x objects per
     * light). */
    map_light drawn_fit[SCENE_MAX_LIGHTS];
    scene_light drawn_light[SCENE_MAX_LIGHTS]; /* the light as it was then */
    bool drawn[SCENE_MAX_LIGHTS];
    int waited[SCENE_MAX_LIGHTS];
    scene_light_set waiting;
    bool *waiting_needed;
    const bvh_gpu *casters; /* map_trace_with's; NULL: no rays */
    /* The camera pass's second targets (map_rays.c): the rays' marks,
     * R8, the program that makes them the stencil, and the marked pixels
     * where the frame counts; the rays' counts, RGBA32F; the last
     * counted frame's sums. */
    map_second_target marks, counts;
    unsigned marks_program;
    long marked_pixels;
    technique_rays counted;
    bool has_counted;
    /* The maps' depth bounds (map_bounds.c): their programs (a 2D
     * map's, a cube map's) and framebuffer; failed (said once): the
     * kernel everywhere. */
    unsigned bounds_programs[2], bounds_framebuffer;
    bool bounds_failed;
    /* The transmittance maps (map.h, "Translucent casters"):
     * shadow_depth.vert with transmittance.frag and its polygon offset's
     * uniforms, loaded where the scene has translucent casters (else id
     * 0), the second for a cube where the GL has no depth clamp (as
     * depth_clamped; else id 0), and their framebuffer; failed (said
     * once): whole shadows. */
    render_program transmit[2];
    map_offset_uniforms transmit_offset[2];
    unsigned transmit_framebuffer;
    bool transmit_failed;
    scene_light_set transmit_warned; /* bit i: light i's lack of a unit said on stderr */
    /* The atlas (map.h, "Atlas"): its tiles; its depth texture (0: not
     * made yet), of the depth format `atlas_depth`, read with the filter
     * `atlas_filter`; per light each face's node (-1: none) and the size
     * its tile was asked at; this frame's faces given a smaller tile than
     * asked, and lights given no room at all (a cube map of their own
     * instead). */
    map_atlas atlas;
    unsigned atlas_texture;
    int atlas_depth, atlas_filter;
    bool atlas_planned; /* map_atlas_plan ran this frame */
    int tile_nodes[SCENE_MAX_LIGHTS][MAP_CUBE_FACES], tile_asked[SCENE_MAX_LIGHTS][MAP_CUBE_FACES];
    int tiles_short, tiles_refused;
    int tiles_halved; /* times map_atlas_plan halved the frame's asks to fit the largest atlas */
    int maps_halved;  /* times map_bound_memory halved the frame's own maps (map.h, "Memory") */
    warp_sample face_samples[WARP_SAMPLE_COUNT]; /* one face's of a light's samples (map_tiles_size) */
};

/* A power-of-two side halved, while above `least`, until the GL's
 * largest texture holds it. */
int map_side_within_gl(const map_renderer *r, int side, int least);
/* What --map-size auto aims at for a light's 2D or cube map: a texel of
 * texel_pixels pixels on screen (MAP_AUTO_TEXEL_PIXELS, over
 * map_auto_finer), at most `largest` texels a side (MAP_AUTO_MAX_SIZE,
 * or MAP_AUTO_CUT_OUT_MAX_SIZE for a sun's map finer for cut-outs;
 * within the GL's largest texture). */
typedef struct map_auto_rule {
    float texel_pixels;
    int largest;
} map_auto_rule;
map_auto_rule map_auto_rule_for(const map_renderer *r, const map_settings *settings, const scene *s,
                                const scene_light *light);

/* ---- the atlas (map_tiles.c; map.h, "Atlas") ---- */

/* A light of `kind` goes in the atlas with these settings: many lights,
 * a cube, hard, read by a kernel, without transmittance maps. */
bool map_tiles_wanted(const map_renderer *r, const map_settings *st, const scene_light *light, map_kind kind);
/* Each face's tile size (m->tiles[face].size) of the fitted cube m at
 * MAP_AUTO_MAX_SIZE: the light's auto size (map_auto_size by `rule`),
 * which it returns, where auto's rule measures a sample on the face,
 * else MAP_ATLAS_MIN_TILE. */
int map_tiles_size(map_renderer *r, map_light *m, const scene_light *light, map_samples samples, map_auto_rule rule);
/* The atlas for the frame, once every light is fitted: the fitted
 * lights' tiles halved where they would outgrow the largest atlas
 * (map_tile_asks_fit); its texture made for the settings' depth format
 * and at the side those tiles want (map_atlas_side_wanted), made again
 * where the format changed, the tiles outgrew it or it is twice the side
 * they want or more, its tiles then freed and every fitted light's
 * placed afresh, the largest first; filtered by the settings' filter.
 * True where it was made again (what its tiles held is gone), or where
 * memory for its tiles failed (said on stderr; no atlas, r->atlas_texture
 * 0). */
bool map_atlas_plan(map_renderer *r, const map_settings *st, int light_count);
/* Light l's face `face` holds a tile asked at the size m asks now. */
bool map_tile_held(const map_renderer *r, const map_light *m, int l, int face);
/* Where a face's tile is: the one it held (what it holds is still
 * there), a new one, or none (no room left). */
typedef enum map_tile_placed { MAP_TILE_KEPT, MAP_TILE_NEW, MAP_TILE_NO_ROOM } map_tile_placed;
/* Light l's face `face` in its tile, into m->tiles[face]: the tile it
 * holds while asked at the same size, else a new one, the largest free
 * one up to the size asked (r->tiles_short counts those smaller). */
map_tile_placed map_tile_place(map_renderer *r, map_light *m, int l, int face);
/* Light l's tiles freed. */
void map_tiles_release(map_renderer *r, int l);
/* The atlas as a 2D map of its size (the map overlay's inset): stored
 * depths, shown as they are. */
map_light map_atlas_as_map(const map_renderer *r);

/* Where a light of the frame's takes rays only where the map is unsure,
 * the receivers are drawn twice (map.h, "Rays"): first marking the pixels
 * that rays would decide (shaders/map.frag, MAP_PASS_MARK_RAYS) into a
 * second target beside the frame's colour, then again, tracing, where the
 * stencil lets through only those. Begin attaches and clears the marks
 * (false: this frame traces in one pass); end (`count`: into
 * r->marked_pixels, for the counts' sums) detaches them and leaves the
 * stencil test on, passing only the marked pixels. */
bool map_ray_marks_begin(map_renderer *r);
void map_ray_marks_end(map_renderer *r, bool count);
/* While the camera pass draws the receivers, each pixel's rays and
 * traced lights go to a second target (shaders/map.frag,
 * MAP_PASS_RAY_COUNTS) attached beside the frame's colour: begin attaches
 * and clears it (false: this frame cannot count), end detaches it and sums
 * it into r->counted. All four leave the target framebuffer bound. */
bool map_ray_counts_begin(map_renderer *r);
void map_ray_counts_end(map_renderer *r);
void map_rays_destroy(map_renderer *r);

/* The depth bounds' cell: texels on a side whose depths one texel of a
 * map's bounds holds between two planes (shaders/map_bounds.frag). A kernel
 * whose reads span at most this many texels reads 2 x 2 cells: a finer
 * cell reads more of them and decided no more pixels on the standard
 * scenes (test_hybrid's marked share). */
#define MAP_BOUNDS_CELL_TEXELS 8
/* Map m's depth bounds, made again where a layer was drawn since (false:
 * an array map's, which have none, or this GL cannot draw them, said
 * once). Leaves the target framebuffer bound, at the frame's viewport. */
bool map_bounds_update(map_renderer *r, map_light *m);
void map_bounds_destroy(map_renderer *r);

/* The depth pass of a fitted map of any kind, uncached (the tests'):
 * (re)makes its texture when needed, then renders every layer from its matrix, with glPolygonOffset
 * as the slope-scaled bias (unless --no-slope-bias; an array map's layers
 * attached one at a time, glFramebufferTextureLayer), and a moment
 * filter's blurs each. Leaves r->framebuffer (or the blur's) bound and
 * the viewport at the map's size: the caller binds its target again. */
void map_render_depth(map_renderer *r, const map_settings *settings, const render_scene *gpu, map_light *m);

/* --map-size auto's size for the fitted map m of the light at
 * light_position, from the samples the light is measured at (see
 * MAP_AUTO_*): a texel's size on screen scales as 1 / size, so the
 * mean at m->size gives the size at which it is the rule's texel_pixels,
 * rounded up to a power of two (to its largest at most), from samples
 * warp_samples_lit kept (none beyond the light's range); those outside
 * the map are not measured. Where more of the samples were left out as
 * edge-on to the light (`grazing`) than kept, the faces measured are not
 * where its shadows are seen: on those faces every texel is unboundedly
 * long and only its width across the light can shrink, so the map takes
 * the most texels, the rule's largest (else a sun a fraction of a degree
 * above the ground, measured on the casters' sides alone, gets a small
 * map and every long shadow edge on the ground follows one texel's
 * rounding: test_shadowmap's stress extremes,
 * tests/data/shadowmap_grazing_sun.json). Where none is measured:
 * FALLBACK, or MIN where the samples are those of the grid over the
 * light's reach (samples.reach_sampled), which found nothing it lights
 * larger than a cell of that grid on screen. */
int map_auto_size(const map_light *m, const scene_light *light, map_samples samples, map_auto_rule rule);
/* The same rule without the grazing case: `unmeasured` where no sample
 * is measured. */
int map_auto_size_or(const map_light *m, const scene_light *light, const warp_sample *samples, int n, int unmeasured,
                     map_auto_rule rule);
/* A kind's GL texture target, and the image of a 2D map's or a cube
 * face's layer (GLenums). */
unsigned map_target(map_kind kind);
unsigned map_layer_image(map_kind kind, int layer);
/* The bound texture of `target` filtered by `filter` (GL_NEAREST or
 * GL_LINEAR), its reads clamped to its edges. */
void map_texture_filter(unsigned target, int filter);
/* A map's depth format (a map_depth) as a GL internal format and pixel
 * type (GLenums). */
void map_depth_format(int depth, unsigned *format, unsigned *type);
/* The bound depth texture of `target` read by `filter` (a map_filter:
 * nearest for none, else bilinear), every read a depth test (compare
 * mode on), clamped to its edges. */
void map_depth_sampling(unsigned target, int filter);
/* "2D", "cube" or "array", for HUD lines. */
const char *map_kind_name(map_kind kind);

/* r->needed[layer]: the casters each layer of light l's fitted map needs
 * (every candidate where it does not cull); counts them in f->skips->counts. */
void map_plan_casters(map_renderer *r, const map_settings *settings, const technique_frame *f, int l);

/* ---- moment maps (map_moments.c) ---- */

/* The box radius of a moment filter's blur, in texels of each layer of
 * light l's fitted map m, into blur (see map_moments.c): a hard
 * light's MAP_MOMENTS_HARD_BLUR_TEXELS, an area light's the mean
 * penumbra its casters cast at their feet, unclamped; each caster's
 * shadow is traced once for every layer. */
void map_moments_blur_texels(const scene *s, int l, const map_light *m, float blur[MAP_MAX_LAYERS]);
/* (Re)makes a moment filter's textures beside m's depth texture (or
 * deletes them for the kernels). */
void map_moments_prepare(map_light *m, map_moments moments);
/* The depths of layer `layer` as blurred moments (their moments, then
 * the box along x and along y); false (said
 * once, r->blur_failed) where a pass cannot run. Leaves its framebuffer
 * bound. */
bool map_moments_blur(map_renderer *r, const map_light *m, map_moments moments, int layer);
void map_moments_destroy(map_renderer *r);

/* Passes that read a map's depths a texel at a time (the moment blur's
 * first, the map inset's reduction) include shaders/map_texel.glsl: their
 * defines go on with MAP_TEXEL_DEFINES, the names it compares
 * with, and map_texel_units puts its samplers on their units (the
 * program in use): a map of kind k is read on unit k. */
#define MAP_TEXEL_DEFINES                                                                                            \
    SHADER_DEFINE(MAP_CUBE), SHADER_DEFINE(MAP_ARRAY), SHADER_DEFINE(MAP_FACE_POSITIVE_X),                           \
        SHADER_DEFINE(MAP_FACE_NEGATIVE_X), SHADER_DEFINE(MAP_FACE_POSITIVE_Y), SHADER_DEFINE(MAP_FACE_NEGATIVE_Y),  \
        SHADER_DEFINE(MAP_FACE_POSITIVE_Z)
void map_texel_units(unsigned program);
/* *framebuffer (made on first use), bound, with `texture`'s image `image`
 * (GL_TEXTURE_2D, a cube face's, or layer `layer` of GL_TEXTURE_2D_ARRAY)
 * as its colour: complete, or said on stderr with what is done `instead`,
 * and false. */
bool map_color_target(unsigned *framebuffer, unsigned texture, unsigned image, int layer, const char *instead);

/* ---- overlays (map_overlay.c) ---- */

/* The 12 edges of the frustum of `frustum` (its clip cube mapped back to
 * world space), drawn through `view_projection`. */
void map_draw_frustum(map_renderer *r, const mat4 frustum, const mat4 view_projection);

/* Each array layer's colour in the cascades overlay, one table for the
 * camera pass's tint (shaders/map_array.glsl's u_cascade_colors,
 * set from it when a camera program is made) and the key's swatches. */
extern const float map_cascade_colors[MAP_MAX_ARRAY_LAYERS][3];

/* The grey of an inset's farthest held depth (map.h, "The map inset"). */
#define MAP_INSET_FAR_GREY_PERCENT 75
/* How many insets a map of `kind` with `layer_count` layers has (an
 * array's layers one each; any other map one), and where inset `inset`
 * lies in a viewport of width x height pixels: x, y, width and height in
 * pixels from the viewport's bottom-left corner. */
int map_inset_count(map_kind kind, int layer_count);
void map_inset_rect(map_kind kind, int layer_count, int inset, int width, int height, int rect[4]);

#endif
