/*
 * Roden & Parberry's clouds (sec. 3): one packed RGBA texture, two primary
 * layers drifting in slightly different directions and speeds, a detail
 * layer and a thin stretched upper layer. The shader is clouds.glsl; this
 * file owns the texture, the drift and the uniforms.
 *
 * A texture fetch is most of what a cloud pixel costs on a software
 * rasteriser (each about a full-screen pass of its own), so the texture is
 * packed further at load, as the paper packs its four images into one:
 * the detail image, which R-P sample at three times the first layer's
 * coordinate, is baked into the blue channel at that coordinate (three
 * periods per period, box-filtered), so one fetch at the first layer's
 * coordinate gives both the photo and its detail; the detail now drifts
 * with the first layer. The sunset gradient (alpha) depends on the angle
 * from the sun alone: the dome evaluates it per vertex from samples of
 * the alpha channel (u_sunset_gradient), the small quads of the sun, moon
 * and stars still fetch it.
 */
#include "layer.h"
#include "moonlight.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SKY_CLOUD_TEXTURE_SIZE 512

static const sky_uniform_desc cloud_uniforms[] = {
    SKY_UT("u_clouds_tex", SKY_TEX_CLOUDS),
    SKY_UF("u_cover", SKY_U_F1, cover),
    SKY_UF("u_density", SKY_U_F1, density),
    SKY_UF("u_upper_cover", SKY_U_F1, upper_cover),
    SKY_UF("u_deck", SKY_U_F1, deck),
    SKY_UF("u_haze", SKY_U_F2, haze),
    SKY_UF("u_flash_dir", SKY_U_F4, flash_dir),
    SKY_UL("u_flash_light", SKY_U_F3, flash_light, SKY_RGB),
    SKY_UF("u_sunset", SKY_U_F1, sunset),
    SKY_UF("u_cloud_uv_scale", SKY_U_F1, cloud_uv_scale),
    SKY_UF("u_cloud_texels_per_step", SKY_U_F1, cloud_texels_per_step),
    SKY_UF("u_dome_step_pixels", SKY_U_F1, dome_step_pixels),
    SKY_UF("u_cloud_offset0", SKY_U_F2, cloud_offset0),
    SKY_UF("u_cloud_offset1", SKY_U_F2, cloud_offset1),
    SKY_UF("u_cloud_offset_upper", SKY_U_F2, cloud_offset_upper),
    SKY_UL("u_cloud_light", SKY_U_F3, cloud_light, SKY_RGB),
    SKY_UF("u_sunset_color", SKY_U_F3, sunset_color),
    SKY_UFV("u_sunset_gradient", sunset_gradient),
};
/* clouds.glsl in both stages: the dome finds its cloud coordinates and
 * sunset per vertex */
static const sky_snippet clouds_snippet = {"SKY_HAS_CLOUDS", "clouds.glsl", cloud_uniforms,
                                        SKY_UNIFORM_COUNT(cloud_uniforms), "clouds.glsl", NULL, NULL};

/* Drift of each layer in texture periods per second at speed 1. The two
 * primary layers differ by about 13 degrees and 20 % in speed (R-P 3.2), so
 * their sum changes shape as they slide apart. */
const double sky_cloud_velocity[SKY_CLOUD_LAYERS][2] = {
    {0.0200, 0.0060},  /* layer 0: photo (and its detail) */
    {0.0165, 0.0088},  /* layer 1: noise          */
    {0.0120, 0.0015},  /* thin upper layer        */
};

/* The texture every STRIDE texels (R photo, G noise, B detail baked), for
 * the clouds' mean opacity on the CPU. */
#define SKY_CLOUD_SAMPLE_STRIDE 8
enum { CLOUD_SAMPLES = SKY_CLOUD_TEXTURE_SIZE / SKY_CLOUD_SAMPLE_STRIDE };

