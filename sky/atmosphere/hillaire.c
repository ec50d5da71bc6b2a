/*
 * The Hillaire path in the sky (Hillaire 2020): transmittance and
 * multiple-scattering tables once at creation (they depend on the
 * atmosphere alone), the sky-view table whenever the sun's elevation or
 * the observer's altitude has moved past a threshold (the table is
 * relative to the sun's azimuth, so a sun that only turns costs nothing).
 * CORE33 builds all three on the GPU into float textures
 * (*_build.frag, GLSL twins of hillaire_cpu.c) and reads the first two
 * back; COMPAT20 builds them with hillaire_cpu.c and uploads the sky-view
 * table in an 8-bit log-luminance + chromaticity encoding (hillaire.glsl
 * decodes it). COMPAT20 builds a sky-view table for a moving sun a slice
 * of rows per frame while the previous one stays on screen (see
 * SKYVIEW_SLICE_MS). The host's lighting comes from a few rays marched on
 * the CPU through the first two tables.
 */
#include "atmosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Rebuild the sky-view table when the sun's elevation has moved by more
 * than this (radians; 0.05 degree: a tenth of the sun's diameter, about
 * 12 s of a mid-latitude sunset) or the observer by more than 10 m. */
#define SKYVIEW_SUN_THRESHOLD (0.05 * SKY_PI / 180.0)
#define SKYVIEW_ALTITUDE_THRESHOLD_KM 0.01
/* COMPAT20 builds the sky-view table on the CPU, on the host's render
 * thread: milliseconds with the default sizes (docs/validation.md), and a
 * time-lapse moves the sun past the threshold above every frame. Two
 * cases:
 *  - a jump: no table yet, the observer's altitude moved past its
 *    threshold, or the sun's elevation moved more than SKYVIEW_SUN_JUMP
 *    since the last frame drawn (since creation before the first). The
 *    host has set a new time or place, and the table shown cannot stand
 *    in for it (the twilight sky changes by a decade in 3 degrees of sun),
 *    so the table is built at once, in the call that made the jump, and
 *    the next frame shows the exact sky for the new sun;
 *  - an animated sun, moving less than that between frames: the new table
 *    is built for the sun of the moment the build starts into a second
 *    pair of buffers, at most SKYVIEW_SLICE_MS of rows per call of
 *    sky_hillaire_frame (each sky_set_params, sky_set_observer,
 *    sky_set_exposure_bias, sky_update makes one), then encoded likewise.
 *    Until its last row is encoded, the table shown stays on the GPU with
 *    its own decoding, horizon and lighting summary; then the two swap in
 *    sky_hillaire_frame and the next draw uploads the new one. A build
 *    still under way when the sun moves on is finished (a restart would
 *    never finish under a moving sun), and the next starts from the sun of
 *    that moment: the sky lags a moving sun by one to two builds (about 10
 *    to 20 frames of sky-demo, which makes two calls a frame).
 * One degree between two frames drawn is a day in 360 frames, eight times
 * sky-demo's default time-lapse at 30 frames a second. */
#define SKYVIEW_SUN_JUMP (1.0 * SKY_PI / 180.0)
/* 0.4 ms: a host that recomputes the frame twice per frame drawn (sky-demo:
 * sky_set_params and sky_update) spends under 1 ms a frame on the table. A
 * slice ends before the unit (a row built, or a row encoded) that would
 * take it past the budget, judged by the dearest unit of the slice so far;
 * every slice does at least one. */
#define SKYVIEW_SLICE_MS 0.4
/* the 8-bit encoding covers this many stops below the table's brightest
 * value (the sun's aureole): 2^-24 is darker than anything the tone map
 * shows next to it */
#define SKYVIEW_STOPS 24.0

static const sky_uniform_desc hillaire_uniforms[] = {
    SKY_UT("u_skyview", SKY_TEX_SKYVIEW),
    SKY_UF("u_skyview_map", SKY_U_F4, skyview_map),
    SKY_UF("u_skyview_horizon", SKY_U_F2, skyview_horizon),
    SKY_UF("u_skyview_decode", SKY_U_F3, skyview_decode),
};
const sky_snippet sky_hillaire_snippet = {"SKY_HAS_HILLAIRE", "hillaire.glsl", hillaire_uniforms,
                                          SKY_UNIFORM_COUNT(hillaire_uniforms), NULL, NULL, NULL};
