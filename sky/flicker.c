/*
 * Roden & Parberry's night sky (sec. 4): the 256x256 flicker-star texture
 * tiled over the dome and the 128x128 galaxy image stretched over it (baked
 * into the dome's vertices). The shader is flicker.glsl; this file owns the
 * star texture, the galaxy lookup and the flicker clock.
 */
#include "layer.h"

/* Fastest flicker, at G = 255, in cycles per second. */
#define SKY_FLICKER_RATE_MAX 2.0
/* kcd/m^2 of a star texel of intensity 1 on a fully dark night: about ten
 * times the moonless sky, so stars read clearly after exposure. */
#define SKY_FLICKER_STAR_LUMINANCE 2.5e-5

static const sky_uniform_desc flicker_uniforms[] = {
    SKY_UT("u_flicker_tex", SKY_TEX_FLICKER),
    SKY_UF("u_flicker_phase", SKY_U_F1, flicker_phase),
    SKY_UF("u_star_luminance", SKY_U_F1, star_luminance),
};
static const sky_snippet flicker_snippet = {"SKY_HAS_FLICKER", "flicker.glsl", flicker_uniforms,
                                         SKY_UNIFORM_COUNT(flicker_uniforms), NULL};

typedef struct flicker_state {
    double phase; /* the flicker clock, wrapped (see flicker_advance) */
} flicker_state;

static int flicker_create(sky_core *s, void *state, char *err, size_t err_len)
{
    (void)state;
    /* the galaxy is not a GPU texture: dome.c bakes it into the dome's
     * vertices through sky_flicker_galaxy_vertex */
    return sky_texture_load(s, SKY_TEX_FLICKER, SKY_LAYER_FLICKER, "flicker.png", 256, 256, 1, err, err_len);
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
    const flicker_state *st = state;
    sky_frame *f = &s->frame;
    f->flicker_phase = (float)(255.0 * st->phase);
    f->star_luminance = (float)SKY_FLICKER_STAR_LUMINANCE * f->night * f->star_local_gain;
    /* Leave out what adds nothing: a star layer whose brightest texel would
     * not reach a quarter of an 8-bit step is not evaluated at all. */
    if (f->star_luminance * f->exposure < 1.0f / 1024.0f) f->star_luminance = 0.0f;
}

static int flicker_visible(const sky_core *s, const void *state)
{
    (void)state;
    return s->frame.star_luminance > 0.0f;
}

double sky_flicker_clock(const void *state) { return ((const flicker_state *)state)->phase; }

const sky_layer_class sky_flicker_layer = {
    .slot = SKY_LAYER_FLICKER,
    .feature = SKY_FLICKER_STARS,
    .state_size = sizeof(flicker_state),
    .dome_role = SKY_DOME_NIGHT,
    .dome_snippet = &flicker_snippet,
    .create = flicker_create,
    .advance = flicker_advance,
    .reset_clock = flicker_reset,
    .frame = flicker_frame,
    .visible = flicker_visible,
};
