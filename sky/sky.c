/*
 * libsky: lifecycle, parameters, per-frame composition and feature
 * selection. Each phenomenon lives in its own file; this one decides which
 * exist, computes the frame state they share, and draws them back to front.
 */
#include "sky_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* ---- helpers ------------------------------------------------------------- */

double sky_wrap(double x, double period)
{
    double r = fmod(x, period);
    if (r < 0.0) r += period;
    return r >= period ? 0.0 : r; /* fmod of -tiny + period rounds to period */
}

double sky_phase_advance(double phase, double rate, double dt)
{
    /* whole cycles leave dt first: rate * dt cannot overflow, and a step
     * shorter than one cycle is used exactly as given */
    if (rate == 0.0) return phase;
    return sky_wrap(phase + rate * sky_wrap(dt, 1.0 / fabs(rate)), 1.0);
}

double sky_smoothstep(double e0, double e1, double x)
{
    double t = sky_clampd((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

sky_result sky_fail(sky *s, sky_result code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->error, sizeof s->error, fmt, ap);
    va_end(ap);
    return code;
}

void sky_format(char *buf, size_t len, const char *fmt, ...)
{
    if (!buf || len == 0) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, len, fmt, ap);
    va_end(ap);
}

const char *sky_last_error(const sky *s) { return s ? s->error : "sky is NULL"; }

const char *sky_layer_name(sky_layer layer)
{
    static const char *const names[SKY_LAYER_COUNT] = {"starmap", "stars", "flicker", "moon",
                                                       "atmosphere", "sun", "clouds"};
    return (unsigned)layer < SKY_LAYER_COUNT ? names[layer] : "unknown";
}

sky_params sky_default_params(void)
{
    sky_params p = {0.45f, 0.5f, 0.3f, 0.1f, 0.2f, 0.45f};
    return p;
}

/* ---- common uniforms ------------------------------------------------------ */

static const sky_uniform_desc common_uniforms[] = {
    SKY_UF("u_exposure", SKY_U_F1, exposure),
    SKY_UF("u_output_hdr", SKY_U_F1, output_hdr),
    SKY_UF("u_fisheye", SKY_U_F1, fisheye),
    SKY_UF("u_aspect", SKY_U_F2, aspect),
    SKY_UF("u_sun_dir", SKY_U_F3, sun_dir),
    SKY_UF("u_view_proj", SKY_U_M4, view_proj),
    SKY_UF("u_night_shift", SKY_U_F1, night_shift),
    SKY_UF("u_refraction_pressure", SKY_U_F1, refraction_pressure),
};
const sky_snippet sky_common_snippet = {NULL, "common.glsl", common_uniforms,
                                        (int)(sizeof common_uniforms / sizeof common_uniforms[0])};

/* ---- frame state ----------------------------------------------------------- */

/* Everything that depends on the sliders and the observer, not on the
 * camera. */
static void compute_frame(sky *s)
{
    sky_frame *f = &s->frame;
    /* The observer was validated when set; only a time slider pushing a
     * date at the very end of the supported span past it can fail here,
     * and then the last valid state is kept. */
    sky_astro a;
    if (sky_observer_astro(&s->observer, s->params.time, &a, NULL, 0) == 0) s->astro = a;
    for (int i = 0; i < 3; i++) f->sun_dir[i] = (float)s->astro.sun.dir[i];
    for (int i = 0; i < 3; i++) f->moon_dir[i] = (float)s->astro.moon.dir[i];
    f->sun_altitude = (float)s->astro.sun.alt; /* apparent: what the eye sees */
    f->refraction_pressure = (float)s->astro.pressure_factor;
    double sin_alt = sin(f->sun_altitude);
    /* R-P's "amount of sunlight" from the time of day: full above 10
     * degrees, none below -6 (end of civil twilight). */
    f->daylight = (float)sky_smoothstep(sin(-6.0 * SKY_PI / 180.0), sin(10.0 * SKY_PI / 180.0), sin_alt);
    /* Mueller sec. 5 star fade (astro.c) */
    f->night = (float)s->astro.star_visibility;
    /* The sky's rotation, J2000 -> horizon = horizon * precession-nutation
     * (eq. 7), as column-major mat4s: for the stars, and transposed (its
     * inverse) for the star map */
    double m[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double acc = 0.0;
            for (int k = 0; k < 3; k++) acc += s->astro.horizon[i * 3 + k] * s->astro.precession_nutation[k * 3 + j];
            m[i * 3 + j] = acc;
        }
    memset(f->star_rot, 0, sizeof f->star_rot);
    memset(f->starmap_rot, 0, sizeof f->starmap_rot);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            f->star_rot[j * 4 + i] = (float)m[i * 3 + j];
            f->starmap_rot[i * 4 + j] = (float)m[i * 3 + j];
        }
    f->star_rot[15] = f->starmap_rot[15] = 1.0f;
    sky_sun_transmittance(f->sun_altitude, f->sun_transmittance);
    sky_atmosphere_frame(s);
    /* A solar eclipse takes the sun's share of R-P's sunlight away (the
     * clouds' sunlit side, the host's daylight) */
    f->daylight *= (float)s->astro.solar_flux_fraction;
    /* The few minutes of a total solar eclipse are too short for the eye
     * to adapt to its dimmed sky (the rods take tens of minutes): the
     * exposure follows the square root of the eclipse's dimming (the mean
     * that atmosphere.c applied to sky_luminance), so totality looks like
     * deep twilight around a bright corona, not like day. The stars (the
     * catalogue, the star map and the flicker stars) are judged against
     * the sky around them, as the moon is (moon.c): in LDR they keep the
     * contrast a full adaptation would give them. */
    double withheld = 1.0 / sqrt(sky_clampd(f->eclipse_sky_mean, 1e-6, 1.0));
    f->star_local_gain = s->cfg.output == SKY_OUTPUT_HDR ? 1.0f : (float)withheld;
    if (s->features & SKY_SUN) sky_sun_frame(s);
    if (s->features & SKY_CLOUDS) sky_clouds_frame(s);
    if (s->features & SKY_FLICKER_STARS) sky_flicker_frame(s);
    /* Automatic exposure from the scene's own brightness: the day sky's
     * scale maps to the filmic curve's shoulder (common.glsl); at night a
     * floor 75 times the night sky (moonlit or not) keeps the sky dark blue
     * and the stars bright. */
    f->exposure =
        (float)(pow(2.0, s->exposure_bias) / (f->sky_luminance * withheld + 75.0 * f->night_luminance));
    /* Night vision: the adaptation luminance (what the exposure maps to
     * mid grey) from photopic, above 3 cd/m^2, to scotopic, below 0.01
     * cd/m^2, on a log scale; the shift is at most 60 % (the moon and
     * stars keep a little colour in the eye of a game player). */
    double adapt = f->sky_luminance * withheld + 75.0 * f->night_luminance; /* the automatic exposure's reference */
    f->night_shift = (float)(0.6 * sky_smoothstep(log10(3e-3), log10(1e-5), log10(adapt)));
    /* Leave out what adds nothing: a star layer whose brightest texel would
     * not reach a quarter of an 8-bit step is not evaluated at all. */
    if (f->star_luminance * f->exposure < 1.0f / 1024.0f) f->star_luminance = 0.0f;
    f->output_hdr = s->cfg.output == SKY_OUTPUT_HDR ? 1.0f : 0.0f;
}

