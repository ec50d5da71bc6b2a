/*
 * libsky: the public API and the composition. The rooms below it (see
 * docs/ARCHITECTURE.md) each own their part of the frame; this file
 * checks what the host passes, runs the stages in their one-way order
 * (parameters -> astronomy -> atmosphere -> exposure -> layers), and walks
 * the layer table back to front to draw.
 */
#include "sky_internal.h"
#include "aerial.h"
#include "irradiance.h"
#include "points.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
sky_result sky_fail(sky *s, sky_result code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->error, sizeof s->error, fmt, ap);
    va_end(ap);
    return code;
}

const char *sky_last_error(const sky *s) { return s ? s->error : "sky is NULL"; }

unsigned sky_version(void)
{
    return ((unsigned)SKY_VERSION_MAJOR << 16) | ((unsigned)SKY_VERSION_MINOR << 8) | (unsigned)SKY_VERSION_PATCH;
}

sky_params sky_default_params(void)
{
    sky_params p = {0.45f, 0.5f, 0.3f, 0.1f, 0.2f, 0.45f};
    return p;
}

/* ---- the frame's stages ------------------------------------------------------ */

/* The astronomy for the observer and the time slider. The observer was
 * validated when set; only a time slider pushing a date at the very end
 * of the supported span past it can fail here, and then the last valid
 * state is kept. */
static void astronomy_stage(sky_core *c)
{
    sky_astro a;
    if (sky_observer_astro(&c->observer, c->params.time, &c->astro_cache, &a, NULL, 0) == 0) c->astro = a;
    sky_frame *f = &c->frame;
    for (int i = 0; i < 3; i++) f->sun_dir[i] = (float)c->astro.sun.dir[i];
    for (int i = 0; i < 3; i++) f->moon_dir[i] = (float)c->astro.moon.dir[i];
    f->sun_altitude = (float)c->astro.sun.alt; /* apparent: what the eye sees */
    f->refraction_pressure = (float)c->astro.pressure_factor;
    /* Mueller sec. 5 star fade (astro.c) */
    f->night = (float)c->astro.star_visibility;
}

/* Everything that depends on the sliders and the observer, not on the
 * camera: the stages in order, then each layer's part. */
static void compute_frame(sky *s)
{
    sky_core *c = &s->core;
    sky_frame *f = &c->frame;
    sky_weather_frame(c);
    astronomy_stage(c);
    f->output_hdr = c->cfg.output == SKY_OUTPUT_HDR ? 1.0f : 0.0f;
    sky_atmosphere_frame(c);
    /* R-P's "amount of sunlight" from the time of day: full above 10
     * degrees, none below -6 (end of civil twilight); a solar eclipse
     * takes the sun's share of it away (the clouds' sunlit side, the
     * host's daylight). */
    double sin_alt = sin(f->sun_altitude);
    f->daylight = (float)sky_smoothstep(sin(-6.0 * SKY_PI / 180.0), sin(10.0 * SKY_PI / 180.0), sin_alt) *
                  (float)sky_solar_eclipse_light_left(c);
    sky_exposure_frame(c);
    FOR_EACH_LAYER(s, L, index, state) {
        if (L->frame) L->frame(c, state);
    }
    sky_weather_light(c);
    /* the naked eye's limit against the finished sky (the layers' glows
     * in it), once a frame for every set of points and the star map */
    f->naked_eye_limit = (float)sky_point_limit(c);
}

/* ---- lifecycle ------------------------------------------------------------- */