typedef struct clouds_state {
    double offsets[SKY_CLOUD_LAYERS][2]; /* wrapped into [0,1) */
    unsigned char sample[CLOUD_SAMPLES * CLOUD_SAMPLES][3];
    float mean_for[4];                   /* cover, density, upper_cover and
                                            deck of cloud_mean              */
    int mean_valid;
} clouds_state;

/* The blue channel (detail) replaced by the detail at three times the
 * coordinate: texel x covers the original's 3x .. 3x + 2 (its centre, at
 * 3 (x + 0.5), is the middle one), averaged, so the minified detail does
 * not alias. The image is periodic, so indices wrap. */
static void bake_detail(unsigned char *rgba)
{
    enum { N = SKY_CLOUD_TEXTURE_SIZE };
    unsigned char *detail = malloc(N * N);
    if (!detail) return; /* then the detail stays at the first layer's scale */
    for (int i = 0; i < N * N; i++) detail[i] = rgba[4 * i + 2];
    for (int y = 0; y < N; y++)
        for (int x = 0; x < N; x++) {
            int sum = 0;
            for (int j = 0; j < 3; j++)
                for (int i = 0; i < 3; i++) sum += detail[((3 * y + j) % N) * N + (3 * x + i) % N];
            rgba[4 * (y * N + x) + 2] = (unsigned char)((sum + 4) / 9);
        }
    free(detail);
}

/* The alpha channel down the texture's middle column, where clouds.glsl's
 * per-pixel lookup reads it (u = 0.5, v clamped to 0.01 .. 0.99), sampled
 * at SKY_SUNSET_SAMPLES points across 0..1 for the dome's vertices. */
static void sample_sunset(const unsigned char *rgba, float out[SKY_SUNSET_SAMPLES])
{
    enum { N = SKY_CLOUD_TEXTURE_SIZE };
    for (int k = 0; k < SKY_SUNSET_SAMPLES; k++) {
        double v = sky_clampd((double)k / (SKY_SUNSET_SAMPLES - 1), 0.01, 0.99) * N - 0.5;
        int y0 = (int)floor(v), y1 = y0 + 1;
        double f = v - y0;
        y0 = y0 < 0 ? 0 : y0, y1 = y1 > N - 1 ? N - 1 : y1;
        /* u = 0.5 falls between the columns N/2 - 1 and N/2 */
        double a0 = (rgba[4 * (y0 * N + N / 2 - 1) + 3] + rgba[4 * (y0 * N + N / 2) + 3]) / 510.0;
        double a1 = (rgba[4 * (y1 * N + N / 2 - 1) + 3] + rgba[4 * (y1 * N + N / 2) + 3]) / 510.0;
        out[k] = (float)(a0 + (a1 - a0) * f);
    }
}

static int clouds_create(sky_core *s, void *state, char *err, size_t err_len)
{
    clouds_state *st = state;
    unsigned char *rgba = NULL;
    if (sky_asset_load_rgba(s, "clouds.png", SKY_CLOUD_TEXTURE_SIZE, SKY_CLOUD_TEXTURE_SIZE, &rgba, err, err_len))
        return -1;
    bake_detail(rgba);
    for (int y = 0; y < CLOUD_SAMPLES; y++)
        for (int x = 0; x < CLOUD_SAMPLES; x++)
            for (int c = 0; c < 3; c++)
                st->sample[y * CLOUD_SAMPLES + x][c] =
                    rgba[4 * ((size_t)y * SKY_CLOUD_SAMPLE_STRIDE * SKY_CLOUD_TEXTURE_SIZE +
                              (size_t)x * SKY_CLOUD_SAMPLE_STRIDE) + (size_t)c];
    sample_sunset(rgba, s->frame.sunset_gradient);
    /* Where the dome is drawn into its image, the quads over it read the
     * clouds' cover from there and nothing reads the alpha channel: the
     * texture keeps three channels (a quarter less memory). */
    int channels = 4;
    if (s->dome_divisor) {
        enum { N = SKY_CLOUD_TEXTURE_SIZE };
        for (int i = 0; i < N * N; i++)
            for (int c = 0; c < 3; c++) rgba[3 * i + c] = rgba[4 * i + c];
        channels = 3;
    }
    int rc = sky_texture_create(s, SKY_TEX_CLOUDS, SKY_LAYER_CLOUDS, rgba, channels, SKY_CLOUD_TEXTURE_SIZE,
                                SKY_CLOUD_TEXTURE_SIZE, 1, err, err_len);
    sky_png_free(rgba);
    return rc;
}

