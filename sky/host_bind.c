/*
 * What the host's own shading takes from the sky: the display snippet and
 * the aerial-perspective snippet with their binders (uniforms set by name
 * in the host's program), the aerial perspective on the CPU, and
 * Hillaire's froxel volume. The host's current program, active unit and
 * other state come back from every call.
 */
#include "sky_internal.h"

#include <math.h>
#include <string.h>

/* An embedded shader source for hosts, "" if this build lacks it. */
static const char *host_glsl(const char *name)
{
    const sky_blob *b = sky_find_blob(name);
    return b ? (const char *)b->data : "";
}

/* What both binders of the host's snippets check first (s not NULL): the
 * sky's context, and a name the context knows as a program (glIsProgram:
 * whether it linked is the host's to know). */
static sky_result host_program_check(sky *s, unsigned program, const char *what)
{
    if (!program) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "%s: program 0", what);
    sky_result rc = sky_own_context_check(s, what);
    if (rc != SKY_OK) return rc;
    if (!sky_gl_is_program(&s->core, program))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "%s: %u is not a program of the current context", what, program);
    return SKY_OK;
}

/* A texture unit the program's stages may use. */
static sky_result host_unit_check(sky *s, int texture_unit, const char *what)
{
    int units = sky_gl_texture_units(&s->core);
    if (texture_unit < 0 || (units > 0 && texture_unit >= units))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "%s: texture unit %d is not 0..%d", what, texture_unit,
                        units - 1);
    return SKY_OK;
}

const char *sky_display_glsl(void) { return host_glsl("display.glsl"); }

sky_result sky_display_bind(sky *s, unsigned program)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    sky_result rc = host_program_check(s, program, "sky_display_bind");
    if (rc != SKY_OK) return rc;
    const sky_frame *f = &s->core.frame;
    const sky_gl_host_uniform u[] = {
        {"sky_display_exposure", 1, {f->display_exposure}, 0},
        {"sky_display_rods", 1, {f->night_shift}, 0},
        {"sky_display_cd", 1, {f->display_cd}, 0},
    };
    sky_gl_host_uniforms(&s->core, program, u, (int)(sizeof u / sizeof u[0]), 0, 0);
    return SKY_OK;
}

const char *sky_aerial_glsl(void) { return host_glsl("aerial.glsl"); }

/* The aerial table as a texture, made or updated when it changed. The
 * upload binds on unit 0 and sets the unpack state: the host's come back. */
static sky_result aerial_upload(sky *s)
{
    sky_core *c = &s->core;
    if (c->textures[SKY_TEX_AERIAL].id && s->aerial.uploaded) return SKY_OK;
    sky_gl_state host;
    sky_gl_state_save(c, &host);
    char why[160];
    int failed = 0;
    if (!c->textures[SKY_TEX_AERIAL].id)
        failed = sky_texture_create(c, SKY_TEX_AERIAL, SKY_LAYER_ATMOSPHERE, s->aerial.texels, 4, SKY_AP_TABLE_W,
                                    SKY_AP_TABLE_H, 0, why, sizeof why);
    else
        sky_texture_update_lut(c, SKY_TEX_AERIAL, SKY_AP_TABLE_W, SKY_AP_TABLE_H, s->aerial.texels, NULL);
    sky_gl_state_restore(c, &host);
    if (failed) return sky_fail(s, SKY_ERR_GL, "sky_aerial_bind: %s", why);
    s->aerial.uploaded = 1;
    return SKY_OK;
}

sky_result sky_aerial_bind(sky *s, unsigned program, int texture_unit)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    sky_result rc = host_program_check(s, program, "sky_aerial_bind");
    if (rc != SKY_OK) return rc;
    sky_core *c = &s->core;
    if ((rc = host_unit_check(s, texture_unit, "sky_aerial_bind")) != SKY_OK) return rc;
    if (sky_aerial_table(c, &s->aerial) < 0)
        return sky_fail(s, SKY_ERR_OUT_OF_MEMORY, "sky_aerial_bind: out of memory for the table");
    if ((rc = aerial_upload(s)) != SKY_OK) return rc;
    /* the uniforms, in the host's program; the table stays bound on
     * texture_unit */
    float up_h[3] = {0.0f, 1.0f, 0.0f}, sun_h[3], up[3], sun[3];
    const float *sd = c->frame.sun_dir;
    double across = hypot(sd[0], sd[2]);
    sun_h[0] = across > 1e-9 ? (float)(sd[0] / across) : 1.0f;
    sun_h[1] = 0.0f;
    sun_h[2] = across > 1e-9 ? (float)(sd[2] / across) : 0.0f;
    sky_camera_to_world(c, up_h, up);
    sky_camera_to_world(c, sun_h, sun);
    double r0, rt;
    sky_aerial_shell(c, &s->aerial, &r0, &rt);
    const sky_gl_host_uniform u[] = {
        {"sky_aerial_table", 0, {0}, texture_unit},
        {"sky_aerial_up", 3, {up[0], up[1], up[2]}, 0},
        {"sky_aerial_sun", 3, {sun[0], sun[1], sun[2]}, 0},
        {"sky_aerial_params", 4,
         {(float)s->aerial.scale, (float)SKY_AP_TABLE_M, (float)(r0 * 1000.0), (float)(rt * 1000.0)}, 0},
        /* a weather's deck and haze, over the table (which a change of
         * weather does not remake) */
        {"sky_aerial_weather", 2, {(float)sky_aerial_deck_dim(c), c->frame.haze_beta}, 0},
        {"sky_aerial_haze", 3, {c->frame.fog_rgb[0], c->frame.fog_rgb[1], c->frame.fog_rgb[2]}, 0},
    };
    sky_gl_host_uniforms(c, program, u, (int)(sizeof u / sizeof u[0]), texture_unit, c->textures[SKY_TEX_AERIAL].id);
    return SKY_OK;
}