sky *sky_create(const sky_config *cfg, char *err, size_t err_len)
{
    if (err && err_len) err[0] = '\0';
    unsigned features;
    sky_atmosphere_params atm;
    float horizon_to_world[9];
    if (sky_config_check(cfg, &features, &atm, horizon_to_world, err, err_len)) return NULL;

    sky *s = calloc(1, sizeof *s);
    if (!s) {
        sky_format(err, err_len, "sky_create: out of memory");
        return NULL;
    }
    sky_core *c = &s->core;
    sky_gl_state host; /* saved once the GL functions are loaded */
    int saved = 0;
    c->cfg = *cfg; /* texture_dir is the caller's string: used during create only */
    c->features = features;
    c->atm = atm;
    sky_atmosphere_effective(&atm, &c->atm_rgb);
    sky_sun_irradiance_rgb(c->sun_irradiance_klx);
    c->atmosphere = cfg->atmosphere == SKY_ATMOSPHERE_DEFAULT ? SKY_ATMOSPHERE_GRADIENT : cfg->atmosphere;
    memcpy(c->horizon_to_world, horizon_to_world, sizeof horizon_to_world);
    const float *m = horizon_to_world; /* columns a, b, c: det = a . (b x c) */
    double det = m[0] * ((double)m[4] * m[8] - (double)m[5] * m[7]) - m[1] * ((double)m[3] * m[8] - (double)m[5] * m[6]) +
                 m[2] * ((double)m[3] * m[7] - (double)m[4] * m[6]);
    c->horizon_handedness = det < 0.0 ? -1 : 1;
    c->params = sky_default_params();
    /* the far plane's clip z / w in the host's depth convention */
    c->frame.far_z = cfg->depth == SKY_DEPTH_FAR_ZERO ? -1.0f : cfg->depth == SKY_DEPTH_FAR_ZERO_CLIP01 ? 0.0f : 1.0f;
    c->observer = sky_default_observer();
    c->dome_snippets = &s->dome_snippets;
    sky_dome_snippets *d = &s->dome_snippets;
    c->texture_count = c->texture_capacity = SKY_TEX_COUNT;
    c->textures = calloc(SKY_TEX_COUNT, sizeof *c->textures);
    s->layer_state = calloc(sky_layer_table_size, sizeof *s->layer_state);
    s->layer_stats = calloc(sky_layer_table_size, sizeof *s->layer_stats);
    d->front = calloc(sky_layer_table_size, sizeof *d->front);
    d->night = calloc(sky_layer_table_size, sizeof *d->night);
    d->optics = calloc(sky_layer_table_size, sizeof *d->optics);
    d->occasional = calloc(sky_layer_table_size, sizeof *d->occasional);
    c->glows = calloc(sky_layer_table_size, sizeof *c->glows);
    if (!c->textures || !s->layer_state || !s->layer_stats || !d->front || !d->night || !d->optics ||
        !d->occasional || !c->glows) {
        sky_format(err, err_len, "sky_create: out of memory");
        goto fail;
    }
    for (int row = 0; row < sky_layer_table_size; row++) {
        const sky_layer_class *L = sky_layer_table[row];
        int index = sky_layer_table_index(row);
        if (L->feature && !(features & L->feature)) continue;
        void *state = s->layer_state[index] = calloc(1, L->state_size ? L->state_size : 1);
        if (!state || (L->dome_role != SKY_DOME_NONE && sky_snippet_bind(c, L->dome_snippet, state))) {
            sky_format(err, err_len, "sky_create: out of memory");
            goto fail;
        }
        if (L->dome_role == SKY_DOME_FRONT) d->front[d->front_count++] = L->dome_snippet;
        if (L->dome_role == SKY_DOME_NIGHT) d->night[d->night_count++] = L->dome_snippet;
        if (L->dome_role == SKY_DOME_OPTICS) d->optics[d->optics_count++] = L->dome_snippet;
        if (L->dome_role == SKY_DOME_NIGHT_OCCASIONAL) d->occasional[d->occasional_count++] = L->dome_snippet;
        if (L->glow_at) c->glows[c->glow_count++] = (sky_glow_source){L, state};
    }

    if (sky_gl_init(c, err, err_len)) goto fail;
    /* what creating binds and sets (buffers, textures, units, the pixel
     * store, the VAO) is the host's again when sky_create returns */
    sky_gl_state_save(c, &host);
    saved = 1;
    if (c->caps.vertex_arrays) s->vao = sky_gl_vertex_array_create(c);
    c->dome_divisor = sky_dome_divisor_for(c);
    c->dome_day_divisor = sky_dome_day_divisor_for(c);
    astronomy_stage(c); /* the default observer's: the stars start at its epoch */
    if (sky_atmosphere_create(c, err, err_len)) goto fail;
    FOR_EACH_LAYER(s, L, index, state) {
        c->creating_layer = (sky_layer)index;
        if (L->create && L->create(c, state, err, err_len)) goto fail;
    }
    c->cfg.texture_dir = NULL;
    GLenum e = sky_gl_error(c);
    if (e != GL_NO_ERROR) {
        sky_format(err, err_len, "sky_create: GL error 0x%04x while creating resources", e);
        goto fail;
    }
    compute_frame(s);
    sky_gl_state_restore(c, &host);
    return s;
fail:
    c->cfg.texture_dir = NULL;
    if (saved) sky_gl_state_restore(c, &host);
    sky_destroy(s);
    return NULL;
}