static void clouds_advance(sky_core *s, void *state, double dt)
{
    clouds_state *st = state;
    /* The texture repeats with period 1, so wrapping each offset into [0, 1)
     * changes nothing on screen while keeping float uniforms exact after
     * any amount of running time. */
    if (!s->weather.set) {
        for (int l = 0; l < SKY_CLOUD_LAYERS; l++)
            for (int i = 0; i < 2; i++)
                st->offsets[l][i] =
                    sky_phase_advance(st->offsets[l][i], s->params.speed * sky_cloud_velocity[l][i], dt);
        return;
    }
    /* Under a weather, the wind's integral over the step (exact however
     * the clock is stepped). A wind of 5 m/s along the first layer's own
     * direction drifts every layer as the sliders do; another turns them
     * together (the second and upper layers keep their angles and speeds
     * to the first) and scales them by its speed. */
    double k[2];
    sky_weather_wind_integral(&s->weather, s->running_before, s->running, k);
    const double *v0 = sky_cloud_velocity[0];
    double n0 = sqrt(v0[0] * v0[0] + v0[1] * v0[1]);
    for (int l = 0; l < SKY_CLOUD_LAYERS; l++) {
        const double *v = sky_cloud_velocity[l];
        /* the rotation and scale taking the first layer's direction to
         * this layer's velocity, per 5 m/s */
        double cs = (v[0] * v0[0] + v[1] * v0[1]) / (5.0 * n0), sn = (v0[0] * v[1] - v0[1] * v[0]) / (5.0 * n0);
        double d[2] = {cs * k[0] - sn * k[1], sn * k[0] + cs * k[1]};
        for (int i = 0; i < 2; i++) st->offsets[l][i] = sky_phase_advance(st->offsets[l][i], s->params.speed, d[i]);
    }
}

/* clouds.glsl's sky_cloud_grey, R-P lines 14-25 and the upper layer:
 * (grey, alpha) from the first layer's photo and detail, the second
 * layer's noise and the upper layer's noise, all 0..1. */
static void cloud_grey(double photo, double detail, double noise, double upper, double cover, double density,
                       double upper_cover, double deck, double *grey, double *alpha)
{
    double g = photo + noise * (1.0 - photo);
    double a = (g - (1.0 - cover)) / sky_clampd(cover, 0.05, 1.0);
    g = g + detail * (1.0 - g);
    a *= detail + (1.0 - detail) * density;
    double k = density * fmax(a, 0.0) * 2.0;
    g = fmin(g + k, 1.5 - 0.5 * (g + k));
    a += k;
    g = sky_clampd(g, 0.0, 1.0);
    a = sky_clampd(a, 0.0, 1.0);
    if (deck > 0.0) {
        g += (0.55 + 0.45 * g - g) * deck;
        a += (1.0 - a) * deck;
    }
    double thin = sky_clampd((upper - 0.55) * 2.5, 0.0, 1.0) * 0.35 * upper_cover * (1.0 - a);
    *grey = g + thin * (1.0 - g);
    *alpha = a + thin;
}

/* The clouds' mean opacity and grey x opacity over the texture: the three
 * layers drift apart, so over time every texel of one meets every texel
 * of the others; each sample of the first layer is paired with a
 * scrambled sample of the noise and of the upper layer. */