/* The same for COMPAT20's 8-bit table: the decoding is compiled in only
 * there (a uniform branch would cost both sides on llvmpipe, twice the
 * float path's frame). */
const sky_snippet sky_hillaire_encoded_snippet = {"SKY_HILLAIRE_ENCODED", "hillaire.glsl", hillaire_uniforms,
                                                  SKY_UNIFORM_COUNT(hillaire_uniforms), NULL, NULL, NULL};

/* COMPAT20: the next sky-view table, built a slice at a time into buffers
 * of its own (the ones the table shown last used). */
typedef struct skyview_build {
    int active;
    int next;               /* next unit: rows 0..h-1 built, then rows h..2h-1 encoded */
    double sun_mu, altitude_km;
    double brightest;       /* luminance of the brightest texel built so far */
    double log2_floor;      /* the encoding's floor, once every row is built */
    float *table;           /* skyview_width * skyview_height * 3 */
    unsigned char *encoded; /* skyview_width * skyview_height * 4 */
} skyview_build;

struct sky_hillaire_state {
    sky_hillaire_tables tables;      /* tables.skyview: the table in use        */
    unsigned char *skyview_encoded;  /* COMPAT20's 8-bit sky-view table in use  */
    skyview_build build;             /* COMPAT20: the next one                  */
    int skyview_valid, skyview_uploaded; /* CPU table (COMPAT20) or GPU build done */
    /* the table in use: its sun, altitude and encoding floor */
    double skyview_sun_mu, skyview_altitude_km, skyview_log2_floor;
    double drawn_sun_mu;             /* the sun at the last draw: jumps are measured from it */
    sky_program transmittance_build, multiscatter_build, skyview_build; /* CORE33 */
    sky_program froxel_build;        /* CORE33: made at the first froxel call  */
    GLuint fbo;                      /* CORE33: renders into each table in turn */
};

static int next_pow2(int n)
{
    int p = 1;
    while (p < n) p <<= 1;
    return p;
}

static const sky_uniform_desc build_uniforms[] = {
    SKY_UT("u_transmittance_table", SKY_TEX_TRANSMITTANCE),
    SKY_UT("u_multiscatter_table", SKY_TEX_MULTISCATTER),
    SKY_UF("u_hl_geometry", SKY_U_F4, hl_geometry),
    SKY_UF("u_hl_profile", SKY_U_F4, hl_profile),
    SKY_UF("u_hl_rayleigh", SKY_U_F3, hl_rayleigh),
    SKY_UF("u_hl_mie_sca", SKY_U_F3, hl_mie_sca),
    SKY_UF("u_hl_mie_ext", SKY_U_F3, hl_mie_ext),
    SKY_UF("u_hl_ozone", SKY_U_F3, hl_ozone),
    SKY_UF("u_hl_albedo", SKY_U_F3, hl_albedo),
    SKY_UF("u_hl_sizes", SKY_U_F4, hl_sizes),
    SKY_UF("u_hl_misc", SKY_U_F4, hl_misc),
    SKY_UF("u_hl_steps", SKY_U_F4, hl_steps),
    SKY_UF("u_hl_chi", SKY_U_F3, hl_chi),
    SKY_UF("u_hl_chi_zonal", SKY_U_F2, hl_chi_zonal),
};
static const sky_snippet build_snippet = {NULL, "hillaire_build.glsl", build_uniforms,
                                          SKY_UNIFORM_COUNT(build_uniforms), NULL, NULL, NULL};
static const sky_uniform_desc order_uniforms[] = {
    SKY_UT("u_ms_order", SKY_TEX_MS_ORDER_PREV),
    SKY_UF("u_ms_pass", SKY_U_F4, ms_pass),
};
static const sky_snippet order_snippet = {NULL, NULL, order_uniforms, SKY_UNIFORM_COUNT(order_uniforms),
                                          NULL, NULL, NULL};
static const sky_uniform_desc froxel_uniforms[] = {
    SKY_UF("u_froxel_clip_to_dir", SKY_U_M4, froxel_clip_to_dir),
    SKY_UF("u_froxel", SKY_U_F4, froxel),
    SKY_UF("u_froxel_sun_irradiance", SKY_U_F3, sun_irradiance),
    SKY_UF("u_froxel_weather", SKY_U_F2, froxel_weather),
    SKY_UF("u_froxel_haze", SKY_U_F3, fog_rgb),
};
static const sky_snippet froxel_snippet = {NULL, NULL, froxel_uniforms, SKY_UNIFORM_COUNT(froxel_uniforms),
                                           NULL, NULL, NULL};