void sky_destroy(sky *s)
{
    if (!s) return;
    sky_core *c = &s->core;
    for (int row = sky_layer_table_size - 1; row >= 0 && s->layer_state; row--) {
        const sky_layer_class *L = sky_layer_table[row];
        void *state = s->layer_state[sky_layer_table_index(row)];
        if (state && L->destroy) L->destroy(c, state);
        free(state);
    }
    free(s->layer_state);
    free(s->layer_stats);
    free(s->dome_snippets.front);
    free(s->dome_snippets.night);
    free(s->dome_snippets.optics);
    free(s->dome_snippets.occasional);
    sky_atmosphere_destroy(c);
    if (c->gl.glDeleteTextures) /* NULL when sky_gl_init failed early */
        for (int i = 0; i < c->texture_count; i++) sky_texture_destroy(c, (sky_texture_id)i);
    free(c->textures);
    free(c->snippet_bindings);
    free(c->glows);
    if (s->vao) sky_gl_vertex_array_destroy(c, s->vao);
    sky_gl_target_destroy(c, s->capture_fbo);
    sky_aerial_free(&s->aerial);
    free(s);
}

/* ---- parameters and time ----------------------------------------------------- */

sky_result sky_set_params(sky *s, const sky_params *p)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!p) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_params: params is NULL");
    const float in[6] = {p->cover, p->height, p->density, p->sunset, p->speed, p->time};
    static const char *const names[6] = {"cover", "height", "density", "sunset", "speed", "time"};
    float out[6];
    sky_result rc = SKY_OK;
    for (int i = 0; i < 6; i++) {
        if (isnan(in[i])) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_params: %s is NaN", names[i]);
        out[i] = sky_clampf(in[i], 0.0f, 1.0f); /* also takes +-Inf to 1 / 0 */
        if (out[i] != in[i])
            rc = sky_fail(s, SKY_CLAMPED, "sky_set_params: %s = %g clamped to %g (range 0..1)", names[i],
                          (double)in[i], (double)out[i]);
    }
    s->core.params.cover = out[0];
    s->core.params.height = out[1];
    s->core.params.density = out[2];
    s->core.params.sunset = out[3];
    s->core.params.speed = out[4];
    s->core.params.time = out[5];
    compute_frame(s);
    return rc;
}

sky_result sky_set_observer(sky *s, const sky_observer *o)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!o) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_observer: observer is NULL");
    if (sky_observer_check(o, s->error, sizeof s->error)) return SKY_ERR_INVALID_ARGUMENT;
    sky_astro a;
    if (sky_observer_astro(o, s->core.params.time, &s->core.astro_cache, &a, s->error, sizeof s->error))
        return SKY_ERR_INVALID_ARGUMENT;
    s->core.observer = *o;
    compute_frame(s);
    return SKY_OK;
}

sky_result sky_get_observer(const sky *s, sky_observer *o)
{
    if (!s || !o) return SKY_ERR_INVALID_ARGUMENT;
    *o = s->core.observer;
    return SKY_OK;
}

sky_result sky_get_astronomy(const sky *s, sky_astronomy *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    sky_astronomy_from_astro(&s->core.astro, out);
    /* the planets layer's places of this frame; without it, computed now */
    const void *planets = s->layer_state[SKY_LAYER_PLANETS];
    if (planets)
        sky_planets_out(sky_planets_places(planets), out);
    else
        sky_planets_fill(&s->core.astro, out);
    return SKY_OK;
}

