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

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The layers, back to front: the dome (the atmosphere with the night
 * backdrop behind and the clouds in front), the catalogue stars added over
 * it, the moon, the sun. Layers with a dome role live in the dome's
 * program and draw nothing themselves. */
static const sky_layer_class *const layer_table[] = {
    &sky_dome_layer, &sky_clouds_layer, &sky_flicker_layer, &sky_starmap_layer,
    &sky_airglow_layer, &sky_zodiacal_layer, &sky_stars_layer, &sky_planets_layer,
    &sky_moon_layer, &sky_sun_layer,
};
#define LAYER_COUNT ((int)(sizeof layer_table / sizeof layer_table[0]))

/* Runs its body for each layer this sky has (those its features left out
 * have no state), in the table's order, with L its class and state its
 * state; `continue` goes on to the next layer. */
#define FOR_EACH_LAYER(s, L, state)                                                                     \
    for (int layer_i_ = 0; layer_i_ < LAYER_COUNT; layer_i_++)                                         \
        for (const sky_layer_class *L = layer_table[layer_i_]; L; L = NULL)                             \
            for (void *state = (s)->layer_state[L->slot]; state; state = NULL)

/* The message for sky_last_error, and the code to return. */
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static sky_result sky_fail(sky *s, sky_result code, const char *fmt, ...)
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

const char *sky_layer_name(sky_layer layer)
{
    static const char *const names[SKY_LAYER_COUNT] = {"starmap", "stars", "flicker", "moon",
                                                       "atmosphere", "sun", "clouds", "planets",
                                                       "airglow",    "zodiacal"};
    return (unsigned)layer < SKY_LAYER_COUNT ? names[layer] : "unknown";
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
    FOR_EACH_LAYER(s, L, state) {
        if (L->frame) L->frame(c, state);
    }
    /* the naked eye's limit against the finished sky (the layers' glows
     * in it), once a frame for every set of points and the star map */
    f->naked_eye_limit = (float)sky_point_limit(c);
}

/* ---- lifecycle ------------------------------------------------------------- */

