/*
 * Roden & Parberry's night sky (sec. 4): the 256x256 flicker-star texture
 * tiled over the dome and the 128x128 galaxy image stretched over it. The
 * galaxy's glow is part of the dome (baked into its vertices,
 * flicker.glsl). The stars are read out of the texture at load and drawn
 * as points (flicker.vert/.frag), each the tent bilinear filtering made of
 * its texel: the same stars, flickering by the same formula, but found
 * once a star rather than once a pixel, and sharp wherever the dome itself
 * is drawn at reduced size (dome.c). This file owns them, the galaxy
 * lookup and the flicker clock.
 */
#include "layer.h"
#include "atmosphere/atmosphere.h"

#include <stdlib.h>

/* Fastest flicker, at G = 255, in cycles per second. */
#define SKY_FLICKER_RATE_MAX 2.0
/* kcd/m^2 of a star texel of intensity 1 on a fully dark night: about ten
 * times the moonless sky, so stars read clearly after exposure. */
#define SKY_FLICKER_STAR_LUMINANCE 2.5e-5
/* The texture: 256 texels, repeated 4 times across the dome coordinate's
 * unit (flicker.glsl's sky_dome_uv * 4 of the paper's tiling). */
#define FLICKER_SIZE 256
#define FLICKER_TILES 4


/* One star: its texel's centre in the dome coordinate (normalised shorts)
 * and the texel (R brightened by the galaxy and divided by 4, G, B, A). */
typedef struct flicker_vertex {
    short uv[2];
    unsigned char texel[4];
} flicker_vertex;

typedef struct flicker_state {
    double phase;          /* the flicker clock, wrapped (see flicker_advance) */
    sky_program program;
    GLuint buffer;
    int count;
    float star_luminance;  /* kcd/m^2 of a full-intensity star texel; 0: off */
    float phase_uniform;   /* the clock in rate units, wrapped                */
    float point_max;       /* the largest point size the context draws        */
} flicker_state;

static const sky_uniform_desc glow_uniforms[] = {
    SKY_USL("u_star_luminance", SKY_U_F1, flicker_state, star_luminance, 1u),
};
static const sky_snippet glow_snippet = {"SKY_HAS_FLICKER", "flicker.glsl", glow_uniforms,
                                         SKY_UNIFORM_COUNT(glow_uniforms), NULL, NULL, NULL};
static const sky_uniform_desc point_uniforms[] = {
    SKY_US("u_flicker_phase", SKY_U_F1, flicker_state, phase_uniform),
    SKY_US("u_point_max", SKY_U_F1, flicker_state, point_max),
};
static const sky_snippet point_snippet = {NULL, NULL, point_uniforms, SKY_UNIFORM_COUNT(point_uniforms),
                                          NULL, NULL, NULL};

/* Every star of every tile that falls inside the horizon circle. */
static int upload_flicker_stars(sky_core *s, flicker_state *st, const unsigned char *tex, const unsigned char *galaxy,
                        char *err, size_t err_len)
{
    enum { TEXELS = FLICKER_SIZE * FLICKER_TILES }; /* across the coordinate's unit */
    int per_tile = 0;
    for (int i = 0; i < FLICKER_SIZE * FLICKER_SIZE; i++) per_tile += tex[4 * i] > 0;
    size_t cap = (size_t)per_tile * (2 * FLICKER_TILES) * (2 * FLICKER_TILES);
    flicker_vertex *v = malloc(sizeof *v * (cap ? cap : 1));
    if (!v) {
        sky_format(err, err_len, "out of memory for the flicker stars");
        return -1;
    }
    int n = 0;
    for (int ty = -FLICKER_TILES; ty < FLICKER_TILES; ty++)
        for (int tx = -FLICKER_TILES; tx < FLICKER_TILES; tx++)
            for (int y = 0; y < FLICKER_SIZE; y++)
                for (int x = 0; x < FLICKER_SIZE; x++) {
                    const unsigned char *t = tex + 4 * (y * FLICKER_SIZE + x);
                    if (!t[0]) continue;
                    double u = (tx * FLICKER_SIZE + x + 0.5) / TEXELS, w = (ty * FLICKER_SIZE + y + 0.5) / TEXELS;
                    double r2 = u * u + w * w;
                    if (r2 >= 1.0) continue;
                    double up = (1.0 - r2) / (1.0 + r2);
                    float d[3] = {(float)(u * (1.0 + up)), (float)up, (float)(w * (1.0 + up))};
                    /* stars inside the galaxy are brightened (1 + 3 g) */
                    double bright = t[0] * (1.0 + 3.0 * sky_flicker_galaxy_vertex(galaxy, d)) / 4.0;
                    flicker_vertex *p = &v[n++];
                    p->uv[0] = (short)(u * 32767.0 + (u < 0 ? -0.5 : 0.5));
                    p->uv[1] = (short)(w * 32767.0 + (w < 0 ? -0.5 : 0.5));
                    p->texel[0] = (unsigned char)(bright + 0.5);
                    p->texel[1] = t[1], p->texel[2] = t[2], p->texel[3] = t[3];
                }
    st->count = n;
    st->buffer = sky_buffer_create(s, GL_ARRAY_BUFFER, v, sizeof *v * (size_t)n, GL_STATIC_DRAW);
    free(v);
    if (!st->buffer) {
        sky_format(err, err_len, "glGenBuffers failed for the flicker stars");
        return -1;
    }
    return 0;
}