/* ---- lifecycle ------------------------------------------------------------- */

static int check_rotation(const float m[9])
{
    for (int i = 0; i < 9; i++)
        if (!isfinite(m[i])) return 0;
    /* columns orthonormal within float tolerance */
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) {
            double dot = 0.0;
            for (int i = 0; i < 3; i++) dot += (double)m[a * 3 + i] * m[b * 3 + i];
            if (fabs(dot - (a == b ? 1.0 : 0.0)) > 1e-3) return 0;
        }
    return 1;
}

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
    if ((unsigned)cfg->atmosphere > SKY_ATMOSPHERE_BLEND || (unsigned)cfg->gl_profile > SKY_GL_COMPAT20 ||
        (unsigned)cfg->output > SKY_OUTPUT_HDR) {
        sky_format(err, err_len, "sky_create: atmosphere %d, gl_profile %d or output %d is out of range",
                   (int)cfg->atmosphere, (int)cfg->gl_profile, (int)cfg->output);
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
    if (!isfinite(cfg->turbidity) || (cfg->turbidity != 0.0f && (cfg->turbidity < 1.0f || cfg->turbidity > 64.0f))) {
        sky_format(err, err_len, "sky_create: turbidity %g is out of range (0 = default, or 1..64)",
                   (double)cfg->turbidity);
        return NULL;
    }
    unsigned features = cfg->features == 0 ? SKY_FEATURES_DEFAULT
                        : (cfg->features & SKY_FEATURES_NONE) ? 0u : cfg->features;
    if (features & ~(unsigned)SKY_FEATURES_AVAILABLE) {
        sky_format(err, err_len, "sky_create: features 0x%x are not built yet (available: 0x%x)",
                   features & ~(unsigned)SKY_FEATURES_AVAILABLE, (unsigned)SKY_FEATURES_AVAILABLE);
        return NULL;
    }
    if ((features & SKY_ECLIPSE) && !(features & SKY_MOON)) {
        sky_format(err, err_len, "sky_create: SKY_ECLIPSE needs SKY_MOON (the eclipse is drawn on the moon)");
        return NULL;
    }
    sky_atmosphere_params atm = cfg->atmosphere_params;
    if (sky_atmosphere_is_zero(&atm)) sky_atmosphere_get_preset(SKY_ATMOSPHERE_EARTH, &atm);
    char atm_err[160];
    if (sky_atmosphere_check(&atm, atm_err, sizeof atm_err) != SKY_OK) {
        sky_format(err, err_len, "sky_create: %s", atm_err);
        return NULL;
    }
    int identity = 1;
    for (int i = 0; i < 9; i++)
        if (cfg->horizon_to_world[i] != 0.0f) identity = 0;
    if (!identity && !check_rotation(cfg->horizon_to_world)) {
        sky_format(err, err_len, "sky_create: horizon_to_world is not a rotation (columns must be orthonormal)");
        return NULL;
    }

    sky *s = calloc(1, sizeof *s);
    if (!s) {
        sky_format(err, err_len, "sky_create: out of memory");
        return NULL;
    }
    s->cfg = *cfg; /* texture_dir is the caller's string: used during create only */
    s->features = features;
    s->atm = atm;
    sky_atmosphere_effective(&atm, &s->atm_rgb);
    sky_sun_irradiance_rgb(s->sun_irradiance_klx);
    s->atmosphere = cfg->atmosphere == SKY_ATMOSPHERE_DEFAULT ? SKY_ATMOSPHERE_GRADIENT : cfg->atmosphere;
    s->world_is_identity = identity;
    for (int i = 0; i < 9; i++) s->horizon_to_world[i] = identity ? (i % 4 == 0 ? 1.0f : 0.0f) : cfg->horizon_to_world[i];
    s->params = sky_default_params();
    s->observer = sky_default_observer();

    if (sky_gl_init(s, err, err_len)) goto fail;
    const sky_gl *gl = &s->gl;
    if (s->profile == SKY_GL_CORE33) {
        gl->glGenVertexArrays(1, &s->vao);
        gl->glBindVertexArray(s->vao);
    }
    if (sky_dome_create(s, err, err_len)) goto fail;
    if ((s->atmosphere == SKY_ATMOSPHERE_HILLAIRE || s->atmosphere == SKY_ATMOSPHERE_BLEND) &&
        sky_hillaire_create(s, err, err_len))
        goto fail;
    if ((features & SKY_CLOUDS) && sky_clouds_create(s, err, err_len)) goto fail;
    if ((features & SKY_FLICKER_STARS) && sky_flicker_create(s, err, err_len)) goto fail;
    if ((features & SKY_STARMAP) && sky_starmap_create(s, err, err_len)) goto fail;
    if ((features & SKY_SUN) && sky_sun_create(s, err, err_len)) goto fail;
    if (features & (SKY_STARS | SKY_MOON)) compute_frame(s); /* the default observer's astronomy */
    if ((features & SKY_STARS) && sky_stars_create(s, err, err_len)) goto fail;
    if ((features & SKY_MOON) && sky_moon_create(s, err, err_len)) goto fail;
    s->cfg.texture_dir = NULL;

    /* The dome program holds only the snippets of enabled features. With
     * night layers there are two variants, with and without them: a
     * uniform branch is not free on every GPU (llvmpipe pays for both
     * sides), and a day frame should do no star work at all. */
    const sky_snippet *dome_snippets[SKY_MAX_SNIPPETS];
    int n = sky_atmosphere_snippets(s->atmosphere, s->profile != SKY_GL_CORE33, dome_snippets);
    int atmosphere_snippets = n;
    if (features & SKY_CLOUDS) dome_snippets[n++] = &sky_clouds_snippet;
    if (sky_program_build(s, &s->dome, "dome.vert", "dome.frag", dome_snippets, n, err, err_len)) goto fail;
    /* Below the horizon there are no clouds and no stars: the lower
     * hemisphere gets the atmosphere alone (the host's terrain usually
     * covers it; what shows in a gap is the horizon haze). */
    if (n > atmosphere_snippets &&
        sky_program_build(s, &s->ground, "dome.vert", "dome.frag", dome_snippets, atmosphere_snippets, err, err_len))
        goto fail;
    if (features & (SKY_FLICKER_STARS | SKY_STARMAP)) {
        if (features & SKY_FLICKER_STARS) dome_snippets[n++] = &sky_flicker_snippet;
        if (features & SKY_STARMAP) dome_snippets[n++] = &sky_starmap_snippet;
        if (sky_program_build(s, &s->dome_night, "dome.vert", "dome.frag", dome_snippets, n, err, err_len)) goto fail;
        /* and the night without clouds, for cover 0 (by day at cover 0 the
         * atmosphere-only program serves) */
        if (features & SKY_CLOUDS) {
            const sky_snippet *clear[SKY_MAX_SNIPPETS];
            int c = 0;
            for (int i = 0; i < n; i++)
                if (dome_snippets[i] != &sky_clouds_snippet) clear[c++] = dome_snippets[i];
            if (sky_program_build(s, &s->dome_night_clear, "dome.vert", "dome.frag", clear, c, err, err_len)) goto fail;
        }
    }
    if (features & SKY_STARS) {
        const sky_snippet *star_snippets[2];
        int m = 0;
        if (features & SKY_CLOUDS) star_snippets[m++] = &sky_clouds_snippet;
        star_snippets[m++] = &sky_stars_snippet;
        if (sky_program_build(s, &s->stars, "stars.vert", "stars.frag", star_snippets, m, err, err_len)) goto fail;
    }
    if (features & SKY_MOON) {
        const sky_snippet *moon_snippets[3];
        int m = 0;
        if (features & SKY_CLOUDS) moon_snippets[m++] = &sky_clouds_snippet;
        if (features & SKY_ECLIPSE) moon_snippets[m++] = &sky_eclipse_snippet;
        moon_snippets[m++] = &sky_moon_snippet;
        if (sky_program_build(s, &s->moon, "moon.vert", "moon.frag", moon_snippets, m, err, err_len)) goto fail;
    }
    if (features & SKY_SUN) {
        const sky_snippet *sun_snippets[2];
        int m = 0;
        if (features & SKY_CLOUDS) sun_snippets[m++] = &sky_clouds_snippet;
        sun_snippets[m++] = &sky_sun_snippet;
        if (sky_program_build(s, &s->sun, "sun.vert", "sun.frag", sun_snippets, m, err, err_len)) goto fail;
    }
    if (s->profile == SKY_GL_CORE33) gl->glBindVertexArray(0);
    GLenum e = gl->glGetError();
    if (e != GL_NO_ERROR) {
        sky_format(err, err_len, "sky_create: GL error 0x%04x while creating resources", e);
        goto fail;
    }
    compute_frame(s);
    return s;
fail:
    s->cfg.texture_dir = NULL;
    sky_destroy(s);
    return NULL;
}