sky *sky_create(const sky_config *cfg, char *err, size_t err_len)
{
    if (err && err_len) err[0] = '\0';
    if (!cfg) {
        sky_format(err, err_len, "sky_create: config is NULL (a zeroed sky_config with get_proc_address set is enough)");
        return NULL;
    }
    if (!cfg->get_proc_address) {
        sky_format(err, err_len, "sky_create: get_proc_address is NULL; pass the host's GL loader");
        return NULL;
    }
    if ((unsigned)cfg->atmosphere > SKY_ATMOSPHERE_BLEND || (unsigned)cfg->gl_profile > SKY_GL_ES20 ||
        (unsigned)cfg->output > SKY_OUTPUT_HDR) {
        sky_format(err, err_len, "sky_create: atmosphere %d, gl_profile %d or output %d is out of range",
                   (int)cfg->atmosphere, (int)cfg->gl_profile, (int)cfg->output);
        return NULL;
    }
    if (cfg->blend_partner != SKY_ATMOSPHERE_DEFAULT && cfg->blend_partner != SKY_ATMOSPHERE_RAYLEIGH &&
        cfg->blend_partner != SKY_ATMOSPHERE_PREETHAM) {
        sky_format(err, err_len,
                   "sky_create: blend_partner %d is not an analytic path the blend can mix (0 = RAYLEIGH, "
                   "SKY_ATMOSPHERE_RAYLEIGH or SKY_ATMOSPHERE_PREETHAM)",
                   (int)cfg->blend_partner);
        return NULL;
    }
    if (cfg->blend_manual && !(cfg->blend_weight >= 0.0f && cfg->blend_weight <= 1.0f)) {
        sky_format(err, err_len, "sky_create: blend_weight %g is out of range (0..1)", (double)cfg->blend_weight);
        return NULL;
    }
    {
        const sky_lut_settings *l = &cfg->luts;
        const int sizes[] = {l->transmittance_width, l->transmittance_height, l->multiscatter_size,
                             l->skyview_width, l->skyview_height};
        const int steps[] = {l->transmittance_steps, l->multiscatter_directions, l->multiscatter_steps,
                             l->skyview_steps};
        for (size_t i = 0; i < sizeof sizes / sizeof sizes[0]; i++)
            if (sizes[i] != 0 && (sizes[i] < 4 || sizes[i] > 1024)) {
                sky_format(err, err_len, "sky_create: luts: a table size of %d is out of range (0 = default, 4..1024)",
                           sizes[i]);
                return NULL;
            }
        for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++)
            if (steps[i] != 0 && (steps[i] < 1 || steps[i] > 256)) {
                sky_format(err, err_len, "sky_create: luts: a sample count of %d is out of range (0 = default, 1..256)",
                           steps[i]);
                return NULL;
            }
    }
    if ((unsigned)cfg->tone_map > SKY_TONE_MAP_NEUTRAL) {
        sky_format(err, err_len, "sky_create: tone_map %d is out of range (hue, filmic or neutral)", (int)cfg->tone_map);
        return NULL;
    }
    if ((unsigned)cfg->depth > SKY_DEPTH_FAR_ZERO_CLIP01) {
        sky_format(err, err_len, "sky_create: depth %d is out of range (a sky_depth)", (int)cfg->depth);
        return NULL;
    }
    if (cfg->dome_divisor < 0 || cfg->dome_divisor > 8) {
        sky_format(err, err_len, "sky_create: dome_divisor %d is out of range (0 = default, 1..8)", cfg->dome_divisor);
        return NULL;
    }
    if (!isfinite(cfg->turbidity) || (cfg->turbidity != 0.0f && (cfg->turbidity < 1.0f || cfg->turbidity > 64.0f))) {
        sky_format(err, err_len, "sky_create: turbidity %g is out of range (0 = default, or 1..64)",
                   (double)cfg->turbidity);
        return NULL;
    }
    if ((cfg->features & SKY_FEATURES_NONE) && cfg->features != SKY_FEATURES_NONE) {
        sky_format(err, err_len, "sky_create: features 0x%x: SKY_FEATURES_NONE (an empty sky) cannot be combined "
                   "with other features", cfg->features);
        return NULL;
    }
    if (!isfinite(cfg->moon_scale) || (cfg->moon_scale != 0.0f && (cfg->moon_scale < 0.5f || cfg->moon_scale > 50.0f))) {
        sky_format(err, err_len, "sky_create: moon_scale %g is out of range (0 = default, or 0.5..50)",
                   (double)cfg->moon_scale);
        return NULL;
    }
    if (!isfinite(cfg->exposure_range) ||
        (cfg->exposure_range != 0.0f && (cfg->exposure_range < 0.01f || cfg->exposure_range > 16.0f))) {
        sky_format(err, err_len, "sky_create: exposure_range %g is out of range (0 = default, or 0.01..16 stops)",
                   (double)cfg->exposure_range);
        return NULL;
    }
    if (!isfinite(cfg->star_control_magnitude) ||
        (cfg->star_control_magnitude != 0.0f && (cfg->star_control_magnitude < 1.0f || cfg->star_control_magnitude > 10.0f))) {
        sky_format(err, err_len, "sky_create: star_control_magnitude %g is out of range (0 = default, or 1..10)",
                   (double)cfg->star_control_magnitude);
        return NULL;
    }
    if (cfg->solar_activity_manual != 0 && cfg->solar_activity_manual != 1) {
        sky_format(err, err_len, "sky_create: solar_activity_manual %d is neither 0 (from the date) nor 1",
                   cfg->solar_activity_manual);
        return NULL;
    }
    if (cfg->solar_activity_manual && !(cfg->solar_activity >= 0.0f && cfg->solar_activity <= 1.0f)) {
        sky_format(err, err_len, "sky_create: solar_activity %g is out of range (0 = minimum .. 1 = maximum)",
                   (double)cfg->solar_activity);
        return NULL;
    }
    if (!(cfg->bortle == 0.0f || (cfg->bortle >= 1.0f && cfg->bortle <= 9.0f))) {
        sky_format(err, err_len, "sky_create: bortle %g is out of range (0 = no light pollution, or 1..9)",
                   (double)cfg->bortle);
        return NULL;
    }
    unsigned features = cfg->features == 0 ? SKY_FEATURES_DEFAULT
                        : cfg->features == SKY_FEATURES_NONE ? 0u : cfg->features;
    if (features & ~(unsigned)SKY_FEATURES_AVAILABLE) {
        sky_format(err, err_len, "sky_create: features 0x%x are not built yet (available: 0x%x)",
                   features & ~(unsigned)SKY_FEATURES_AVAILABLE, (unsigned)SKY_FEATURES_AVAILABLE);
        return NULL;
    }
    if ((features & SKY_LUNAR_ECLIPSE) && !(features & SKY_MOON)) {
        sky_format(err, err_len, "sky_create: SKY_LUNAR_ECLIPSE needs SKY_MOON (the eclipse is drawn on the moon)");
        return NULL;
    }
    sky_atmosphere_params described = cfg->atmosphere_params, atm;
    if (sky_atmosphere_is_zero(&described)) sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &described);
    char atm_err[160];
    if (sky_atmosphere_check(&described, atm_err, sizeof atm_err) != SKY_OK) {
        sky_format(err, err_len, "sky_create: %s", atm_err);
        return NULL;
    }
    /* the haze knob: the description's aerosol at cfg->turbidity (turbidity
     * was checked above: 0 or 1..64) */
    sky_atmosphere_with_turbidity(&described, cfg->turbidity, &atm);
    float horizon_to_world[9];
    if (sky_camera_horizon_to_world(cfg->horizon_to_world, horizon_to_world)) {
        sky_format(err, err_len,
                   "sky_create: horizon_to_world is not orthonormal (its columns must be unit vectors at right "
                   "angles: a rotation, or a reflection for a left-handed world; all zero = identity)");
        return NULL;
    }

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
    for (int i = 0; i < LAYER_COUNT; i++) {
        const sky_layer_class *L = layer_table[i];
        if (L->feature && !(features & L->feature)) continue;
        s->layer_state[L->slot] = calloc(1, L->state_size ? L->state_size : 1);
        if (!s->layer_state[L->slot]) {
            sky_format(err, err_len, "sky_create: out of memory");
            goto fail;
        }
        sky_dome_snippets *d = &s->dome_snippets;
        if (L->dome_role == SKY_DOME_FRONT) d->front[d->front_count++] = L->dome_snippet;
        if (L->dome_role == SKY_DOME_NIGHT) d->night[d->night_count++] = L->dome_snippet;
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
    FOR_EACH_LAYER(s, L, state) {
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
    for (int i = LAYER_COUNT - 1; i >= 0; i--) {
        const sky_layer_class *L = layer_table[i];
        if (s->layer_state[L->slot] && L->destroy) L->destroy(c, s->layer_state[L->slot]);
        free(s->layer_state[L->slot]);
    }
    sky_atmosphere_destroy(c);
    if (c->gl.glDeleteTextures) /* NULL when sky_gl_init failed early */
        for (int i = 0; i < SKY_TEX_COUNT; i++) sky_texture_destroy(c, (sky_texture_id)i);
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

sky_result sky_update(sky *s, double dt)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!isfinite(dt) || dt < 0.0)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_update: dt = %g must be finite and >= 0", dt);
    FOR_EACH_LAYER(s, L, state) {
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
    FOR_EACH_LAYER(s, L, state) {
        if (L->reset_clock) L->reset_clock(state);
    }
    return sky_update(s, seconds);
}

/* ---- drawing --------------------------------------------------------------------- */

static void reset_layer_stats(sky *s)
{
    for (int l = 0; l < SKY_LAYER_COUNT; l++) {
        s->stats.layers[l].drawn = 0;
        s->stats.layers[l].draws = 0;
        s->stats.layers[l].ms = -1.0;
    }
    s->stats.draws_per_frame = 0;
    /* table builds since the last draw (sky_update, sky_set_params, ...) */
    s->stats.lut_ms = s->core.lut_ms;
    s->core.lut_ms = 0.0;
}

/* Draws one layer, timed when the host asked for per-layer timings. */
static void draw_layer(sky *s, const sky_layer_class *L, void *state)
{
    sky_core *c = &s->core;
    sky_layer_stats *st = &s->stats.layers[L->slot];
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
    FOR_EACH_LAYER(s, L, state) {
        if (L->view) L->view(c, state);
    }
    /* which of the dome's snippets show: the dome picks its variant */
    c->dome_front_shows = c->dome_night_shows = 0;
    FOR_EACH_LAYER(s, L, state) {
        if (L->dome_role == SKY_DOME_NONE) continue;
        int shows = L->visible(c, state);
        s->stats.layers[L->slot].drawn = shows;
        if (L->dome_role == SKY_DOME_FRONT) c->dome_front_shows |= shows;
        if (L->dome_role == SKY_DOME_NIGHT) c->dome_night_shows |= shows;
    }
    FOR_EACH_LAYER(s, L, state) {
        if (c->capture_without_sun && L->slot == SKY_LAYER_SUN) continue;
        if (L->draw && L->visible(c, state)) draw_layer(s, L, state);
    }
    if (!c->cfg.check_gl_errors) return SKY_OK;
    GLenum e = sky_gl_error(c);
    if (e != GL_NO_ERROR) return sky_fail(s, SKY_ERR_GL, "sky_draw: GL error 0x%04x", e);
    return SKY_OK;
}

static sky_result draw_with(sky *s, const float *view, const float *proj)
{
    double t0 = sky_now_ms();
    sky_core *c = &s->core;
    /* a context to draw in, and the sky's: found without glGetError */
    if (!sky_gl_context_current(c))
        return sky_fail(s, SKY_ERR_GL, "sky_draw: no GL context is current");
    if (!sky_gl_is_program(c, c->identity_program))
        return sky_fail(s, SKY_ERR_GL,
                        "sky_draw: the current GL context is not the one the sky was created in (a sky draws "
                        "only in its own context, or one sharing its objects)");
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
    sky_result rc = draw_with(s, view, proj);
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

sky_result sky_capture_environment(sky *s, unsigned cube_texture, int face_size, int face, unsigned flags)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    sky_core *c = &s->core;
    const sky_gl *gl = &c->gl;
    if (face_size < 4 || face_size > 2048 || (face_size & (face_size - 1)))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: face_size %d is not a power of two "
                        "in 4..2048", face_size);
    if (face < SKY_CAPTURE_ALL_FACES || face > 5)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: face %d is not 0..5 or "
                        "SKY_CAPTURE_ALL_FACES", face);
    if (flags & ~SKY_CAPTURE_SUN_DISC)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: unknown flags 0x%x", flags);
    if (!sky_gl_context_current(c)) return sky_fail(s, SKY_ERR_GL, "sky_capture_environment: no GL context is current");
    int hdr = c->cfg.output == SKY_OUTPUT_HDR;
    if (hdr && c->profile != SKY_GL_CORE33 && !cube_texture)
        return sky_fail(s, SKY_ERR_UNSUPPORTED, "sky_capture_environment: HDR output in %s is captured into "
                        "the host's float cube map only (the library's textures there are 8-bit)",
                        c->profile == SKY_GL_ES20 ? "ES20" : "COMPAT20");
    GLint limit = 0;
    gl->glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &limit);
    if (limit > 0 && face_size > limit)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: face_size %d is over this context's "
                        "limit %d", face_size, (int)limit);
    /* without framebuffer objects each face is drawn into the host's
     * draw buffer at its viewport's corner and copied from there */
    int backbuffer = !c->caps.render_to_rgba8;
    if (backbuffer) {
        GLint vp[4] = {0, 0, 0, 0};
        gl->glGetIntegerv(GL_VIEWPORT, vp);
        if (face_size > vp[2] || face_size > vp[3])
            return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: face_size %d does not fit the "
                            "viewport (%d x %d) it is drawn through: this %s context has no framebuffer objects",
                            face_size, (int)vp[2], (int)vp[3], c->gl_version);
    }
    /* the texture: the host's, checked, or our own at this size */
    sky_gl_state host;
    sky_gl_state_save(c, &host);
    GLuint tex = cube_texture;
    if (!tex) {
        sky_texture *own = &c->textures[SKY_TEX_ENVIRONMENT];
        if (own->id && own->width != face_size) sky_texture_destroy(c, SKY_TEX_ENVIRONMENT);
        char why[160];
        if (!own->id && sky_texture_create_cube(c, SKY_TEX_ENVIRONMENT, SKY_LAYER_ATMOSPHERE, NULL, face_size, hdr, why,
                                                sizeof why)) {
            sky_gl_state_restore(c, &host);
            return sky_fail(s, SKY_ERR_GL, "sky_capture_environment: %s", why);
        }
        tex = own->id;
    } else if (!c->caps.es) { /* (ES 2.0 cannot ask a texture its size: sky.h) */
        GLint w = 0;
        gl->glActiveTexture(GL_TEXTURE0);
        gl->glBindTexture(GL_TEXTURE_CUBE_MAP, tex);
        gl->glGetTexLevelParameteriv(GL_TEXTURE_CUBE_MAP_POSITIVE_X, 0, GL_TEXTURE_WIDTH, &w);
        sky_gl_state_restore(c, &host);
        if (w != face_size)
            return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_capture_environment: texture %u is not a cube map "
                            "with %d x %d faces (its +X level 0 is %d wide)", cube_texture, face_size, face_size,
                            (int)w);
    }
    if (!backbuffer && !s->capture_fbo) {
        c->gl.glGenFramebuffers(1, &s->capture_fbo);
        if (!s->capture_fbo) {
            sky_gl_state_restore(c, &host);
            return sky_fail(s, SKY_ERR_GL, "sky_capture_environment: no framebuffer object");
        }
    }
    GLint draw_fbo = 0, read_fbo = 0;
    if (!backbuffer) {
        gl->glGetIntegerv(GL_FRAMEBUFFER_BINDING, &draw_fbo);
        read_fbo = draw_fbo;
        if (c->caps.separate_framebuffers) gl->glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fbo);
    }
    sky_result rc = SKY_OK;
    c->capture_without_sun = !(flags & SKY_CAPTURE_SUN_DISC);
    c->capturing = 1;
    for (int f = face < 0 ? 0 : face; f <= (face < 0 ? 5 : face) && rc == SKY_OK; f++) {
        float view[16], proj[16];
        sky_capture_face_matrices(f, view, proj);
        if (backbuffer) {
            gl->glViewport(host.viewport[0], host.viewport[1], face_size, face_size);
            if ((rc = draw_with(s, view, proj)) != SKY_OK) break;
            gl->glActiveTexture(GL_TEXTURE0);
            gl->glBindTexture(GL_TEXTURE_CUBE_MAP, tex);
            gl->glCopyTexSubImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f, 0, 0, 0, host.viewport[0],
                                    host.viewport[1], face_size, face_size);
            continue;
        }
        gl->glBindFramebuffer(GL_FRAMEBUFFER, s->capture_fbo);
        gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_CUBE_MAP_POSITIVE_X + (GLenum)f,
                                   tex, 0);
        GLenum status = gl->glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE) {
            rc = sky_fail(s, SKY_ERR_GL, "sky_capture_environment: cannot render into face %d of texture %u "
                          "(framebuffer status 0x%04x: its format?)", f, tex, status);
            break;
        }
        gl->glViewport(0, 0, face_size, face_size);
        rc = draw_with(s, view, proj);
    }
    c->capture_without_sun = c->capturing = 0;
    for (int i = 0; i < 4; i++) s->capture_overwrote[i] = 0;
    if (backbuffer) {
        s->capture_overwrote[0] = host.viewport[0];
        s->capture_overwrote[1] = host.viewport[1];
        s->capture_overwrote[2] = s->capture_overwrote[3] = face_size;
    } else {
        gl->glBindFramebuffer(GL_FRAMEBUFFER, s->capture_fbo);
        gl->glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_CUBE_MAP_POSITIVE_X, 0, 0);
        if (c->caps.separate_framebuffers) {
            gl->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)draw_fbo);
            gl->glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)read_fbo);
        } else {
            gl->glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)draw_fbo);
        }
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