/* One full-screen pass of a build program into the w x h corner of a
 * texture. */
static void gpu_pass(sky_core *s, GLuint fbo, sky_program *prog, sky_texture_id target, int w, int h)
{
    sky_gl_target t;
    sky_gl_target_begin(s, fbo, target, w, h, &t);
    sky_program_apply(s, prog);
    sky_gl_draw_arrays(s, GL_TRIANGLES, 0, 3);
    sky_gl_target_end(s, &t);
}

/* The multiple-scattering table on the GPU: 6 layers (SKY_TEX_MULTISCATTER),
 * and one order's table while it is built: 7 (SKY_TEX_MS_ORDER). */
#define MS_LAYERS 6
#define MS_ORDER_LAYERS 7

/* Where quantity q (0 .. SKY_HL_MS_ALL - 1) of an order's texel (the
 * mean, D_x, D_y, Q_xx, Q_yy, Q_xy, Z_3, Z_4, each RGB) sits in the
 * layers: layer * 4 + channel. The mean, D_x, D_y, Q_xx, Q_yy and Z_4 in
 * the RGB of layers 0-5, Q_xy in the alphas of layers 0-2 and Z_3 in
 * those of 3-5 (multiscatter_build.frag writes them so,
 * hl_scatter_moments reads them so). The irradiance, in layer 6, only
 * the next pass reads. */
static int order_slot(int q)
{
    static const int layer[8] = {0, 1, 2, 3, 4, -1, -1, 5};
    int what = q / 3, c = q % 3;
    if (what == 5) return c * 4 + 3;
    if (what == 6) return (3 + c) * 4 + 3;
    return layer[what] * 4 + c;
}

/* The multiple-scattering table (CORE33): SKY_HL_ORDERS passes, each
 * tracing one order on the GPU from the one before; each is read back and
 * added to the CPU's tables (sky_hillaire_add_order: the CPU's rays, the
 * host's lighting, use them too), and their sum becomes the table the
 * sky-view build reads. The order tables go once it is made. */
static int build_multiscatter(sky_core *s, sky_hillaire_state *hs, int mn, char *err, size_t err_len)
{
    size_t texels = (size_t)mn * (size_t)mn;
    float *rgba = malloc(sizeof(float) * 4u * texels * MS_LAYERS);
    /* each order as sky_hillaire_add_order reads it (the irradiance, which
     * it does not read, left 0) */
    float *orders = calloc(2u * texels * SKY_HL_ORDER, sizeof(float));
    int rc = !rgba || !orders ? -1 : 0;
    if (!rc && (sky_texture_create_lut_layers(s, SKY_TEX_MS_ORDER, SKY_LAYER_ATMOSPHERE, mn, mn, MS_ORDER_LAYERS,
                                              NULL, err, err_len) ||
                sky_texture_create_lut_layers(s, SKY_TEX_MS_ORDER_PREV, SKY_LAYER_ATMOSPHERE, mn, mn,
                                              MS_ORDER_LAYERS, NULL, err, err_len)))
        rc = -2;
    float *cur = orders, *prev = orders ? orders + texels * SKY_HL_ORDER : NULL;
    for (int k = 1; k <= SKY_HL_ORDERS && !rc; k++) {
        int nd, np, ns;
        sky_hillaire_order_samples(&hs->tables, k, &nd, &np, &ns);
        s->frame.ms_pass[0] = (float)k;
        s->frame.ms_pass[1] = (float)nd;
        s->frame.ms_pass[2] = (float)ns;
        s->frame.ms_pass[3] = (float)np;
        sky_gl_target target;
        sky_gl_target_begin_slices(s, hs->fbo, SKY_TEX_MS_ORDER, 0, MS_ORDER_LAYERS, mn, mn, &target);
        sky_program_apply(s, &hs->multiscatter_build);
        sky_gl_draw_arrays(s, GL_TRIANGLES, 0, 3);
        sky_gl_target_end_slices(s, MS_ORDER_LAYERS, &target);
        for (int l = 0; l < MS_LAYERS && !rc; l++)
            rc = sky_gl_read_rgba(s, hs->fbo, SKY_TEX_MS_ORDER, l, mn, mn, rgba + 4u * texels * (size_t)l);
        if (rc) break;
        for (size_t i = 0; i < texels; i++)
            for (int q = 0; q < SKY_HL_MS_ALL; q++) {
                int slot = order_slot(q);
                cur[i * SKY_HL_ORDER + (size_t)q] = rgba[4u * texels * (size_t)(slot / 4) + 4u * i + (size_t)(slot % 4)];
            }
        sky_hillaire_add_order(&hs->tables, k, cur, prev);
        /* the order just traced is the one the next pass scatters */
        float *swap = prev;
        prev = cur;
        cur = swap;
        sky_texture traced = s->textures[SKY_TEX_MS_ORDER];
        s->textures[SKY_TEX_MS_ORDER] = s->textures[SKY_TEX_MS_ORDER_PREV];
        s->textures[SKY_TEX_MS_ORDER_PREV] = traced;
    }
    sky_texture_destroy(s, SKY_TEX_MS_ORDER);
    sky_texture_destroy(s, SKY_TEX_MS_ORDER_PREV);
    if (!rc) { /* the sum, in the order's first six layers */
        const sky_hillaire_tables *t = &hs->tables;
        for (size_t i = 0; i < texels; i++)
            for (int q = 0; q < SKY_HL_MS_ALL; q++) {
                int slot = order_slot(q);
                rgba[4u * texels * (size_t)(slot / 4) + 4u * i + (size_t)(slot % 4)] =
                    q < 3 ? t->multiscatter[3 * i + (size_t)q] : t->ms_moments[SKY_HL_MOMENTS * i + (size_t)(q - 3)];
            }
        if (sky_texture_create_lut_layers(s, SKY_TEX_MULTISCATTER, SKY_LAYER_ATMOSPHERE, mn, mn, MS_LAYERS, rgba, err,
                                          err_len))
            rc = -2;
    }
    free(rgba);
    free(orders);
    if (rc == -1)
        sky_format(err, err_len, "sky_create: building the multiple-scattering table failed (out of memory or a GL "
                   "error)");
    return rc ? -1 : 0;
}