static void cloud_means(const clouds_state *st, double cover, double density, double upper_cover, double deck,
                        float out[2])
{
    enum { N = CLOUD_SAMPLES * CLOUD_SAMPLES };
    double sa = 0.0, sga = 0.0;
    for (int i = 0; i < N; i++) {
        const unsigned char *first = st->sample[i], *second = st->sample[(i * 1031 + 17) % N],
                            *upper = st->sample[(i * 2053 + 911) % N];
        double g, a;
        cloud_grey(first[0] / 255.0, first[2] / 255.0, second[1] / 255.0, upper[1] / 255.0, cover, density,
                   upper_cover, deck, &g, &a);
        sa += a;
        sga += g * a;
    }
    out[0] = (float)(sa / N);
    out[1] = (float)(sga / N);
}

static void clouds_frame(sky_core *s, void *state)
{
    clouds_state *st = state;
    sky_frame *f = &s->frame;
    const sky_params *p = &s->params;
    f->cover = p->cover;
    f->density = p->density;
    f->sunset = p->sunset;
    /* height: high clouds (1) look smaller, so more texture periods fit
     * across the dome (R-P 3.1: height scales the texture coordinates). */
    f->cloud_uv_scale = (float)(0.15 * pow(4.0, p->height));
    float *offsets[SKY_CLOUD_LAYERS] = {f->cloud_offset0, f->cloud_offset1, f->cloud_offset_upper};
    for (int l = 0; l < SKY_CLOUD_LAYERS; l++)
        for (int i = 0; i < 2; i++) offsets[l][i] = (float)st->offsets[l][i];
    /* R-P line 28's amount of sunlight, in luminance: half of the day sky's
     * scale as skylight plus the direct sun through the atmosphere; at night
     * clouds are lit by the night sky, so they hide the stars, and by the
     * moon by the same rule: its sky's scale (twice the moonlit zenith) as
     * skylight, plus its beam as it reaches them (its colour, the air's
     * extinction, set or not: sky_moon_lighting over the light above the
     * air), which makes them brighter than the sky around them. */
    double moon_scale = 2.0 * f->moon_sky_luminance, beam[3] = {0.0, 0.0, 0.0};
    if (moon_scale > 0.0) {
        double top[3];
        float lit[3];
        sky_moon_light_above_air(s, top);
        sky_moon_lighting(s, lit);
        for (int i = 0; i < 3; i++) beam[i] = top[i] > 0.0 ? lit[i] / top[i] : 0.0;
    }
    double night_rest = f->night_luminance - f->moon_sky_luminance;
    for (int i = 0; i < 3; i++)
        f->cloud_light[i] = (float)(f->sky_luminance * (0.45f + 1.1f * f->daylight * f->sun_transmittance[i]) +
                                    0.6 * night_rest + moon_scale * (0.45 + 1.1 * beam[i]));
    /* a weather's deck (light_through below 1): where it covers the sky
     * its base shows the light that passes, diffused and so greyer */
    if (f->light_through < 1.0f) {
        double lt = f->light_through;
        double grey = 0.2126 * f->cloud_light[0] + 0.7152 * f->cloud_light[1] + 0.0722 * f->cloud_light[2];
        for (int i = 0; i < 3; i++) f->cloud_light[i] = (float)(lt * (grey + (f->cloud_light[i] - grey) * lt));
    }
    f->sunset_color[0] = 1.0f;
    f->sunset_color[1] = 0.42f;
    f->sunset_color[2] = 0.18f;
    if (!st->mean_valid || st->mean_for[0] != p->cover || st->mean_for[1] != p->density ||
        st->mean_for[2] != f->upper_cover || st->mean_for[3] != f->deck) {
        if (p->cover > 0.0f)
            cloud_means(st, p->cover, p->density, f->upper_cover, f->deck, f->cloud_mean);
        else
            f->cloud_mean[0] = f->cloud_mean[1] = 0.0f;
        st->mean_for[0] = p->cover;
        st->mean_for[1] = p->density;
        st->mean_for[2] = f->upper_cover;
        st->mean_for[3] = f->deck;
        st->mean_valid = 1;
    }
    f->deck_opacity = f->cloud_mean[0];
}