sky_result sky_draw_fisheye(sky *s)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    return draw_with(s, NULL, NULL);
}

/* ---- queries ----------------------------------------------------------------------- */

sky_result sky_get_stats(const sky *s, sky_stats *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    const sky_core *c = &s->core;
    *out = s->stats;
    out->gl_version = c->gl_version;
    out->profile = c->profile;
    out->features = c->features;
    out->lut_ms = s->stats.lut_ms;
    out->textures = 0;
    out->gpu_bytes = c->buffer_bytes;
    for (int l = 0; l < SKY_LAYER_COUNT; l++) {
        out->layers[l].bytes = 0;
        out->layers[l].enabled = 0;
    }
    for (int i = 0; i < SKY_TEX_COUNT; i++)
        if (c->textures[i].id) {
            out->textures++;
            out->gpu_bytes += c->textures[i].bytes;
            out->layers[c->textures[i].owner].bytes += c->textures[i].bytes;
        }
    FOR_EACH_LAYER(s, L, state) {
        out->layers[L->slot].enabled = 1;
        if (L->buffer_bytes) out->layers[L->slot].bytes += L->buffer_bytes(c, state);
    }
    out->programs = c->program_count;
    out->buffers = c->buffer_count;
    return SKY_OK;
}

int sky_layer_count(void) { return SKY_LAYER_COUNT; }

