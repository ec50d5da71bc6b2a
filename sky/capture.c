/*
 * The environment capture (sky_capture_environment): the sky drawn into
 * the six faces of a cube map through sky_draw's own path, one face per
 * draw, into the host's cube map or the library's own; without
 * framebuffer objects each face is drawn at the corner of the host's draw
 * buffer and copied from there (sky_capture_overwrote says where).
 */
#include "sky_internal.h"

#include <string.h>

/* GL's cube-map faces: the direction each looks along and its up (the
 * face's image runs right along forward x up, and down along up). */
static const float cube_forward[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
static const float cube_up[6][3] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};

sky_result sky_capture_face_matrices(int face, float view[16], float proj[16])
{
    if (face < 0 || face > 5 || !view || !proj) return SKY_ERR_INVALID_ARGUMENT;
    const float *f = cube_forward[face], *u = cube_up[face];
    float r[3] = {f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0]};
    float v[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]};
    memset(view, 0, 16 * sizeof(float));
    for (int c = 0; c < 3; c++) {
        view[c * 4 + 0] = r[c];
        view[c * 4 + 1] = v[c];
        view[c * 4 + 2] = -f[c];
    }
    view[15] = 1.0f;
    /* 90 degrees square; the sky ignores the depth range */
    const float n = 0.1f, far = 100.0f;
    memset(proj, 0, 16 * sizeof(float));
    proj[0] = proj[5] = 1.0f;
    proj[10] = (far + n) / (n - far);
    proj[11] = -1.0f;
    proj[14] = 2.0f * far * n / (n - far);
    return SKY_OK;
}

/* The checks before anything is drawn: SKY_OK, or the error. */
static sky_result capture_check(sky *s, int face_size, int face, unsigned flags, unsigned cube_texture,
                                int backbuffer)
{
    sky_core *c = &s->core;
    if (face_size < 4 || face_size > 2048 || (face_size & (face_size - 1)))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: face_size %d is not a power of two "
                        "in 4..2048", face_size);
    if (face < SKY_CAPTURE_ALL_FACES || face > 5)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: face %d is not 0..5 or "
                        "SKY_CAPTURE_ALL_FACES", face);
    if (flags & ~SKY_CAPTURE_SUN_DISC)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: unknown flags 0x%x", flags);
    if (!sky_gl_context_current(c)) return sky_fail(s, SKY_ERR_GL, "sky_capture_environment: no GL context is current");
    if (c->cfg.output == SKY_OUTPUT_HDR && c->profile != SKY_GL_CORE33 && !cube_texture)
        return sky_fail(s, SKY_ERR_UNSUPPORTED, "sky_capture_environment: HDR output in %s is captured into "
                        "the host's float cube map only (the library's textures there are 8-bit)",
                        c->profile == SKY_GL_ES20 ? "ES20" : "COMPAT20");
    int limit = sky_gl_cube_size_max(c);
    if (limit > 0 && face_size > limit)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: face_size %d is over this context's "
                        "limit %d", face_size, limit);
    if (backbuffer) {
        GLint vp[4] = {0, 0, 0, 0};
        sky_gl_viewport_get(c, vp);
        if (face_size > vp[2] || face_size > vp[3])
            return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: face_size %d does not fit the "
                            "viewport (%d x %d) it is drawn through: this %s context has no framebuffer objects",
                            face_size, (int)vp[2], (int)vp[3], c->gl_version);
    }
    return SKY_OK;
}

/* The cube map to draw into (*tex): the host's, checked, or the library's
 * own at this size. It binds on unit 0: the caller restores the host's
 * state. */