/* CORE33: the three tables as float textures, the framebuffer that
 * renders into them and the three build programs; the transmittance and
 * multiple-scattering tables are built here (once: they depend on the
 * atmosphere alone). Their sizes must be powers of two here (the builds
 * read them edge to edge). */
static int create_gpu_build(sky_core *s, sky_hillaire_state *hs, char *err, size_t err_len)
{
    const sky_hillaire_settings *set = &hs->tables.settings;
    int tw = set->transmittance_width, th = set->transmittance_height, mn = set->multiscatter_size;
    if (next_pow2(tw) != tw || next_pow2(th) != th || next_pow2(mn) != mn) {
        sky_format(err, err_len, "sky_create: luts: the transmittance (%dx%d) and multiple-scattering (%d) tables "
                   "must be powers of two", tw, th, mn);
        return -1;
    }
    if (sky_texture_create_lut(s, SKY_TEX_TRANSMITTANCE, SKY_LAYER_ATMOSPHERE, tw, th, 1, err, err_len)) return -1;
    const sky_snippet *snippets[1] = {&build_snippet}, *order_snippets[2] = {&build_snippet, &order_snippet};
    if (sky_program_build(s, &hs->transmittance_build, "fullscreen.vert", "transmittance_build.frag", snippets, 1, err,
                          err_len) ||
        sky_program_build(s, &hs->multiscatter_build, "fullscreen.vert", "multiscatter_build.frag", order_snippets, 2,
                          err, err_len) ||
        sky_program_build(s, &hs->skyview_build, "fullscreen.vert", "skyview_build.frag", snippets, 1, err, err_len))
        return -1;
    if (!(hs->fbo = sky_gl_target_create(s, SKY_TEX_SKYVIEW, err, err_len))) return -1;
    /* the constants of the build */
    const sky_atmosphere_params *a = &hs->tables.atm;
    sky_frame *f = &s->frame;
    double R = a->planet_radius_km, Rt = a->top_radius_km;
    f->hl_geometry[0] = (float)R;
    f->hl_geometry[1] = (float)Rt;
    f->hl_geometry[2] = (float)sqrt(Rt * Rt - R * R);
    f->hl_geometry[3] = (float)R;
    f->hl_profile[0] = a->rayleigh_scale_height_km;
    f->hl_profile[1] = a->mie_scale_height_km;
    f->hl_profile[2] = a->ozone_peak_km;
    f->hl_profile[3] = a->ozone_half_width_km;
    for (int c = 0; c < 3; c++) {
        f->hl_rayleigh[c] = a->rayleigh_scattering[c];
        f->hl_mie_sca[c] = a->mie_scattering[c];
        f->hl_mie_ext[c] = a->mie_extinction[c];
        f->hl_ozone[c] = a->ozone_absorption[c];
        f->hl_albedo[c] = a->ground_albedo[c];
    }
    f->hl_sizes[0] = (float)set->skyview_width;
    f->hl_sizes[1] = (float)set->skyview_height;
    f->hl_sizes[2] = (float)tw;
    f->hl_sizes[3] = (float)th;
    f->hl_misc.multiscatter_size = (float)mn;
    f->hl_misc.skyview_steps = (float)set->skyview_steps;
    f->hl_misc.mie_g = a->mie_g;
    f->hl_steps[0] = (float)set->transmittance_steps;
    for (int c = 0; c < 3; c++) f->hl_chi[c] = (float)hs->tables.chi[c];
    f->hl_chi_zonal[0] = (float)hs->tables.chi[3];
    f->hl_chi_zonal[1] = (float)hs->tables.chi[4];
    /* the two fixed tables, built here and read back for the CPU's rays
     * (the host's lighting) */
    gpu_pass(s, hs->fbo, &hs->transmittance_build, SKY_TEX_TRANSMITTANCE, tw, th);
    if (sky_gl_read_rgb(s, hs->fbo, SKY_TEX_TRANSMITTANCE, tw, th, hs->tables.transmittance)) {
        sky_format(err, err_len, "sky_create: reading the lookup tables back failed (out of memory or a GL error)");
        return -1;
    }
    return build_multiscatter(s, hs, mn, err, err_len);
}