/* A world direction (any length) into the horizon frame: the transpose
 * of horizon_to_world (orthonormal). 0, or -1 for a non-finite or zero
 * vector. */
static int world_to_horizon(const sky_core *c, const float w[3], double h[3])
{
    double len = 0.0;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(w[i])) return -1;
        len += (double)w[i] * w[i];
    }
    len = sqrt(len);
    if (!(len > 0.0) || !isfinite(len)) return -1;
    const float *m = c->horizon_to_world; /* column j: horizon axis j in the world */
    for (int j = 0; j < 3; j++) h[j] = (m[3 * j] * w[0] + m[3 * j + 1] * w[1] + m[3 * j + 2] * w[2]) / len;
    return 0;
}

sky_result sky_get_aerial_perspective(sky *s, const float direction[3], float distance_m, sky_aerial *out)
{
    if (out) {
        for (int i = 0; i < 3; i++) out->transmittance[i] = 1.0f, out->inscatter[i] = 0.0f;
    }
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!direction || !out) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_aerial_perspective: NULL argument");
    double d[3];
    if (world_to_horizon(&s->core, direction, d))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_aerial_perspective: the direction (%g, %g, %g) is not "
                        "a finite non-zero vector", (double)direction[0], (double)direction[1], (double)direction[2]);
    if (!(distance_m >= 0.0f))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_aerial_perspective: distance %g m is not 0 or more",
                        (double)distance_m);
    double in[3], tr[3];
    if (sky_aerial_eval(&s->core, &s->aerial, d, (double)distance_m / 1000.0, in, tr))
        return sky_fail(s, SKY_ERR_OUT_OF_MEMORY, "sky_get_aerial_perspective: out of memory for the atmosphere's "
                        "tables");
    for (int i = 0; i < 3; i++) {
        out->transmittance[i] = (float)tr[i];
        out->inscatter[i] = (float)in[i];
    }
    return SKY_OK;
}

sky_result sky_aerial_froxels(sky *s, const float view[16], const float proj[16], unsigned *texture)
{
    if (texture) *texture = 0;
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    sky_core *c = &s->core;
    if (!view || !proj || !texture) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_aerial_froxels: NULL argument");
    float clip_to_dir[16];
    if (sky_camera_clip_to_horizon(c, view, proj, clip_to_dir))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_aerial_froxels: the camera is not finite, or its view or "
                        "projection is degenerate");
    if (c->profile != SKY_GL_CORE33 ||
        (c->atmosphere != SKY_ATMOSPHERE_HILLAIRE && c->atmosphere != SKY_ATMOSPHERE_BLEND))
        return sky_fail(s, SKY_ERR_UNSUPPORTED, "sky_aerial_froxels: the froxel volume is Hillaire's, in CORE33 (the "
                        "hillaire and blend paths); sky_aerial_bind serves every path and profile");
    sky_result own = sky_own_context_check(s, "sky_aerial_froxels");
    if (own != SKY_OK) return own;
    /* the build binds its program, tables and framebuffer; the volume is
     * made on unit 0's 3D target the first time: the host's come back */
    sky_gl_state host;
    sky_gl_state_save(c, &host);
    GLuint host_volume = sky_gl_volume_binding(c);
    if (s->vao) sky_gl_vertex_array_bind(c, s->vao); /* a core context draws nothing without one */
    /* a weather's deck and haze over the march, as sky_aerial_bind's */
    c->frame.froxel_weather[0] = (float)sky_aerial_deck_dim(c);
    c->frame.froxel_weather[1] = c->frame.haze_beta;
    char why[200];
    int rc = sky_atmosphere_froxels(c, clip_to_dir, why, sizeof why);
    sky_gl_volume_bind(c, host_volume);
    sky_gl_state_restore(c, &host);
    if (rc) return sky_fail(s, SKY_ERR_GL, "sky_aerial_froxels: %s", why);
    *texture = c->textures[SKY_TEX_FROXELS].id;
    return SKY_OK;
}

/* ---- the cloud shadows' snippet (the map: cloud_shadow.c) ---------------------- */

const char *sky_cloud_shadow_glsl(void) { return host_glsl("cloud_shadow.glsl"); }

sky_result sky_cloud_shadow_bind(sky *s, unsigned program, int texture_unit)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    sky_result rc = host_program_check(s, program, "sky_cloud_shadow_bind");
    if (rc != SKY_OK || (rc = host_unit_check(s, texture_unit, "sky_cloud_shadow_bind")) != SKY_OK) return rc;
    sky_cloud_shadow made;
    if (!s->shadow_last.texture && (rc = sky_get_cloud_shadow(s, 1.0f, 10000.0f, &made)) != SKY_OK) return rc;
    const sky_cloud_shadow *map = &s->shadow_last;
    const float *m = map->matrix;
    const sky_gl_host_uniform u[] = {
        {"sky_cloud_shadow_map", 0, {0}, texture_unit},
        {"sky_cloud_shadow_s", 4, {m[0], m[4], m[8], m[12]}, 0},
        {"sky_cloud_shadow_t", 4, {m[1], m[5], m[9], m[13]}, 0},
        {"sky_cloud_shadow_far", 1, {map->mean}, 0},
    };
    sky_gl_host_uniforms(&s->core, program, u, (int)(sizeof u / sizeof u[0]), texture_unit, map->texture);
    return SKY_OK;
}