static sky_result capture_texture(sky *s, unsigned cube_texture, int face_size, GLuint *tex)
{
    sky_core *c = &s->core;
    *tex = cube_texture;
    if (!cube_texture) {
        sky_texture *own = &c->textures[SKY_TEX_ENVIRONMENT];
        if (own->id && own->width != face_size) sky_texture_destroy(c, SKY_TEX_ENVIRONMENT);
        char why[160];
        if (!own->id && sky_texture_create_cube(c, SKY_TEX_ENVIRONMENT, SKY_LAYER_ATMOSPHERE, NULL, face_size,
                                                c->cfg.output == SKY_OUTPUT_HDR, why, sizeof why))
            return sky_fail(s, SKY_ERR_GL, "sky_capture_environment: %s", why);
        *tex = own->id;
        return SKY_OK;
    }
    if (c->caps.es) return SKY_OK; /* (ES 2.0 cannot ask a texture its size: sky.h) */
    int w = sky_gl_cube_width(c, cube_texture);
    if (w != face_size)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: texture %u is not a cube map with "
                        "%d x %d faces (its +X level 0 is %d wide)", cube_texture, face_size, face_size, w);
    return SKY_OK;
}

sky_result sky_capture_environment(sky *s, unsigned cube_texture, int face_size, int face, unsigned flags)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    sky_core *c = &s->core;
    /* without framebuffer objects each face is drawn into the host's
     * draw buffer at its viewport's corner and copied from there */
    int backbuffer = !c->caps.render_to_rgba8;
    sky_result rc = capture_check(s, face_size, face, flags, cube_texture, backbuffer);
    if (rc != SKY_OK) return rc;
    sky_gl_state host;
    sky_gl_state_save(c, &host);
    GLuint tex = 0;
    rc = capture_texture(s, cube_texture, face_size, &tex);
    if (rc == SKY_OK && !backbuffer && !s->capture_fbo && !(s->capture_fbo = sky_gl_framebuffer_create(c)))
        rc = sky_fail(s, SKY_ERR_GL, "sky_capture_environment: no framebuffer object");
    if (rc != SKY_OK) {
        sky_gl_state_restore(c, &host);
        return rc;
    }
    GLint draw_fbo = 0, read_fbo = 0;
    if (!backbuffer) sky_gl_framebuffers_get(c, &draw_fbo, &read_fbo);
    c->capture_without_sun = !(flags & SKY_CAPTURE_SUN_DISC);
    c->capturing = 1;
    for (int f = face < 0 ? 0 : face; f <= (face < 0 ? 5 : face) && rc == SKY_OK; f++) {
        float view[16], proj[16];
        sky_capture_face_matrices(f, view, proj);
        if (backbuffer) {
            sky_gl_viewport_set(c, host.viewport[0], host.viewport[1], face_size, face_size);
            if ((rc = sky_draw_view(s, view, proj)) != SKY_OK) break;
            sky_gl_cube_copy_face(c, tex, f, host.viewport[0], host.viewport[1], face_size);
            continue;
        }
        GLenum status = sky_gl_target_cube_face(c, s->capture_fbo, tex, f);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            rc = sky_fail(s, SKY_ERR_GL, "sky_capture_environment: cannot render into face %d of texture %u "
                          "(framebuffer status 0x%04x: its format?)", f, tex, status);
            break;
        }
        sky_gl_viewport_set(c, 0, 0, face_size, face_size);
        rc = sky_draw_view(s, view, proj);
    }
    c->capture_without_sun = c->capturing = 0;
    for (int i = 0; i < 4; i++) s->capture_overwrote[i] = 0;
    if (backbuffer) {
        s->capture_overwrote[0] = host.viewport[0];
        s->capture_overwrote[1] = host.viewport[1];
        s->capture_overwrote[2] = s->capture_overwrote[3] = face_size;
    } else {
        sky_gl_target_cube_face(c, s->capture_fbo, 0, 0);
        sky_gl_framebuffers_set(c, draw_fbo, read_fbo);
    }
    sky_gl_state_restore(c, &host);
    return rc;
}

int sky_capture_overwrote(const sky *s, int rect[4])
{
    if (rect)
        for (int i = 0; i < 4; i++) rect[i] = s ? s->capture_overwrote[i] : 0;
    return s && s->capture_overwrote[2] > 0;
}

unsigned sky_environment_texture(const sky *s)
{
    return s ? s->core.textures[SKY_TEX_ENVIRONMENT].id : 0u;
}