int sky_hillaire_create(sky_core *s, sky_hillaire_state **out, char *err, size_t err_len)
{
    sky_hillaire_state *hs = *out = calloc(1, sizeof *hs);
    if (!hs) {
        sky_format(err, err_len, "out of memory for the Hillaire tables");
        return -1;
    }
    char why[200];
    if (sky_hillaire_init(&hs->tables, &s->atm_rgb, &s->cfg.luts, why, sizeof why)) {
        sky_format(err, err_len, "sky_create: luts: %s", why);
        return -1;
    }
    double t0 = sky_now_ms();
    const sky_hillaire_settings *set = &hs->tables.settings;
    int w = next_pow2(set->skyview_width), h = next_pow2(set->skyview_height);
    /* COMPAT20 wants power-of-two RGBA8 textures: the table sits in the
     * corner of one, and the shader maps its texel centres there */
    if (sky_texture_create_lut(s, SKY_TEX_SKYVIEW, SKY_LAYER_ATMOSPHERE, w, h, s->profile == SKY_GL_CORE33, err,
                               err_len))
        return -1;
    if (s->profile == SKY_GL_CORE33) {
        /* the builds bind programs and textures: the host's state comes back */
        sky_gl_state host;
        sky_gl_state_save(s, &host);
        int rc = create_gpu_build(s, hs, err, err_len);
        sky_gl_state_restore(s, &host);
        if (rc) return -1;
    } else {
        sky_hillaire_build_transmittance(&hs->tables);
        if (sky_hillaire_build_multiscatter(&hs->tables)) {
            sky_format(err, err_len, "out of memory for the multiple-scattering table");
            return -1;
        }
        size_t texels = (size_t)set->skyview_width * set->skyview_height;
        hs->skyview_encoded = malloc(texels * 4);
        hs->build.encoded = malloc(texels * 4);
        hs->build.table = malloc(texels * 3 * sizeof(float));
        if (!hs->skyview_encoded || !hs->build.encoded || !hs->build.table) {
            sky_format(err, err_len, "out of memory for the sky-view texture");
            return -1;
        }
    }
    s->lut_ms += sky_now_ms() - t0; /* both tables: the GPU's finished by the read-back */
    hs->skyview_valid = 0;
    return 0;
}

void sky_hillaire_destroy(sky_core *s, sky_hillaire_state *hs)
{
    if (!hs) return;
    sky_gl_target_destroy(s, hs->fbo);
    sky_program_destroy(s, &hs->transmittance_build);
    sky_program_destroy(s, &hs->multiscatter_build);
    sky_program_destroy(s, &hs->skyview_build);
    sky_program_destroy(s, &hs->froxel_build);
    sky_hillaire_free(&hs->tables);
    free(hs->skyview_encoded);
    free(hs->build.encoded);
    free(hs->build.table);
    free(hs);
}