void sky_destroy(sky *s)
{
    if (!s) return;
    const sky_gl *gl = &s->gl;
    if (gl->glDeleteTextures) { /* NULL when sky_gl_init failed early */
        for (int i = 0; i < SKY_TEX_COUNT; i++) sky_texture_destroy(s, (sky_texture_id)i);
        sky_program_destroy(s, &s->dome);
        sky_program_destroy(s, &s->dome_night);
        sky_program_destroy(s, &s->dome_night_clear);
        sky_program_destroy(s, &s->ground);
        sky_program_destroy(s, &s->stars);
        sky_program_destroy(s, &s->moon);
        sky_stars_destroy(s);
        sky_program_destroy(s, &s->sun);
        sky_program_destroy(s, &s->transmittance_build);
        sky_program_destroy(s, &s->multiscatter_build);
        sky_program_destroy(s, &s->skyview_build);
        GLuint buffers[7] = {s->dome_vertices,     s->dome_indices, s->sun_grid.vertices, s->sun_grid.indices,
                             s->moon_grid.vertices, s->moon_grid.indices, s->star_buffer};
        gl->glDeleteBuffers(7, buffers);
        if (s->vao) gl->glDeleteVertexArrays(1, &s->vao);
    }
    sky_hillaire_destroy(s);
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
    s->params.cover = out[0];
    s->params.height = out[1];
    s->params.density = out[2];
    s->params.sunset = out[3];
    s->params.speed = out[4];
    s->params.time = out[5];
    compute_frame(s);
    return rc;
}