sky_result sky_get_layer_stats(const sky *s, int layer, sky_layer_stats *out)
{
    if (!s || !out || layer < 0 || layer >= SKY_LAYER_COUNT) return SKY_ERR_INVALID_ARGUMENT;
    sky_stats all;
    sky_get_stats(s, &all);
    *out = all.layers[layer];
    return SKY_OK;
}

sky_result sky_get_lighting(const sky *s, sky_lighting *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    const sky_core *c = &s->core;
    const sky_frame *f = &c->frame;
    memset(out, 0, sizeof *out);
    sky_camera_to_world(c, f->sun_dir, out->sun_direction);
    out->sun_altitude_deg = (float)(f->sun_altitude * 180.0 / SKY_PI);
    /* Solar illuminance above the atmosphere (sun.c: 128 klx at 1 au, what
     * the drawn disc sums to), through the atmosphere, times the part of
     * the disc not yet set */
    float above = (float)sky_disc_above_horizon(f->sun_altitude, c->astro.sun_semidiameter);
    /* and the share of its light a solar eclipse leaves */
    above *= (float)sky_solar_eclipse_light_left(c);
    float e0 = (float)sky_sun_illuminance_klx(c);
    for (int i = 0; i < 3; i++) out->sun_color[i] = e0 * f->sun_transmittance[i] * above;
    /* sky irradiance and horizon: the atmosphere path's (atmosphere.c) */
    for (int i = 0; i < 3; i++) {
        out->ambient_color[i] = f->ambient_rgb[i];
        out->fog_color[i] = f->fog_rgb[i];
    }
    out->daylight = f->daylight;
    out->exposure = f->exposure;
    if (c->features & SKY_MOON) {
        sky_camera_to_world(c, f->moon_dir, out->moon_direction);
        sky_moon_lighting(c, out->moon_color);
    }
    return SKY_OK;
}