/* Luminance of the brightest texel of a row (the encoding's top). */
static double row_brightest(const float *row, int w)
{
    double brightest = 0.0;
    for (int i = 0; i < w; i++)
        brightest = fmax(brightest, 0.2126 * row[3 * i] + 0.7152 * row[3 * i + 1] + 0.0722 * row[3 * i + 2]);
    return brightest;
}

/* COMPAT20's encoding of rows row0 .. row1 - 1: a 16-bit level of log2
 * luminance over the table's top SKYVIEW_STOPS stops (0: black, below
 * them), high byte in R and low byte in G, and the rg chromaticity in B
 * and A. */
static void encode_rows(const float *table, unsigned char *encoded, int w, int row0, int row1, double log2_floor)
{
    for (int i = row0 * w; i < row1 * w; i++) {
        const float *t = table + 3 * (size_t)i;
        double r = fmax(t[0], 0.0), g = fmax(t[1], 0.0), b = fmax(t[2], 0.0);
        double sum = r + g + b, Y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        /* level 0 is black (the ground in the planet's shadow), the rest
         * the log scale from the floor up */
        double level = Y > 0.0 ? (log2(Y) - log2_floor) / SKYVIEW_STOPS : -1.0;
        unsigned q = level > 0.0 ? (unsigned)lround(sky_clampd(level, 1.0 / 65535.0, 1.0) * 65535.0) : 0u;
        unsigned char *o = encoded + 4 * (size_t)i;
        o[0] = (unsigned char)(q >> 8);
        o[1] = (unsigned char)(q & 255u);
        o[2] = (unsigned char)lround(255.0 * (sum > 0.0 ? r / sum : 1.0 / 3.0));
        o[3] = (unsigned char)lround(255.0 * (sum > 0.0 ? g / sum : 1.0 / 3.0));
    }
}

static void build_start(skyview_build *b, double altitude_km, double sun_mu)
{
    b->active = 1;
    b->next = 0;
    b->sun_mu = sun_mu;
    b->altitude_km = altitude_km;
    b->brightest = 0.0;
}

/* Runs the build on, a unit at a time: a row built (hillaire_cpu.c marches
 * each row on its own), or, once all are built and the brightest texel is
 * known, a row encoded. With budget_ms < 0, to the end; else until the
 * next unit would pass budget_ms since the call began, judged by the
 * dearest unit of this call (at least one unit a call, so that every call
 * moves it on; a clock that steps back ends the slice too). Returns 1 when
 * the table is complete. */
static int build_run(sky_hillaire_state *hs, double budget_ms)
{
    skyview_build *b = &hs->build;
    int w = hs->tables.settings.skyview_width, h = hs->tables.settings.skyview_height;
    double t0 = budget_ms >= 0.0 ? sky_now_ms() : 0.0, last = t0, dearest = 0.0;
    for (int units = 0; b->next < 2 * h; units++) {
        if (budget_ms >= 0.0 && units > 0) {
            double now = sky_now_ms(), spent = now - t0;
            dearest = fmax(dearest, now - last);
            last = now;
            if (!(spent >= 0.0 && spent + dearest <= budget_ms)) return 0;
        }
        if (b->next < h) {
            int j = b->next;
            sky_hillaire_build_skyview_rows(&hs->tables, b->altitude_km, b->sun_mu, j, j + 1, b->table);
            b->brightest = fmax(b->brightest, row_brightest(b->table + (size_t)j * w * 3, w));
        } else {
            int j = b->next - h;
            if (j == 0) b->log2_floor = log2(fmax(b->brightest, 1e-30)) - SKYVIEW_STOPS;
            encode_rows(b->table, b->encoded, w, j, j + 1, b->log2_floor);
        }
        b->next++;
    }
    return 1;
}

/* The finished build becomes the table in use (its buffers take the old
 * table's, for the next build); the next draw uploads it. */