sky_result sky_set_observer(sky *s, const sky_observer *o)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!o) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_observer: observer is NULL");
    if (sky_observer_check(o, s->error, sizeof s->error)) return SKY_ERR_INVALID_ARGUMENT;
    sky_astro a;
    if (sky_observer_astro(o, s->params.time, &a, s->error, sizeof s->error)) return SKY_ERR_INVALID_ARGUMENT;
    s->observer = *o;
    compute_frame(s);
    return SKY_OK;
}

sky_result sky_get_observer(const sky *s, sky_observer *o)
{
    if (!s || !o) return SKY_ERR_INVALID_ARGUMENT;
    *o = s->observer;
    return SKY_OK;
}

sky_result sky_get_astronomy(const sky *s, sky_astronomy *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    sky_astronomy_from_astro(&s->astro, out);
    return SKY_OK;
}

sky_result sky_get_params(const sky *s, sky_params *p)
{
    if (!s || !p) return SKY_ERR_INVALID_ARGUMENT;
    *p = s->params;
    return SKY_OK;
}

sky_result sky_set_exposure_bias(sky *s, float ev)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (isnan(ev)) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_exposure_bias: ev is NaN");
    float c = sky_clampf(ev, -10.0f, 10.0f);
    s->exposure_bias = c;
    compute_frame(s);
    if (c != ev) return sky_fail(s, SKY_CLAMPED, "sky_set_exposure_bias: %g clamped to %g (range -10..10)", (double)ev, (double)c);
    return SKY_OK;
}

