/*
 * Roden & Parberry's clouds (sec. 3): one packed RGBA texture, two primary
 * layers drifting in slightly different directions and speeds, a detail
 * layer and a thin stretched upper layer. The shader is clouds.glsl; this
 * file owns the texture, the drift and the uniforms.
 */
#include "layer.h"

#include <math.h>
#include <string.h>

#define SKY_CLOUD_TEXTURE_SIZE 512

static const sky_uniform_desc cloud_uniforms[] = {
    SKY_UT("u_clouds_tex", SKY_TEX_CLOUDS),
    SKY_UF("u_cover", SKY_U_F1, cover),
    SKY_UF("u_density", SKY_U_F1, density),
    SKY_UF("u_sunset", SKY_U_F1, sunset),
    SKY_UF("u_cloud_uv_scale", SKY_U_F1, cloud_uv_scale),
    SKY_UF("u_cloud_offset0", SKY_U_F2, cloud_offset0),
    SKY_UF("u_cloud_offset1", SKY_U_F2, cloud_offset1),
    SKY_UF("u_cloud_offset_detail", SKY_U_F2, cloud_offset_detail),
    SKY_UF("u_cloud_offset_upper", SKY_U_F2, cloud_offset_upper),
    SKY_UF("u_cloud_light", SKY_U_F3, cloud_light),
    SKY_UF("u_sunset_color", SKY_U_F3, sunset_color),
};
static const sky_snippet clouds_snippet = {"SKY_HAS_CLOUDS", "clouds.glsl", cloud_uniforms,
                                        SKY_UNIFORM_COUNT(cloud_uniforms)};

/* Drift of each layer in texture periods per second at speed 1. The two
 * primary layers differ by about 13 degrees and 20 % in speed (R-P 3.2), so
 * their sum changes shape as they slide apart. */
const double sky_cloud_velocity[4][2] = {
    {0.0200, 0.0060},  /* layer 0: photo          */
    {0.0165, 0.0088},  /* layer 1: noise          */
    {0.0300, 0.0100},  /* detail                  */
    {0.0120, 0.0015},  /* thin upper layer        */
};

typedef struct clouds_state {
    double offsets[4][2]; /* wrapped into [0,1): layers 0, 1, detail, upper */
} clouds_state;

static int clouds_create(sky_core *s, void *state, char *err, size_t err_len)
{
    (void)state;
    return sky_texture_load(s, SKY_TEX_CLOUDS, SKY_LAYER_CLOUDS, "clouds.png", SKY_CLOUD_TEXTURE_SIZE,
                            SKY_CLOUD_TEXTURE_SIZE, 1, err, err_len);
}

static void clouds_advance(sky_core *s, void *state, double dt)
{
    clouds_state *st = state;
    /* The texture repeats with period 1, so wrapping each offset into [0, 1)
     * changes nothing on screen while keeping float uniforms exact after
     * any amount of running time. */
    for (int l = 0; l < 4; l++)
        for (int i = 0; i < 2; i++)
            st->offsets[l][i] = sky_phase_advance(st->offsets[l][i], s->params.speed * sky_cloud_velocity[l][i], dt);
}

static void clouds_frame(sky_core *s, void *state)
{
    const clouds_state *st = state;
    sky_frame *f = &s->frame;
    const sky_params *p = &s->params;
    f->cover = p->cover;
    f->density = p->density;
    f->sunset = p->sunset;
    /* height: high clouds (1) look smaller, so more texture periods fit
     * across the dome (R-P 3.1: height scales the texture coordinates). */
    f->cloud_uv_scale = (float)(0.15 * pow(4.0, p->height));
    float *offsets[4] = {f->cloud_offset0, f->cloud_offset1, f->cloud_offset_detail, f->cloud_offset_upper};
    for (int l = 0; l < 4; l++)
        for (int i = 0; i < 2; i++) offsets[l][i] = (float)st->offsets[l][i];
    /* R-P line 28's amount of sunlight, in luminance: half of the day sky's
     * scale as skylight plus the direct sun through the atmosphere; at night
     * clouds are lit by the night sky, so they hide the stars, and by the
     * moon, which makes them brighter than the sky around them. */
    static const float moon_tint[3] = {0.95f, 0.97f, 1.0f};
    for (int i = 0; i < 3; i++)
        f->cloud_light[i] = f->sky_luminance * (0.45f + 1.1f * f->daylight * f->sun_transmittance[i]) +
                            0.6f * f->night_luminance + 4.0e-7f * f->moonlight * moon_tint[i];
    f->sunset_color[0] = 1.0f;
    f->sunset_color[1] = 0.42f;
    f->sunset_color[2] = 0.18f;
}

/* At cover 0 Roden-Parberry's line 15 makes every cloud texel vanish: the
 * dome then takes its variant without cloud code. */
static int clouds_visible(const sky_core *s, const void *state)
{
    (void)state;
    return s->params.cover > 0.0f;
}

static void clouds_reset(void *state) { memset(state, 0, sizeof(clouds_state)); }

const double *sky_clouds_offsets(const void *state) { return &((const clouds_state *)state)->offsets[0][0]; }

const sky_layer_class sky_clouds_layer = {
    .slot = SKY_LAYER_CLOUDS,
    .feature = SKY_CLOUDS,
    .state_size = sizeof(clouds_state),
    .dome_role = SKY_DOME_FRONT,
    .dome_snippet = &clouds_snippet,
    .create = clouds_create,
    .advance = clouds_advance,
    .reset_clock = clouds_reset,
    .frame = clouds_frame,
    .visible = clouds_visible,
};