sky_result sky_get_irradiance_sh(sky *s, sky_irradiance_sh *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    memset(out, 0, sizeof *out);
    const double(*sh)[3] = sky_irradiance_cached(&s->core, &s->irradiance);
    for (int k = 0; k < SKY_SH_COUNT; k++)
        for (int i = 0; i < 3; i++) {
            if (k < 9)
                out->radiance[k][i] = (float)sh[k][i];
            else if (k < 18)
                out->radiance_l4[k - 9][i] = (float)sh[k][i];
            else
                out->radiance_zonal[k - 18][i] = (float)sh[k][i];
        }
    float up_h[3] = {0.0f, 1.0f, 0.0f};
    sky_camera_to_world(&s->core, up_h, out->up);
    sky_lighting l;
    sky_get_lighting(s, &l);
    for (int i = 0; i < 3; i++) {
        out->sun_direction[i] = l.sun_direction[i];
        out->sun_color[i] = l.sun_color[i];
        out->moon_direction[i] = l.moon_direction[i];
        out->moon_color[i] = l.moon_color[i];
    }
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
    const sky_gl *gl = &c->gl;
    if (!view || !proj || !texture) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_aerial_froxels: NULL argument");
    float clip_to_dir[16];
    if (sky_camera_clip_to_horizon(c, view, proj, clip_to_dir))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_aerial_froxels: the camera is not finite, or its view or "
                        "projection is degenerate");
    if (c->profile != SKY_GL_CORE33 ||
        (c->atmosphere != SKY_ATMOSPHERE_HILLAIRE && c->atmosphere != SKY_ATMOSPHERE_BLEND))
        return sky_fail(s, SKY_ERR_UNSUPPORTED, "sky_aerial_froxels: the froxel volume is Hillaire's, in CORE33 (the "
                        "hillaire and blend paths); sky_aerial_bind serves every path and profile");
    if (!sky_gl_context_current(c)) return sky_fail(s, SKY_ERR_GL, "sky_aerial_froxels: no GL context is current");
    /* the build binds its program, tables and framebuffer; the volume is
     * made on unit 0's 3D target the first time: the host's come back */
    sky_gl_state host;
    sky_gl_state_save(c, &host);
    GLint host_volume = 0;
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glGetIntegerv(GL_TEXTURE_BINDING_3D, &host_volume);
    if (s->vao) gl->glBindVertexArray(s->vao); /* a core context draws nothing without one */
    char why[200];
    int rc = sky_atmosphere_froxels(c, clip_to_dir, why, sizeof why);
    gl->glActiveTexture(GL_TEXTURE0);
    gl->glBindTexture(GL_TEXTURE_3D, (GLuint)host_volume);
    sky_gl_state_restore(c, &host);
    if (rc) return sky_fail(s, SKY_ERR_GL, "sky_aerial_froxels: %s", why);
    *texture = c->textures[SKY_TEX_FROXELS].id;
    return SKY_OK;
}