sky_result sky_update(sky *s, double dt)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!isfinite(dt) || dt < 0.0)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_update: dt = %g must be finite and >= 0", dt);
    s->scintillation_phase =
        sky_phase_advance(s->scintillation_phase, SKY_SCINTILLATION_RATE / SKY_SCINTILLATION_PERIOD, dt);
    if (s->features & SKY_CLOUDS) sky_clouds_advance(s, dt);
    if (s->features & SKY_FLICKER_STARS) sky_flicker_advance(s, dt);
    compute_frame(s);
    return SKY_OK;
}

sky_result sky_set_elapsed(sky *s, double seconds)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!isfinite(seconds) || seconds < 0.0)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_set_elapsed: %g must be finite and >= 0", seconds);
    s->scintillation_phase = 0.0;
    memset(s->cloud_offsets, 0, sizeof s->cloud_offsets);
    s->flicker_phase = 0.0;
    return sky_update(s, seconds);
}

/* ---- camera ------------------------------------------------------------------- */

/* Inverts a 4x4 column-major matrix in double. Returns 0 if singular. */
static int invert4(const double m[16], double out[16])
{
    double inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] +
             m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] -
             m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] +
             m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] -
              m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] -
             m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] +
             m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] -
             m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] +
              m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] +
             m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] -
             m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] +
              m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] -
              m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] -
             m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] +
             m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] -
              m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] +
              m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    double scale = 0.0;
    for (int i = 0; i < 16; i++) scale = fmax(scale, fabs(m[i]));
    if (!isfinite(det) || fabs(det) <= 1e-12 * pow(scale, 4.0)) return 0;
    for (int i = 0; i < 16; i++) out[i] = inv[i] / det;
    return 1;
}

/* The rotation from the horizon frame to the camera: the view's 3x3 made
 * orthonormal (a scaled or slightly skewed view still means a direction),
 * times horizon_to_world. Returns 0 for a degenerate view. */
static int camera_rotation(const sky *s, const float view[16], double rot[9])
{
    double r[3][3]; /* rows of the view's rotation: camera axes in world */
    for (int row = 0; row < 3; row++)
        for (int c = 0; c < 3; c++) r[row][c] = view[c * 4 + row];
    /* Gram-Schmidt on forward (row 2), then up (row 1); right = up x fwd. */
    double *f = r[2], *u = r[1];
    double fl = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(fl > 1e-12)) return 0;
    for (int i = 0; i < 3; i++) f[i] /= fl;
    double d = u[0] * f[0] + u[1] * f[1] + u[2] * f[2];
    for (int i = 0; i < 3; i++) u[i] -= d * f[i];
    double ul = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(ul > 1e-9 * fl)) return 0;
    for (int i = 0; i < 3; i++) u[i] /= ul;
    double x[3] = {u[1] * f[2] - u[2] * f[1], u[2] * f[0] - u[0] * f[2], u[0] * f[1] - u[1] * f[0]};
    /* keep the view's handedness for the x axis */
    if (x[0] * r[0][0] + x[1] * r[0][1] + x[2] * r[0][2] < 0.0)
        for (int i = 0; i < 3; i++) x[i] = -x[i];
    double cam[3][3] = {{x[0], x[1], x[2]}, {u[0], u[1], u[2]}, {f[0], f[1], f[2]}};
    /* rot = cam * H (H maps horizon to world), stored row-major */
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double acc = 0.0;
            for (int k = 0; k < 3; k++) acc += cam[i][k] * s->horizon_to_world[j * 3 + k];
            rot[i * 3 + j] = acc;
        }
    return 1;
}