/* The samples at (u, v) in texture periods, bilinear and wrapped, as the
 * GPU filters the texture (at the samples' coarser step): channel c. */
static double sample_at(const clouds_state *st, double u, double v, int c)
{
    double x = (u - floor(u)) * CLOUD_SAMPLES - 0.5, y = (v - floor(v)) * CLOUD_SAMPLES - 0.5;
    int x0 = (int)floor(x), y0 = (int)floor(y);
    double fx = x - x0, fy = y - y0;
    int xa = (x0 + CLOUD_SAMPLES) % CLOUD_SAMPLES, xb = (x0 + 1 + CLOUD_SAMPLES) % CLOUD_SAMPLES;
    int ya = (y0 + CLOUD_SAMPLES) % CLOUD_SAMPLES, yb = (y0 + 1 + CLOUD_SAMPLES) % CLOUD_SAMPLES;
    double a = st->sample[ya * CLOUD_SAMPLES + xa][c], b = st->sample[ya * CLOUD_SAMPLES + xb][c];
    double cc = st->sample[yb * CLOUD_SAMPLES + xa][c], d = st->sample[yb * CLOUD_SAMPLES + xb][c];
    return ((a + (b - a) * fx) * (1.0 - fy) + (cc + (d - cc) * fx) * fy) / 255.0;
}

void sky_clouds_shadow(const sky_core *s, const void *state, double extent_m, int w, int h, double height_m,
                       int first_row, int row_step, unsigned char *out)
{
    const clouds_state *st = state;
    const sky_frame *f = &s->frame;
    double sy = f->sun_dir[1];
    /* no sun, or one too low to throw the layer's shadow near: its beam
     * (sun_color) is nothing or nearly; the map stays lit */
    if (sy < sin(2.0 * SKY_PI / 180.0) || !(f->cover > 0.0f)) {
        for (int j = first_row; j < h; j += row_step) memset(out + (size_t)j * (size_t)w, 255, (size_t)w);
        return;
    }
    /* a ground point's cloud: up the sun's ray to the layer's height */
    double ox = f->sun_dir[0] / sy * height_m, oz = f->sun_dir[2] / sy * height_m;
    /* clouds.glsl's plane point of a flat layer: its horizontal position
     * over its height, times the height slider's scale */
    double per_m = f->cloud_uv_scale / height_m, side = extent_m / (w > h ? w : h);
    for (int j = first_row; j < h; j += row_step)
        for (int i = 0; i < w; i++) {
            double px = ((i + 0.5 - 0.5 * w) * side + ox) * per_m, py = ((j + 0.5 - 0.5 * h) * side + oz) * per_m;
            /* clouds.glsl's sky_cloud_layers and sky_cloud_upper */
            double u0 = px + st->offsets[0][0], v0 = py + st->offsets[0][1];
            double u1 = (px * 0.96 - py * 0.28) * 1.15 + st->offsets[1][0],
                   v1 = (px * 0.28 + py * 0.96) * 1.15 + st->offsets[1][1];
            double u2 = px * 0.35 + st->offsets[2][0], v2 = py * 2.5 + st->offsets[2][1];
            double grey, alpha;
            /* the layers without a weather's deck: the deck is in sun_color */
            cloud_grey(sample_at(st, u0, v0, 0), sample_at(st, u0, v0, 2), sample_at(st, u1, v1, 1),
                       sample_at(st, u2, v2, 1), f->cover, f->density, f->upper_cover, 0.0, &grey, &alpha);
            /* a cloud passes a fifth of the beam (its thin edges, its
             * forward scattering); under a deck the map evens out */
            double sun = 1.0 - 0.8 * alpha;
            sun += (1.0 - sun) * f->deck;
            out[(size_t)j * (size_t)w + (size_t)i] = (unsigned char)(255.0 * sky_clampd(sun, 0.0, 1.0) + 0.5);
        }
}