sky_result sky_get_params(const sky *s, sky_params *p)
{
    if (!s || !p) return SKY_ERR_INVALID_ARGUMENT;
    *p = s->core.params;
    return SKY_OK;
}

sky_result sky_set_exposure_bias(sky *s, float ev)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (isnan(ev)) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_exposure_bias: ev is NaN");
    float c = sky_clampf(ev, -10.0f, 10.0f);
    s->core.exposure_bias = c;
    compute_frame(s);
    if (c != ev) return sky_fail(s, SKY_CLAMPED, "sky_set_exposure_bias: %g clamped to %g (range -10..10)", (double)ev, (double)c);
    return SKY_OK;
}

sky_result sky_set_kp(sky *s, float kp)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (isnan(kp)) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_kp: kp is NaN");
    float c = sky_clampf(kp, 0.0f, 9.0f);
    s->core.cfg.kp = c;
    compute_frame(s);
    if (c != kp) return sky_fail(s, SKY_CLAMPED, "sky_set_kp: %g clamped to %g (range 0..9)", (double)kp, (double)c);
    return SKY_OK;
}

sky_result sky_update(sky *s, double dt)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!isfinite(dt) || dt < 0.0)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_update: dt = %g must be finite and >= 0", dt);
    /* the running clock is not wrapped: the weather's transitions are
     * placed on it (a double keeps a millisecond for a hundred thousand years) */
    s->core.running_before = s->core.running;
    s->core.running += dt;
    FOR_EACH_LAYER(s, L, index, state) {
        if (L->advance) L->advance(&s->core, state, dt);
    }
    compute_frame(s);
    return SKY_OK;
}

sky_result sky_set_elapsed(sky *s, double seconds)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!isfinite(seconds) || seconds < 0.0)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_elapsed: %g must be finite and >= 0", seconds);
    FOR_EACH_LAYER(s, L, index, state) {
        if (L->reset_clock) L->reset_clock(state);
    }
    s->core.running = 0.0;
    return sky_update(s, seconds);
}

/* ---- drawing --------------------------------------------------------------------- */

static void reset_layer_stats(sky *s)
{
    for (int l = 0; l < sky_layer_table_size; l++) {
        s->layer_stats[l].drawn = 0;
        s->layer_stats[l].draws = 0;
        s->layer_stats[l].ms = -1.0;
    }
    s->stats.draws_per_frame = 0;
    /* table builds since the last draw (sky_update, sky_set_params, ...) */
    s->stats.lut_ms = s->core.lut_ms;
    s->core.lut_ms = 0.0;
}

/* Draws one layer, timed when the host asked for per-layer timings. */
static void draw_layer(sky *s, const sky_layer_class *L, int index, void *state)
{
    sky_core *c = &s->core;
    sky_layer_stats *st = &s->layer_stats[index];
    double t0 = 0.0;
    if (c->cfg.profile_layers) {
        sky_gl_finish(c);
        t0 = sky_now_ms();
    }
    sky_gl_blend(c, L->blend);
    int draws = L->draw(c, state);
    if (c->cfg.profile_layers) {
        sky_gl_finish(c);
        st->ms = sky_now_ms() - t0;
    }
    st->drawn = 1;
    st->draws += draws;
    s->stats.draws_per_frame += draws;
}