/* An embedded shader source for hosts, "" if this build lacks it. */
static const char *host_glsl(const char *name)
{
    const sky_blob *b = sky_find_blob(name);
    return b ? (const char *)b->data : "";
}

/* What both binders of the host's snippets check first (s not NULL). */
static sky_result host_program_check(sky *s, unsigned program, const char *what)
{
    if (!program) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "%s: program 0", what);
    if (!sky_gl_context_current(&s->core)) return sky_fail(s, SKY_ERR_GL, "%s: no GL context is current", what);
    return SKY_OK;
}

const char *sky_display_glsl(void) { return host_glsl("display.glsl"); }

sky_result sky_display_bind(sky *s, unsigned program)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    sky_result rc = host_program_check(s, program, "sky_display_bind");
    if (rc != SKY_OK) return rc;
    sky_core *c = &s->core;
    const sky_gl *gl = &c->gl;
    GLint host_program = 0;
    gl->glGetIntegerv(GL_CURRENT_PROGRAM, &host_program);
    gl->glUseProgram(program);
    const sky_frame *f = &c->frame;
    gl->glUniform1f(gl->glGetUniformLocation(program, "sky_display_exposure"), f->display_exposure);
    gl->glUniform1f(gl->glGetUniformLocation(program, "sky_display_rods"), f->night_shift);
    gl->glUniform1f(gl->glGetUniformLocation(program, "sky_display_cd"), f->display_cd);
    gl->glUseProgram((GLuint)host_program);
    return SKY_OK;
}