static int flicker_create(sky_core *s, void *state, char *err, size_t err_len)
{
    flicker_state *st = state;
    unsigned char *tex = NULL, *galaxy = NULL;
    if (sky_asset_load_rgba(s, "flicker.png", FLICKER_SIZE, FLICKER_SIZE, &tex, err, err_len)) return -1;
    if (sky_asset_load_rgba(s, "galaxy.png", 128, 128, &galaxy, err, err_len)) {
        sky_png_free(tex);
        return -1;
    }
    int rc = upload_flicker_stars(s, st, tex, galaxy, err, err_len);
    sky_png_free(tex);
    sky_png_free(galaxy);
    if (rc) return -1;
    st->point_max = sky_gl_point_size_max(s);
    if (sky_snippet_bind(s, &point_snippet, state)) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    /* the atmosphere's transmittance in front of each star, then its own */
    const sky_snippet *own[SKY_ATMOSPHERE_SNIPPETS + 2];
    int n = sky_atmosphere_snippets(s->atmosphere, s->cfg.blend_partner, s->profile != SKY_GL_CORE33, own);
    own[n++] = &glow_snippet;
    own[n++] = &point_snippet;
    return sky_program_build_over_dome(s, s->dome_snippets, &st->program, "flicker.vert", "flicker.frag", own, n, err,
                                       err_len);
}

static void flicker_destroy(sky_core *s, void *state)
{
    flicker_state *st = state;
    sky_program_destroy(s, &st->program);
    const size_t bytes = sizeof(flicker_vertex) * (size_t)st->count;
    sky_buffers_destroy(s, &st->buffer, &bytes, 1);
}

float sky_flicker_galaxy_vertex(const unsigned char *galaxy, const float d[3])
{
    if (d[1] <= 0.0f) return 0.0f;
    /* the stereographic dome coordinate of flicker.glsl, stretched so the
     * horizon circle fills the 128x128 image; bilinear, clamped at edges */
    double u = (d[0] / (1.0 + d[1]) * 0.5 + 0.5) * 128.0 - 0.5;
    double v = (d[2] / (1.0 + d[1]) * 0.5 + 0.5) * 128.0 - 0.5;
    u = sky_clampd(u, 0.0, 127.0);
    v = sky_clampd(v, 0.0, 127.0);
    int x0 = (int)u, y0 = (int)v, x1 = x0 < 127 ? x0 + 1 : 127, y1 = y0 < 127 ? y0 + 1 : 127;
    double fx = u - x0, fy = v - y0;
#define GAL(x, y) (galaxy[4 * ((y) * 128 + (x))] / 255.0)
    double g = (GAL(x0, y0) * (1 - fx) + GAL(x1, y0) * fx) * (1 - fy) + (GAL(x0, y1) * (1 - fx) + GAL(x1, y1) * fx) * fy;
#undef GAL
    return (float)g;
}

static void flicker_advance(sky_core *s, void *state, double dt)
{
    flicker_state *st = state;
    (void)s;
    /* A star with rate byte k flickers at k/255 * RATE_MAX Hz. The clock
     * tau = RATE_MAX * t / 255 wrapped into [0, 1) advances every star by a
     * whole number of cycles at each wrap, so the wrap is invisible and the
     * float phase k * tau never grows. */
    st->phase = sky_phase_advance(st->phase, SKY_FLICKER_RATE_MAX / 255.0, dt);
}

static void flicker_reset(void *state) { ((flicker_state *)state)->phase = 0.0; }

static void flicker_frame(sky_core *s, void *state)
{
    flicker_state *st = state;
    const sky_frame *f = &s->frame;
    st->phase_uniform = (float)(255.0 * st->phase);
    st->star_luminance = (float)SKY_FLICKER_STAR_LUMINANCE * f->night * f->star_local_gain;
    /* Leave out what adds nothing: a star layer whose brightest texel would
     * not reach a quarter of an 8-bit step is not evaluated at all. */
    if (st->star_luminance * f->exposure < 1.0f / 1024.0f) st->star_luminance = 0.0f;
}

float sky_flicker_star_luminance(const void *flicker_state_)
{
    return ((const flicker_state *)flicker_state_)->star_luminance;
}

static int flicker_visible(const sky_core *s, const void *state)
{
    (void)s;
    return ((const flicker_state *)state)->star_luminance > 0.0f;
}

static int flicker_draw(sky_core *s, void *state)
{
    flicker_state *st = state;
    static const sky_gl_layout layout = {sizeof(flicker_vertex),
                                         {{2, GL_SHORT, GL_TRUE, 0},
                                          {0, 0, 0, 0},
                                          {4, GL_UNSIGNED_BYTE, GL_TRUE, 2 * sizeof(short)}}};
    sky_program_apply(s, &st->program);
    sky_gl_vertices_bind(s, st->buffer, 0, &layout);
    sky_gl_program_point_size(s, 1);
    sky_gl_draw_arrays(s, GL_POINTS, 0, st->count);
    sky_gl_program_point_size(s, 0);
    return 1;
}

static size_t flicker_buffer_bytes(const sky_core *s, const void *state)
{
    (void)s;
    const flicker_state *st = state;
    return st->buffer ? sizeof(flicker_vertex) * (size_t)st->count : 0;
}

double sky_flicker_clock(const void *state) { return ((const flicker_state *)state)->phase; }

const sky_layer_class sky_flicker_layer = {
    .name = "flicker",
    .slot = SKY_LAYER_FLICKER,
    .feature = SKY_FLICKER_STARS,
    .state_size = sizeof(flicker_state),
    .dome_role = SKY_DOME_NIGHT,
    .dome_snippet = &glow_snippet,
    .blend = SKY_BLEND_ADD,
    .create = flicker_create,
    .destroy = flicker_destroy,
    .advance = flicker_advance,
    .reset_clock = flicker_reset,
    .frame = flicker_frame,
    .visible = flicker_visible,
    .draw = flicker_draw,
    .buffer_bytes = flicker_buffer_bytes,
};