static sky_result draw_frame(sky *s)
{
    sky_core *c = &s->core;
    sky_gl_frame_begin(c, s->vao);
    FOR_EACH_LAYER(s, L, index, state) {
        if (L->view) L->view(c, state);
    }
    /* which of the dome's snippets show: the dome picks its variant */
    c->dome_front_shows = c->dome_night_shows = c->dome_optics_shows = c->dome_occasional_shows = 0;
    FOR_EACH_LAYER(s, L, index, state) {
        if (L->dome_role == SKY_DOME_NONE) continue;
        int shows = L->visible(c, state);
        s->layer_stats[index].drawn = shows;
        if (L->dome_role == SKY_DOME_FRONT) c->dome_front_shows |= shows;
        if (L->dome_role == SKY_DOME_NIGHT) c->dome_night_shows |= shows;
        if (L->dome_role == SKY_DOME_OPTICS) c->dome_optics_shows |= shows;
        if (L->dome_role == SKY_DOME_NIGHT_OCCASIONAL) c->dome_occasional_shows |= shows;
    }
    FOR_EACH_LAYER(s, L, index, state) {
        if (c->capture_without_sun && L->slot == SKY_LAYER_SUN) continue;
        if (L->draw && L->visible(c, state)) draw_layer(s, L, index, state);
    }
    if (!c->cfg.check_gl_errors) return SKY_OK;
    GLenum e = sky_gl_error(c);
    if (e != GL_NO_ERROR) return sky_fail(s, SKY_ERR_GL, "sky_draw: GL error 0x%04x", e);
    return SKY_OK;
}

sky_result sky_own_context_check(sky *s, const char *what)
{
    /* a context, and the sky's: found without glGetError */
    if (!sky_gl_context_current(&s->core)) return sky_fail(s, SKY_ERR_GL, "%s: no GL context is current", what);
    if (!sky_gl_is_program(&s->core, s->core.identity_program))
        return sky_fail(s, SKY_ERR_GL,
                        "%s: the current GL context is not the one the sky was created in (a sky draws "
                        "only in its own context, or one sharing its objects)",
                        what);
    return SKY_OK;
}

sky_result sky_draw_view(sky *s, const float *view, const float *proj)
{
    double t0 = sky_now_ms();
    sky_core *c = &s->core;
    sky_result own = sky_own_context_check(s, "sky_draw");
    if (own != SKY_OK) return own;
    if (c->cfg.check_gl_errors) {
        GLenum pending = sky_gl_error(c);
        if (pending != GL_NO_ERROR)
            return sky_fail(s, SKY_ERR_GL, "sky_draw: GL error 0x%04x was pending before the call: the host's, "
                            "not the sky's (cfg.check_gl_errors)", pending);
    }
    sky_gl_state host;
    sky_gl_state_save(c, &host);
    c->drawing = 1;
    reset_layer_stats(s);
    memcpy(c->viewport, host.viewport, sizeof c->viewport);
    sky_result rc = SKY_OK;
    if (!view) {
        sky_camera_fisheye(c, host.viewport);
        sky_gl_clear_viewport(c, host.viewport);
    } else if (sky_camera_set(c, view, proj, host.viewport, s->error, sizeof s->error)) {
        rc = SKY_ERR_INVALID_ARGUMENT;
    }
    if (rc == SKY_OK) rc = draw_frame(s);
    sky_gl_state_restore(c, &host);
    c->drawing = 0;
    if (c->cfg.profile_layers) sky_gl_finish(c);
    s->stats.frame_ms = sky_now_ms() - t0;
    return rc;
}

sky_result sky_draw(sky *s, const float view[16], const float proj[16])
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!view || !proj) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_draw: view or proj is NULL");
    sky_result rc = sky_draw_view(s, view, proj);
    /* A projection whose clip w is +z in eye space is a left-handed one
     * (OpenGL's is -z); its world must come with a reflecting
     * horizon_to_world, or the sky is a mirror image (sky.h, Conventions). */
    if (rc == SKY_OK && isfinite(proj[11]) && (proj[11] > 0.0f) != (s->core.horizon_handedness < 0))
        return sky_fail(s, SKY_WARN_MIRRORED,
                        "sky_draw: drawn mirrored: the projection is %s-handed (clip w = %sz) but horizon_to_world "
                        "is a %s; a left-handed engine passes a reflecting one, such as diag(1, 1, -1) (sky.h, "
                        "Conventions)",
                        proj[11] > 0.0f ? "left" : "right", proj[11] > 0.0f ? "+" : "-",
                        s->core.horizon_handedness < 0 ? "reflection" : "rotation");
    return rc;
}

sky_result sky_draw_fisheye(sky *s)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    return sky_draw_view(s, NULL, NULL);
}

