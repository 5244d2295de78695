#include "volume_near.h"

#include <cglm/cglm.h>
#include <glad/gl.h>

#include "frustum.h"
#include "volume_silhouette.h"

/* The define that makes volume.frag keep the light's side of the plane. */
#define VOLUME_NEAR_DEFINE "VOLUME_NEAR_COUNT"

static bool volume_near_load(render_program *p, bool wide, int *projection, int *plane) {
    static const char *const files[] = {"volume_near.vert", "volume.frag"};
    const shader_define defines[] = {
        {VOLUME_NEAR_DEFINE, 1}, {wide ? VOLUME_SILHOUETTE_WIDE_DEFINE : NULL, 1}, {NULL, 0}};
    if (!render_program_load(p, files, (int)(sizeof files / sizeof *files), defines))
        return false;
    p->both_sides = true; /* the caster's shape on the near plane, culled as it says (render.h) */
    *projection = shader_uniform(p->id, "u_near_projection");
    *plane = shader_uniform(p->id, "u_near_plane");
    return true;
}

bool volume_near_init(volume_near *n) {
    *n = (volume_near){0};
    if (!volume_near_load(&n->stencil, false, &n->stencil_projection, &n->stencil_plane) ||
        !volume_near_load(&n->wide, true, &n->wide_projection, &n->wide_plane))
        return false;
    n->wide_color = shader_uniform(n->wide.id, "u_color");
    return true;
}

void volume_near_destroy(volume_near *n) {
    render_program_destroy(&n->stencil);
    render_program_destroy(&n->wide);
}

void volume_near_caster(volume_near *n, const technique_frame *f, int i, const float light[4], const float plane[4],
                        bool closed, bool wide) {
    /* 1. World -> the near plane, from the light -> clip. */
    mat4 onto_plane, projection;
    frustum_plane_projection(plane, light, onto_plane);
    glm_mat4_mul((vec4 *)f->view->raster_view_projection, onto_plane, projection);
    /* 2. A closed mesh's triangles that face away from the light culled:
     *    as the GL sees them after the projection (see top), the front
     *    ones where the light lies in front of the near plane, that is
     *    where the eye, behind that plane, lies on the side of `plane`
     *    away from the light. */
    if (closed) {
        const float *eye = f->view->eye;
        float eye_side = plane[0] * eye[0] + plane[1] * eye[1] + plane[2] * eye[2] + plane[3];
        glEnable(GL_CULL_FACE);
        glCullFace(eye_side < 0 ? GL_FRONT : GL_BACK);
    } else {
        glDisable(GL_CULL_FACE);
    }
    /* 3. Each fragment adds one, whatever its depth. */
    const render_program *p = wide ? &n->wide : &n->stencil;
    render_program_use(p, f->view);
    glUniformMatrix4fv(wide ? n->wide_projection : n->stencil_projection, 1, GL_FALSE, (const float *)projection);
    glUniform4fv(wide ? n->wide_plane : n->stencil_plane, 1, plane);
    if (wide)
        glUniform4f(n->wide_color, 1, 0, 0, 0);
    glDepthFunc(GL_ALWAYS);
    glStencilOp(GL_KEEP, GL_KEEP, GL_INCR_WRAP);
    render_draw_object(f->gpu, p, i);
    glDisable(GL_CULL_FACE);
    glCullFace(GL_BACK);
}