/* (layer.h) The clouds' base height: cfg.cloud_height_m at the height slider's
 * middle, scaled as the slider scales the drawn clouds (clouds.c:
 * 0.15 x 4^height texture periods per unit of the plane). */
double sky_cloud_height_m(const sky_core *c)
{
    double base = c->cfg.cloud_height_m > 0.0f ? c->cfg.cloud_height_m : 1500.0;
    return base * pow(4.0, c->params.height - 0.5);
}

/* The fade of detail a pixel cannot hold is judged in the viewport's
 * pixels: a step in the dome's image spans its divisor of them. */
void sky_clouds_image_step(sky_core *s, int step_pixels)
{
    s->frame.dome_step_pixels = (float)step_pixels;
    s->frame.cloud_texels_per_step = (float)SKY_CLOUD_TEXTURE_SIZE / (float)step_pixels;
}

void sky_clouds_mean_at(const sky_core *s, const double d[3], double *alpha, double rgb[3])
{
    const sky_frame *f = &s->frame;
    *alpha = 0.0;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (d[1] <= 0.0) return;
    if (f->cloud_mean[0] > 0.0f) {
        /* sky_clouds_vertex: the fade into the horizon, the sunset amount
         * by the angle from the sun; sky_cloud_colour */
        double fade = sky_smoothstep(0.0, 0.06, d[1]);
        *alpha = f->cloud_mean[0] * (fade + (sky_smoothstep(0.0, 0.008, d[1]) - fade) * f->deck);
        double from_sun =
            sky_clampd(0.5 - 0.5 * (d[0] * f->sun_dir[0] + d[1] * f->sun_dir[1] + d[2] * f->sun_dir[2]), 0.01, 0.99) *
            (SKY_SUNSET_SAMPLES - 1);
        int i = (int)fmin(floor(from_sun), SKY_SUNSET_SAMPLES - 2);
        double sunset =
            (f->sunset_gradient[i] + (f->sunset_gradient[i + 1] - f->sunset_gradient[i]) * (from_sun - i)) * f->sunset;
        double grey = f->cloud_mean[1] / f->cloud_mean[0];
        for (int c = 0; c < 3; c++) rgb[c] = (grey * (1.0 - sunset) + f->sunset_color[c] * sunset) * f->cloud_light[c];
    }
    /* a weather's haze in front (clouds.glsl's sky_weather_haze, in the
     * horizon's light): folded into one colour and cover, so that mixing
     * the sky with them gives the sky, the clouds, then the haze */
    if (f->haze[0] > 0.0f) {
        double h = 1.0 - exp(-f->haze[0] / fmax(d[1], f->haze[1])), a = *alpha, cover = a + (1.0 - a) * h;
        for (int c = 0; c < 3; c++) rgb[c] = cover > 0.0 ? (rgb[c] * a * (1.0 - h) + f->fog_rgb[c] * h) / cover : 0.0;
        *alpha = cover;
    }
}

/* At cover 0 Roden-Parberry's line 15 makes every cloud texel vanish: the
 * dome then takes its variant without cloud code, unless a weather's haze
 * (drawn with the clouds) needs it. */
static int clouds_visible(const sky_core *s, const void *state)
{
    (void)state;
    return s->params.cover > 0.0f || s->frame.haze[0] > 0.0f;
}

static void clouds_reset(void *state)
{
    clouds_state *st = state;
    memset(st->offsets, 0, sizeof st->offsets);
}

const double *sky_clouds_offsets(const void *state) { return &((const clouds_state *)state)->offsets[0][0]; }

const sky_layer_class sky_clouds_layer = {
    .name = "clouds",
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