static void build_install(sky_hillaire_state *hs)
{
    skyview_build *b = &hs->build;
    sky_hillaire_install_skyview(&hs->tables, &b->table, b->altitude_km, b->sun_mu);
    unsigned char *shown = hs->skyview_encoded;
    hs->skyview_encoded = b->encoded;
    b->encoded = shown;
    hs->skyview_log2_floor = b->log2_floor;
    hs->skyview_sun_mu = b->sun_mu;
    hs->skyview_altitude_km = b->altitude_km;
    hs->skyview_valid = 1;
    hs->skyview_uploaded = 0;
    b->active = 0;
}

int sky_hillaire_frame(sky_core *s, sky_hillaire_state *hs)
{
    sky_frame *f = &s->frame;
    if (!hs) return 0;
    int rebuilt = 0;
    const sky_hillaire_settings *set = &hs->tables.settings;
    double R = s->atm.planet_radius_km, top = s->atm.top_radius_km;
    double alt_km = sky_clampd(s->observer.altitude_m / 1000.0, 0.0, top - R);
    double mu = sky_clampd(f->sun_dir[1], -1.0, 1.0);
    int moved_alt = !hs->skyview_valid || fabs(alt_km - hs->skyview_altitude_km) > SKYVIEW_ALTITUDE_THRESHOLD_KM;
    int stale = moved_alt || fabs(asin(mu) - asin(hs->skyview_sun_mu)) > SKYVIEW_SUN_THRESHOLD;
    if (!hs->skyview_encoded) {
        /* CORE33: on the GPU in sky_draw */
        if (stale) {
            hs->skyview_sun_mu = mu;
            hs->skyview_altitude_km = alt_km;
            hs->skyview_valid = 1;
            hs->skyview_uploaded = 0;
            rebuilt = 1;
        }
    } else if (!stale) {
        /* the table in use still fits (the sun came back): a build for
         * another sun is dropped */
        hs->build.active = 0;
    } else {
        /* COMPAT20: on the CPU now, at once or a slice (SKYVIEW_SUN_JUMP) */
        double t0 = sky_now_ms();
        if (!hs->skyview_valid) hs->drawn_sun_mu = mu; /* creation: the first frame */
        if (moved_alt || fabs(asin(mu) - asin(sky_clampd(hs->drawn_sun_mu, -1.0, 1.0))) > SKYVIEW_SUN_JUMP) {
            build_start(&hs->build, alt_km, mu);
            build_run(hs, -1.0);
            build_install(hs);
            rebuilt = 1;
        } else {
            if (!hs->build.active) build_start(&hs->build, alt_km, mu);
            if (build_run(hs, SKYVIEW_SLICE_MS)) {
                build_install(hs);
                rebuilt = 1;
            }
        }
        s->lut_ms += sky_now_ms() - t0;
    }
    /* everything below describes the table in use (the one on the GPU,
     * or going there at the next draw), not the sun of this frame */
    f->hl_geometry[3] = (float)(R + hs->skyview_altitude_km);
    f->hl_misc.sun_mu = (float)hs->skyview_sun_mu;
    const sky_texture *tex = &s->textures[SKY_TEX_SKYVIEW];
    f->skyview_map[0] = (float)set->skyview_width;
    f->skyview_map[1] = (float)set->skyview_height;
    f->skyview_map[2] = tex->width ? (float)set->skyview_width / (float)tex->width : 1.0f;
    f->skyview_map[3] = tex->height ? (float)set->skyview_height / (float)tex->height : 1.0f;
    /* the geometric horizon of an observer at r: the tangent to the
     * ground (the table's rows put it at v = 0.5) */
    double theta_h = SKY_PI - asin(sky_clampd(R / (R + hs->skyview_altitude_km), 0.0, 1.0));
    f->skyview_horizon[0] = (float)theta_h;
    f->skyview_horizon[1] = (float)(SKY_PI - theta_h);
    f->skyview_decode[0] = hs->skyview_encoded ? 1.0f : 0.0f;
    f->skyview_decode[1] = (float)hs->skyview_log2_floor;
    f->skyview_decode[2] = (float)SKYVIEW_STOPS;
    return rebuilt;
}

/* CORE33: one pass over the table's corner of the sky-view texture. */
static void build_on_gpu(sky_core *s, sky_hillaire_state *hs)
{
    const sky_hillaire_settings *set = &hs->tables.settings;
    double t0 = sky_now_ms();
    gpu_pass(s, hs->fbo, &hs->skyview_build, SKY_TEX_SKYVIEW, set->skyview_width, set->skyview_height);
    /* the time it takes: only where the host asked for GPU timings (a
     * glFinish stalls the pipeline); else what the submission cost */
    if (s->cfg.profile_layers) sky_gl_finish(s);
    s->lut_ms += sky_now_ms() - t0;
}