/* Validates the camera and fills u_view_proj: horizon directions to clip. */
static sky_result setup_camera(sky *s, const float view[16], const float proj[16])
{
    for (int i = 0; i < 16; i++)
        if (!isfinite(view[i]) || !isfinite(proj[i]))
            return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_draw: %s[%d] is not finite",
                            !isfinite(view[i]) ? "view" : "proj", i);
    double rot[9];
    if (!camera_rotation(s, view, rot))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_draw: the view matrix has a degenerate rotation");
    double p[16], pinv[16];
    for (int i = 0; i < 16; i++) p[i] = proj[i];
    if (!invert4(p, pinv)) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_draw: the projection is singular");
    /* u_view_proj = proj * [rot 0; 0 1], column-major */
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++) {
            double acc = 0.0;
            for (int k = 0; k < 4; k++) {
                double m = (k < 3 && col < 3) ? rot[k * 3 + col] : (k == 3 && col == 3 ? 1.0 : 0.0);
                acc += p[k * 4 + row] * m;
            }
            s->frame.view_proj[col * 4 + row] = (float)acc;
        }
    s->frame.fisheye = 0.0f;
    /* radians per pixel at the view centre: 2 tan(fov/2) / height */
    GLint vp[4];
    s->gl.glGetIntegerv(GL_VIEWPORT, vp);
    s->frame.pixel_angle = (float)(2.0 / (fabs(p[5]) * (vp[3] > 0 ? vp[3] : 1)));
    return SKY_OK;
}

/* The all-sky image: the aspect that keeps its circle round, and black
 * around it where no part of the dome lands (viewport only). */
static void setup_fisheye(sky *s, const GLint viewport[4])
{
    double w = viewport[2] > 0 ? viewport[2] : 1, h = viewport[3] > 0 ? viewport[3] : 1;
    s->frame.aspect[0] = (float)(w > h ? w / h : 1.0);
    s->frame.aspect[1] = (float)(h > w ? h / w : 1.0);
    s->frame.fisheye = 1.0f;
    s->frame.pixel_angle = (float)(SKY_PI / (w < h ? w : h)); /* 90 degrees on the circle's radius */
    const sky_gl *gl = &s->gl;
    gl->glEnable(GL_SCISSOR_TEST);
    gl->glScissor(viewport[0], viewport[1], viewport[2], viewport[3]);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    gl->glClear(GL_COLOR_BUFFER_BIT);
    gl->glDisable(GL_SCISSOR_TEST);
}

/* ---- drawing --------------------------------------------------------------------- */

double sky_now_ms(void)
{
    struct timespec ts;
    timespec_get(&ts, TIME_UTC);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* A disc's grid (sun, moon): grid position (a_pos) and direction (a_dir). */
static void draw_grid(sky *s, const sky_disc_grid *g)
{
    const sky_gl *gl = &s->gl;
    gl->glBindBuffer(GL_ARRAY_BUFFER, g->vertices);
    gl->glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, g->indices);
    gl->glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 5 * sizeof(float), (const void *)0);
    gl->glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 5 * sizeof(float), (const void *)(2 * sizeof(float)));
    gl->glEnableVertexAttribArray(0);
    gl->glEnableVertexAttribArray(1);
    gl->glDisableVertexAttribArray(2);
    gl->glDrawElements(GL_TRIANGLES, SKY_DISC_GRID_INDICES, GL_UNSIGNED_SHORT, (const void *)0);
}

static void reset_layer_stats(sky *s)
{
    for (int l = 0; l < SKY_LAYER_COUNT; l++) {
        s->stats.layers[l].drawn = 0;
        s->stats.layers[l].draws = 0;
        s->stats.layers[l].ms = -1.0;
    }
    s->stats.draws_per_frame = 0;
    /* table builds since the last draw (sky_update, sky_set_params, ...) */
    s->stats.lut_ms = s->lut_ms;
    s->lut_ms = 0.0;
}

/* Draws one layer: a disc's grid, or the dome's hemispheres (grid NULL). */
static void draw_layer(sky *s, sky_layer layer, const sky_program *prog, const sky_disc_grid *grid)
{
    const sky_gl *gl = &s->gl;
    int timed = s->cfg.profile_layers;
    double t0 = 0.0;
    if (timed) {
        gl->glFinish();
        t0 = sky_now_ms();
    }
    sky_program_apply(s, prog);
    if (grid) {
        draw_grid(s, grid);
    } else {
        sky_dome_draw(s, 1);
        /* the lower hemisphere: its own cheap program when the upper one
         * carries more than the atmosphere; none in the all-sky image */
        if (s->frame.fisheye < 0.5f) {
            if (s->ground.id) {
                sky_program_apply(s, &s->ground);
                s->stats.draws_per_frame++;
                s->stats.layers[layer].draws++;
            }
            sky_dome_draw(s, 0);
        }
    }
    if (timed) {
        gl->glFinish();
        s->stats.layers[layer].ms = sky_now_ms() - t0;
    }
    s->stats.layers[layer].drawn = 1;
    s->stats.layers[layer].draws++;
    s->stats.draws_per_frame++;
}

