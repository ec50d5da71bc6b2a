/*
 * The clouds' shadows for the host's ground (sky.h, "Cloud shadows"): the
 * map on the CPU (clouds.c computes it from the layers as drawn), as a
 * texture of the sky's with the matrix from the host's positions (its
 * GLSL and binder are host_bind.c's, beside the host's other snippets).
 */
#include "sky_internal.h"

#include <math.h>
#include <string.h>

enum { SHADOW_TEXTURE_SIZE = 64 };

static void shadow_pixels(sky *s, double extent_m, int w, int h, int first_row, int row_step, unsigned char *out)
{
    const void *clouds = s->layer_state[SKY_LAYER_CLOUDS];
    if (clouds)
        sky_clouds_shadow(&s->core, clouds, extent_m, w, h, sky_cloud_height_m(&s->core), first_row, row_step, out);
    else
        memset(out, 255, (size_t)w * (size_t)h); /* no clouds drawn, none to cast */
}

sky_result sky_cloud_shadow_image(sky *s, float extent_m, int w, int h, unsigned char *out)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!out) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_cloud_shadow_image: out is NULL");
    if (w < 1 || h < 1 || w > 4096 || h > 4096)
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_cloud_shadow_image: %d x %d is not 1..4096 on each side", w,
                        h);
    if (!(extent_m >= 10.0f && extent_m <= 1e6f))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_cloud_shadow_image: extent %g m is not 10..1e6",
                        (double)extent_m);
    shadow_pixels(s, extent_m, w, h, 0, 1, out);
    return SKY_OK;
}

/* The matrix from a host position (relative to the observer, host units,
 * world frame) to the map: the east and south components in metres over
 * the extent, centred. Column-major. */
static void shadow_matrix(const sky_core *c, double metres_per_unit, double extent_m, float m[16])
{
    static const float east_h[3] = {1.0f, 0.0f, 0.0f}, south_h[3] = {0.0f, 0.0f, 1.0f};
    float east[3], south[3];
    sky_camera_to_world(c, east_h, east);
    sky_camera_to_world(c, south_h, south);
    memset(m, 0, 16 * sizeof *m);
    double k = metres_per_unit / extent_m;
    for (int i = 0; i < 3; i++) {
        m[4 * i + 0] = (float)(k * east[i]);  /* s: west to east  */
        m[4 * i + 1] = (float)(k * south[i]); /* t: north to south, the map's rows */
    }
    m[12] = m[13] = 0.5f;
    m[15] = 1.0f;
}

sky_result sky_get_cloud_shadow(sky *s, float metres_per_unit, float extent_m, sky_cloud_shadow *out)
{
    if (!s) return SKY_ERR_INVALID_ARGUMENT;
    if (!out) return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_cloud_shadow: out is NULL");
    if (!(metres_per_unit >= 1e-6f && metres_per_unit <= 1e6f))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_cloud_shadow: metres_per_unit %g is not 1e-6..1e6",
                        (double)metres_per_unit);
    if (!(extent_m >= 10.0f && extent_m <= 1e6f))
        return sky_fail(s, SKY_ERR_INVALID_ARGUMENT, "sky_get_cloud_shadow: extent %g m is not 10..1e6",
                        (double)extent_m);
    sky_result rc = sky_own_context_check(s, "sky_get_cloud_shadow");
    if (rc != SKY_OK) return rc;
    sky_core *c = &s->core;
    enum { N = SHADOW_TEXTURE_SIZE, QUARTERS = 4 };
    _Static_assert(sizeof s->shadow_map == N * N, "the cached map is the texture's size");
    /* Spread over frames: each call refreshes a quarter of the rows (the
     * clouds drift some metres a frame, a texel is 150 m), all of them
     * when what the map depends on beyond the drift changed: the sun, the
     * sliders, the deck, the extent, or a clock set elsewhere. */
    const sky_frame *f = &c->frame;
    const float key[8] = {f->sun_dir[0], f->sun_dir[1], f->sun_dir[2], f->cover, f->density + 2.0f * f->deck,
                          f->upper_cover, extent_m, (float)sky_cloud_height_m(c)};
    /* (the sun by a tenth of a degree or more: its slow motion under a
     * running time slider moves a shadow a few metres a frame) */
    int full = !c->textures[SKY_TEX_CLOUD_SHADOW].id || memcmp(key + 3, s->shadow_key + 3, 5 * sizeof *key) != 0;
    for (int i = 0; i < 3 && !full; i++) full = fabsf(key[i] - s->shadow_key[i]) > 0.0017f;
    if (full)
        shadow_pixels(s, extent_m, N, N, 0, 1, s->shadow_map);
    else
        shadow_pixels(s, extent_m, N, N, s->shadow_phase, QUARTERS, s->shadow_map);
    s->shadow_phase = (s->shadow_phase + 1) % QUARTERS;
    if (full) memcpy(s->shadow_key, key, sizeof key);
    unsigned char rgba[N * N * 4];
    for (int i = 0; i < N * N; i++)
        rgba[4 * i] = rgba[4 * i + 1] = rgba[4 * i + 2] = rgba[4 * i + 3] = s->shadow_map[i];
    /* the texture: made once, then updated; the host's unit and binding
     * and unpack state come back */
    sky_gl_state host;
    sky_gl_state_save(c, &host);
    char why[160];
    int failed = 0;
    if (!c->textures[SKY_TEX_CLOUD_SHADOW].id)
        failed = sky_texture_create(c, SKY_TEX_CLOUD_SHADOW, SKY_LAYER_CLOUDS, rgba, 4, N, N, 0, why, sizeof why);
    else
        sky_texture_update_lut(c, SKY_TEX_CLOUD_SHADOW, N, N, rgba, NULL);
    sky_gl_state_restore(c, &host);
    if (failed) return sky_fail(s, SKY_ERR_GL, "sky_get_cloud_shadow: %s", why);
    sky_cloud_shadow *last = &s->shadow_last;
    memset(last, 0, sizeof *last);
    last->texture = c->textures[SKY_TEX_CLOUD_SHADOW].id;
    last->size = N;
    last->height_m = (float)sky_cloud_height_m(c);
    last->extent_m = extent_m;
    shadow_matrix(c, metres_per_unit, extent_m, last->matrix);
    unsigned sum = 0;
    for (int i = 0; i < N * N; i++) sum += s->shadow_map[i];
    last->mean = (float)sum / (255.0f * N * N);
    *out = *last;
    return SKY_OK;
}