const char *sky_aerial_glsl(void) { return host_glsl("aerial.glsl"); }

sky_result sky_aerial_bind(sky *s, unsigned program, int texture_unit)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    sky_result rc = host_program_check(s, program, "sky_aerial_bind");
    if (rc != SKY_OK) return rc;
    sky_core *c = &s->core;
    const sky_gl *gl = &c->gl;
    GLint units = 0;
    gl->glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
    if (texture_unit < 0 || (units > 0 && texture_unit >= units))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_aerial_bind: texture unit %d is not 0..%d", texture_unit,
                        (int)units - 1);
    int rebuilt = sky_aerial_table(c, &s->aerial);
    if (rebuilt < 0) return sky_fail(s, SKY_ERR_OUT_OF_MEMORY, "sky_aerial_bind: out of memory for the table");
    GLint host_program = 0, host_unit = 0;
    gl->glGetIntegerv(GL_CURRENT_PROGRAM, &host_program);
    gl->glGetIntegerv(GL_ACTIVE_TEXTURE, &host_unit);
    if (!c->textures[SKY_TEX_AERIAL].id || !s->aerial.uploaded) {
        /* the upload binds on unit 0 and sets the unpack state: the host's
         * come back */
        sky_gl_state host;
        sky_gl_state_save(c, &host);
        char why[160];
        if (!c->textures[SKY_TEX_AERIAL].id) {
            if (sky_texture_create(c, SKY_TEX_AERIAL, SKY_LAYER_ATMOSPHERE, s->aerial.texels, 4, SKY_AP_TABLE_W,
                                   SKY_AP_TABLE_H, 0, why, sizeof why)) {
                sky_gl_state_restore(c, &host);
                return sky_fail(s, SKY_ERR_GL, "sky_aerial_bind: %s", why);
            }
        } else {
            sky_texture_update_lut(c, SKY_TEX_AERIAL, SKY_AP_TABLE_W, SKY_AP_TABLE_H, s->aerial.texels, NULL);
        }
        sky_gl_state_restore(c, &host);
        s->aerial.uploaded = 1;
    }
    /* the uniforms, in the host's program; its own program and active
     * unit come back, the table stays bound on texture_unit */
    float up_h[3] = {0.0f, 1.0f, 0.0f}, sun_h[3], up[3], sun[3];
    const float *sd = c->frame.sun_dir;
    double across = hypot(sd[0], sd[2]);
    sun_h[0] = across > 1e-9 ? (float)(sd[0] / across) : 1.0f;
    sun_h[1] = 0.0f;
    sun_h[2] = across > 1e-9 ? (float)(sd[2] / across) : 0.0f;
    sky_camera_to_world(c, up_h, up);
    sky_camera_to_world(c, sun_h, sun);
    gl->glUseProgram(program);
    gl->glActiveTexture(GL_TEXTURE0 + (GLenum)texture_unit);
    gl->glBindTexture(GL_TEXTURE_2D, c->textures[SKY_TEX_AERIAL].id);
    gl->glUniform1i(gl->glGetUniformLocation(program, "sky_aerial_table"), texture_unit);
    gl->glUniform3f(gl->glGetUniformLocation(program, "sky_aerial_up"), up[0], up[1], up[2]);
    gl->glUniform3f(gl->glGetUniformLocation(program, "sky_aerial_sun"), sun[0], sun[1], sun[2]);
    double r0, rt;
    sky_aerial_shell(c, &s->aerial, &r0, &rt);
    gl->glUniform4f(gl->glGetUniformLocation(program, "sky_aerial_params"), (float)s->aerial.scale,
                    (float)SKY_AP_TABLE_M, (float)(r0 * 1000.0), (float)(rt * 1000.0));
    gl->glActiveTexture((GLenum)host_unit);
    gl->glUseProgram((GLuint)host_program);
    return SKY_OK;
}