static sky_result draw_frame(sky *s)
{
    const sky_gl *gl = &s->gl;
    gl->glDisable(GL_DEPTH_TEST);
    gl->glDisable(GL_CULL_FACE);
    gl->glDisable(GL_STENCIL_TEST);
    gl->glDepthMask(GL_FALSE);
    gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl->glDisable(GL_BLEND);
    if (s->profile == SKY_GL_CORE33) gl->glBindVertexArray(s->vao);

    /* 1. the dome: atmosphere, with flicker stars behind it and clouds in
     * front, in one pass over the screen */
    if (s->features & SKY_STARMAP) sky_starmap_frame(s);
    int night = s->dome_night.id && (s->frame.star_luminance > 0.0f || s->frame.starmap_scale > 0.0f);
    /* at cover 0 the variants without cloud code (Roden-Parberry's line
     * 15 makes every cloud texel vanish there anyway) */
    int clear = (s->features & SKY_CLOUDS) && !sky_clouds_visible(s);
    const sky_program *dome = night ? (clear ? &s->dome_night_clear : &s->dome_night) : (clear ? &s->ground : &s->dome);
    sky_hillaire_upload(s); /* a sky-view table rebuilt since the last draw */
    draw_layer(s, SKY_LAYER_ATMOSPHERE, dome, NULL);
    if (s->features & SKY_FLICKER_STARS) s->stats.layers[SKY_LAYER_FLICKER].drawn = night && s->frame.star_luminance > 0;
    if (s->features & SKY_STARMAP) s->stats.layers[SKY_LAYER_STARMAP].drawn = night && s->frame.starmap_scale > 0;
    if (s->features & SKY_CLOUDS) s->stats.layers[SKY_LAYER_CLOUDS].drawn = sky_clouds_visible(s);

    /* 2. catalogue stars, added over the dome: their light dimmed by the
     * atmosphere (extinction in the shader) and hidden by the clouds */
    if (s->features & SKY_STARS) {
        GLint vp[4];
        gl->glGetIntegerv(GL_VIEWPORT, vp);
        for (int i = 0; i < 4; i++) s->frame.star_viewport[i] = (float)vp[i];
        sky_stars_frame(s);
        if (sky_stars_visible(s)) {
            gl->glEnable(GL_BLEND);
            gl->glBlendEquation(GL_FUNC_ADD);
            gl->glBlendFunc(GL_ONE, GL_ONE);
            double t0 = s->cfg.profile_layers ? (gl->glFinish(), sky_now_ms()) : 0.0;
            sky_program_apply(s, &s->stars);
            sky_stars_draw(s);
            if (s->cfg.profile_layers) {
                gl->glFinish();
                s->stats.layers[SKY_LAYER_STARS].ms = sky_now_ms() - t0;
            }
            s->stats.layers[SKY_LAYER_STARS].drawn = 1;
            s->stats.layers[SKY_LAYER_STARS].draws++;
            s->stats.draws_per_frame++;
        }
    }

    /* 3. the moon: added by day; at night it also hides the stars behind
     * it (src alpha: its coverage times the night factor) */
    if (s->features & SKY_MOON) {
        sky_moon_frame(s);
        if (sky_moon_visible(s)) {
            sky_moon_update_quad(s);
            gl->glEnable(GL_BLEND);
            gl->glBlendEquation(GL_FUNC_ADD);
            gl->glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
            draw_layer(s, SKY_LAYER_MOON, &s->moon, &s->moon_grid);
        }
    }

    /* 4. the sun quad, added over the dome (it hides behind the clouds by
     * evaluating them itself) */
    if (sky_sun_visible(s)) {
        sky_sun_update_quad(s);
        gl->glEnable(GL_BLEND);
        gl->glBlendEquation(GL_FUNC_ADD);
        gl->glBlendFunc(GL_ONE, GL_ONE);
        draw_layer(s, SKY_LAYER_SUN, &s->sun, &s->sun_grid);
    }
    GLenum e = gl->glGetError();
    if (e != GL_NO_ERROR) return sky_fail(s, SKY_ERR_GL, "sky_draw: GL error 0x%04x", e);
    return SKY_OK;
}

static sky_result draw_with(sky *s, const float *view, const float *proj)
{
    double t0 = sky_now_ms();
    sky_gl_state host;
    const sky_gl *gl = &s->gl;
    while (gl->glGetError() != GL_NO_ERROR) {} /* the host's errors are not ours */
    sky_gl_state_save(s, &host);
    reset_layer_stats(s);
    sky_result rc = view ? setup_camera(s, view, proj) : (setup_fisheye(s, host.viewport), SKY_OK);
    if (rc == SKY_OK) rc = draw_frame(s);
    sky_gl_state_restore(s, &host);
    if (s->cfg.profile_layers) gl->glFinish();
    s->stats.frame_ms = sky_now_ms() - t0;
    return rc;
}