void sky_hillaire_upload(sky_core *s, sky_hillaire_state *hs)
{
    if (!hs) return;
    hs->drawn_sun_mu = s->frame.sun_dir[1]; /* what the next jump is measured from */
    if (hs->skyview_uploaded || !hs->skyview_valid) return;
    const sky_hillaire_settings *set = &hs->tables.settings;
    if (hs->skyview_encoded)
        sky_texture_update_lut(s, SKY_TEX_SKYVIEW, set->skyview_width, set->skyview_height, hs->skyview_encoded, NULL);
    else
        build_on_gpu(s, hs);
    hs->skyview_uploaded = 1;
}

int sky_hillaire_froxels(sky_core *s, sky_hillaire_state *hs, const float clip_to_dir[16], char *err, size_t err_len)
{
    enum { N = SKY_FROXEL_SIZE, PASS = 8 };
    if (!hs || !hs->fbo) {
        sky_format(err, err_len, "the froxel volume needs Hillaire's tables on the GPU (CORE33, the hillaire and "
                   "blend paths)");
        return -1;
    }
    double t0 = sky_now_ms();
    if (!s->textures[SKY_TEX_FROXELS].id &&
        sky_texture_create_volume(s, SKY_TEX_FROXELS, SKY_LAYER_ATMOSPHERE, N, N, N, err, err_len))
        return -1;
    if (!hs->froxel_build.id) {
        const sky_snippet *snippets[2] = {&build_snippet, &froxel_snippet};
        if (sky_program_build(s, &hs->froxel_build, "fullscreen.vert", "froxel_build.frag", snippets, 2, err,
                              err_len))
            return -1;
    }
    sky_frame *f = &s->frame;
    memcpy(f->froxel_clip_to_dir, clip_to_dir, sizeof f->froxel_clip_to_dir);
    f->froxel[1] = (float)SKY_FROXEL_KM_PER_SLICE;
    f->froxel[2] = 1.0f; /* a step per slice: the air of one km changes little */
    for (int first = 0; first < N; first += PASS) {
        sky_gl_target t;
        f->froxel[0] = (float)first;
        sky_gl_target_begin_slices(s, hs->fbo, SKY_TEX_FROXELS, first, PASS, N, N, &t);
        sky_program_apply(s, &hs->froxel_build);
        sky_gl_draw_arrays(s, GL_TRIANGLES, 0, 3);
        sky_gl_target_end_slices(s, PASS, &t);
    }
    if (s->cfg.profile_layers) sky_gl_finish(s);
    s->lut_ms += sky_now_ms() - t0;
    return 0;
}

sky_hillaire_tables *sky_hillaire_state_tables(const sky_hillaire_state *hs)
{
    return hs ? (sky_hillaire_tables *)&hs->tables : NULL;
}

void sky_hillaire_skyview_at(const sky_hillaire_state *hs, double *sun_mu, double *altitude_km)
{
    *sun_mu = hs ? hs->skyview_sun_mu : 0.0;
    *altitude_km = hs ? hs->skyview_altitude_km : 0.0;
}

void sky_hillaire_eval(const sky_core *s, const sky_hillaire_state *hs, const double d[3], double rgb[3])
{
    const sky_frame *f = &s->frame;
    double sun[3] = {f->sun_dir[0], f->sun_dir[1], f->sun_dir[2]};
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!hs) return;
    /* the sun at the elevation of the table in use, at its own azimuth:
     * the summary made from this (the host's ambient and fog, the
     * exposure) belongs to the sky on screen, which lags a moving sun
     * while COMPAT20 builds the next table. A table built for this very
     * sun takes the sun as it is. */
    double mu = hs->skyview_sun_mu;
    if (mu != sun[1]) {
        double across = hypot(sun[0], sun[2]), c = sqrt(fmax(0.0, 1.0 - mu * mu));
        if (across > 1e-9) {
            sun[0] *= c / across;
            sun[2] *= c / across;
        } else {
            sun[0] = c;
            sun[2] = 0.0;
        }
        sun[1] = mu;
    }
    sky_hillaire_ray(&hs->tables, hs->skyview_altitude_km, d, sun, rgb);
    for (int i = 0; i < 3; i++) rgb[i] *= f->sun_irradiance[i];
}