sky_result sky_irradiance_sh_eval(const sky_irradiance_sh *sh, const float normal[3], float irradiance[3])
{
    if (!sh || !normal || !irradiance) return SKY_ERR_INVALID_ARGUMENT;
    irradiance[0] = irradiance[1] = irradiance[2] = 0.0f;
    double len = 0.0;
    for (int i = 0; i < 3; i++) {
        if (!isfinite(normal[i])) return SKY_ERR_INVALID_ARGUMENT;
        len += (double)normal[i] * normal[i];
    }
    len = sqrt(len);
    if (!(len > 0.0) || !isfinite(len)) return SKY_ERR_INVALID_ARGUMENT;
    double n[3] = {normal[0] / len, normal[1] / len, normal[2] / len}, c[SKY_SH_COUNT][3], e[3];
    double up[3] = {sh->up[0], sh->up[1], sh->up[2]};
    for (int k = 0; k < SKY_SH_COUNT; k++)
        for (int i = 0; i < 3; i++)
            c[k][i] = k < 9 ? sh->radiance[k][i] : k < 18 ? sh->radiance_l4[k - 9][i] : sh->radiance_zonal[k - 18][i];
    sky_irradiance_eval(c, n, up, e);
    /* a degree-2 sum can dip below zero facing a dark hemisphere */
    for (int i = 0; i < 3; i++) irradiance[i] = (float)fmax(e[i], 0.0);
    return SKY_OK;
}