sky_result sky_draw(sky *s, const float view[16], const float proj[16])
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!view || !proj) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_draw: view or proj is NULL");
    return draw_with(s, view, proj);
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
    *out = s->stats;
    out->gl_version = s->gl_version;
    out->profile = s->profile;
    out->features = s->features;
    out->lut_ms = s->stats.lut_ms;
    out->textures = 0;
    out->gpu_bytes = s->buffer_bytes;
    for (int l = 0; l < SKY_LAYER_COUNT; l++) out->layers[l].bytes = 0;
    for (int i = 0; i < SKY_TEX_COUNT; i++)
        if (s->textures[i].id) {
            out->textures++;
            out->gpu_bytes += s->textures[i].bytes;
            out->layers[s->textures[i].owner].bytes += s->textures[i].bytes;
        }
    out->layers[SKY_LAYER_ATMOSPHERE].bytes += s->buffer_bytes;
    if (s->sun_grid.vertices) {
        out->layers[SKY_LAYER_SUN].bytes += SKY_DISC_GRID_BYTES;
        out->layers[SKY_LAYER_ATMOSPHERE].bytes -= SKY_DISC_GRID_BYTES;
    }
    if (s->moon_grid.vertices) {
        out->layers[SKY_LAYER_MOON].bytes += SKY_DISC_GRID_BYTES;
        out->layers[SKY_LAYER_ATMOSPHERE].bytes -= SKY_DISC_GRID_BYTES;
    }
    if (s->star_buffer) {
        size_t star_bytes = sizeof(float) * 9 * (size_t)s->catalog.count;
        out->layers[SKY_LAYER_STARS].bytes += star_bytes;
        out->layers[SKY_LAYER_ATMOSPHERE].bytes -= star_bytes;
    }
    out->programs = s->program_count;
    out->buffers = s->buffer_count;
    static const unsigned layer_feature[SKY_LAYER_COUNT] = {SKY_STARMAP, SKY_STARS, SKY_FLICKER_STARS, SKY_MOON,
                                                            0, SKY_SUN, SKY_CLOUDS};
    for (int l = 0; l < SKY_LAYER_COUNT; l++)
        out->layers[l].enabled = l == SKY_LAYER_ATMOSPHERE || (s->features & layer_feature[l]) != 0;
    return SKY_OK;
}

static void to_world(const sky *s, const float h[3], float w[3])
{
    for (int i = 0; i < 3; i++)
        w[i] = s->horizon_to_world[0 * 3 + i] * h[0] + s->horizon_to_world[1 * 3 + i] * h[1] +
               s->horizon_to_world[2 * 3 + i] * h[2];
}

sky_result sky_get_lighting(const sky *s, sky_lighting *out)
{
    if (!s || !out) return SKY_ERR_INVALID_ARGUMENT;
    const sky_frame *f = &s->frame;
    memset(out, 0, sizeof *out);
    to_world(s, f->sun_dir, out->sun_direction);
    out->sun_altitude_deg = (float)(f->sun_altitude * 180.0 / SKY_PI);
    /* Solar illuminance above the atmosphere, 128 klx, through the
     * atmosphere, times the part of the disc not yet set */
    float above = (float)sky_disc_above_horizon(f->sun_altitude, s->astro.sun_semidiameter);
    /* and the share of its light a solar eclipse leaves */
    above *= (float)s->astro.solar_flux_fraction;
    for (int i = 0; i < 3; i++) out->sun_color[i] = 128.0f * f->sun_transmittance[i] * above;
    /* sky irradiance and horizon: the atmosphere path's (atmosphere.c) */
    for (int i = 0; i < 3; i++) {
        out->ambient_color[i] = f->ambient_rgb[i];
        out->fog_color[i] = f->fog_rgb[i];
    }
    out->daylight = f->daylight;
    out->exposure = f->exposure;
    if (s->features & SKY_MOON) {
        const sky_astro *a = &s->astro;
        to_world(s, f->moon_dir, out->moon_direction);
        /* the full moon gives about 0.27 lux at the zenith; the phase law
         * of Allen's Astrophysical Quantities (magnitude grows as
         * 0.026 |phi| + 4e-9 phi^4, phi in degrees) for other phases;
         * extinction as for the sun's beam */
        double phi = a->moon_phase_angle * 180.0 / SKY_PI;
        double phase = pow(10.0, -0.4 * (0.026 * fabs(phi) + 4e-9 * phi * phi * phi * phi));
        float t[3];
        sky_sun_transmittance(a->moon.alt, t);
        float up = (float)sky_disc_above_horizon(a->moon.alt, a->moon_semidiameter);
        for (int i = 0; i < 3; i++) out->moon_color[i] = (float)(2.7e-4 * phase) * t[i] * up;
    }
    return SKY_OK;
}
