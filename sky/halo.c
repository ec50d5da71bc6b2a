/*
 * Halos (SKY_HALO): sunlight (and moonlight) refracted by the hexagonal
 * ice crystals of thin high cloud. Dome role OPTICS: light over the sky and
 * the clouds in the dome's optics variant (halo.glsl), drawn while the
 * thin upper layer is out with the sun or the moon up.
 *
 * - The 22 and 46 degree halos: randomly oriented crystals, light through
 *   two faces at 60 degrees (22) or a side and an end face at 90 (46).
 *   Each ray's deviation through a prism of apex A for a skew ray is the
 *   principal plane's with Bravais' index n' = sqrt(n^2 - sin^2 b) / cos b
 *   (b the ray's angle out of that plane); the angle between the rays is
 *   then cos theta = cos^2 b cos D + sin^2 b (Tape 1994, "Atmospheric
 *   Halos", AGU Antarctic Research Series 64, ch. 2). The table's
 *   profile: those deviations over every orientation (the rays' directions
 *   evenly over the sphere, weighted by the face's projected area), per
 *   steradian, for ice's index at 550 nm, then shifted per wavelength by
 *   the minimum deviation 2 asin(n sin(A / 2)) - A, which sets the sharp
 *   red inner edge (ice's index: a Cauchy fit through Warren & Brandt
 *   2008, J. Geophys. Res. 113, D14220: 1.3185 at 400 nm, 1.3060 at 700).
 *   The share of the light the crystals send along each path: 0.25 for
 *   the 22 degree halo, 0.02 for the 46 (Tape's ray tracings give the 46
 *   a few per cent of the 22's light).
 * - Parhelia (sundogs, moondogs): plates floating face down refract the
 *   light horizontally, at the light's elevation h, minimum deviation
 *   with n' = sqrt(n^2 - sin^2 h) / cos h, which grows with h (22 degrees
 *   at the horizon, 32 at 40 degrees up) until n' > 2 (61 degrees): they
 *   stand out of the halo as the light rises. Their profile in azimuth:
 *   a prism's deviation density ~ 1 / sqrt(D - D_min) past its minimum,
 *   smoothed by the sun's disc and the plates' wobble (a degree).
 *
 * The light: E_beam tau p, tau = 0.15 times the thin layer's cover (a
 * thin cirrus's optical depth; the cirrus state's thin layer, over the
 * sliders' most, and the sliders' 0.35 of cover at cover 1: 0.15).
 */
#include "layer.h"
#include "atmosphere/spectrum.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define HALO_TEXELS 256
#define HALO_RHO_MAX_DEG 60.0
#define HALO_SHARE_22 0.25
#define HALO_SHARE_46 0.02
#define HALO_ICE_DEPTH 0.15      /* optical depth of the thin layer at cover 1 */
#define PROFILE_BINS 500         /* the profile past the minimum, 0..50 degrees by 0.1 */
#define PROFILE_BIN_DEG 0.1
#define SUN_RADIUS_DEG 0.2665
#define PLATE_WOBBLE_DEG 1.0

typedef struct halo_state {
    int texture;       /* HALO_TEXELS x 1 RGBA8: sqrt(p / p_max), rho from the light */
    float scale;       /* p_max per steradian                                       */
    float halo[4];     /* rgb: the halos at the table's 1, kcd/m^2; a: 1 grey (the moon's) */
    float light[4];    /* xyz: toward the light of the brighter halo (the sun or
                          the moon); w: 1 / the cosine of its elevation            */
    float dogs[4];     /* rgb: the parhelia's distance in azimuth per channel
                          (radians); a: their strength over the halo's              */
    float light_y;     /* the halo's peak luminance (visible)                      */
} halo_state;

static const sky_uniform_desc halo_uniforms[] = {
    SKY_UTS("u_halo_tex", halo_state, texture),
    SKY_USL("u_halo", SKY_U_F4, halo_state, halo, SKY_RGB),
    SKY_US("u_halo_light", SKY_U_F4, halo_state, light),
    SKY_US("u_halo_dogs", SKY_U_F4, halo_state, dogs),
};
static const sky_snippet halo_snippet = {"SKY_HAS_HALO", "halo.glsl", halo_uniforms,
                                         SKY_UNIFORM_COUNT(halo_uniforms), NULL, NULL, "sky_halo"};

/* Ice's index at lambda_nm: 1.2999 + 2969 / l^2 (through Warren & Brandt's
 * 1.3185 at 400 nm and 1.3060 at 700; 1.3097 at 550). */
static double halo_ice_index(double l) { return 1.2999 + 2969.0 / (l * l); }

/* A prism's minimum deviation, radians. */
static double halo_minimum_deviation(double n, double apex)
{
    return 2.0 * asin(sky_clampd(n * sin(0.5 * apex), -1.0, 1.0)) - apex;
}

/* The profile of randomly oriented prisms of apex A and index n past
 * their minimum deviation: per steradian of all the light through them,
 * by PROFILE_BIN_DEG bins, smoothed by the sun's disc. */
static void halo_random_prisms(double n, double apex, double *profile)
{
    enum { STEPS_I = 360, STEPS_B = 120 };
    double dmin = halo_minimum_deviation(n, apex), total = 0.0;
    memset(profile, 0, sizeof(double) * PROFILE_BINS);
    for (int jb = 0; jb < STEPS_B; jb++) {
        double b = -0.5 * SKY_PI + (jb + 0.5) * SKY_PI / STEPS_B, cb = cos(b), sb = sin(b);
        double np = sqrt(n * n - sb * sb) / cb;
        for (int ji = 0; ji < STEPS_I; ji++) {
            double i = -0.5 * SKY_PI + (ji + 0.5) * SKY_PI / STEPS_I;
            /* the share of directions (cos b) and the face's projected area (cos i) */
            double w = cb * cos(i);
            total += w;
            double r1 = asin(sin(i) / np), r2 = apex - r1, s2 = np * sin(r2);
            if (fabs(s2) >= 1.0) continue; /* reflected inside: another path */
            double d = i + asin(s2) - apex;
            double cos_theta = cb * cb * cos(d) + sb * sb;
            double theta = acos(sky_clampd(cos_theta, -1.0, 1.0));
            int bin = (int)((theta - dmin) * 180.0 / SKY_PI / PROFILE_BIN_DEG);
            if (bin >= 0 && bin < PROFILE_BINS) profile[bin] += w;
        }
    }
    /* per steradian: a bin's ring is 2 pi sin(theta) d(theta) */
    for (int k = 0; k < PROFILE_BINS; k++) {
        double theta = dmin + (k + 0.5) * PROFILE_BIN_DEG * SKY_PI / 180.0;
        profile[k] /= total * 2.0 * SKY_PI * sin(theta) * PROFILE_BIN_DEG * SKY_PI / 180.0;
    }
    /* the sun's disc: a box of its diameter; farther out a box of a tenth
     * of the distance, which smooths the quadrature's grain in the tail */
    double smooth[PROFILE_BINS];
    int disc = (int)(SUN_RADIUS_DEG / PROFILE_BIN_DEG + 0.5);
    for (int k = 0; k < PROFILE_BINS; k++) {
        double s = 0.0;
        int count = 0, half = k / 10 > disc ? k / 10 : disc;
        for (int j = k - half; j <= k + half; j++, count++)
            if (j >= 0 && j < PROFILE_BINS) s += profile[j];
        smooth[k] = s / count;
    }
    memcpy(profile, smooth, sizeof smooth);
}

/* The profile at delta radians past the minimum (0 before it). */
static double halo_profile_at(const double *profile, double delta)
{
    double u = delta * 180.0 / SKY_PI / PROFILE_BIN_DEG - 0.5;
    if (u < -0.5 || u >= PROFILE_BINS - 1) return 0.0;
    if (u < 0.0) return profile[0];
    int k = (int)u;
    return profile[k] + (profile[k + 1] - profile[k]) * (u - k);
}

static int halo_create(sky_core *s, void *state, char *err, size_t err_len)
{
    halo_state *st = state;
    double *profiles = malloc(sizeof(double) * 2 * PROFILE_BINS);
    if (!profiles) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    static const double apex[2] = {SKY_PI / 3.0, SKY_PI / 2.0}, share[2] = {HALO_SHARE_22, HALO_SHARE_46};
    double n550 = halo_ice_index(550.0);
    for (int k = 0; k < 2; k++) halo_random_prisms(n550, apex[k], profiles + k * PROFILE_BINS);
    /* each texel's spectrum through the matching functions, over the sun's */
    double sun_xyz[3] = {0.0, 0.0, 0.0}, sun_rgb[3];
    for (int w = 0; w < SKY_SPECTRUM_SAMPLES; w++) {
        double l = sky_spectrum_wavelength_nm(w), e = sky_spectrum_solar_irradiance(l), cmf[3];
        sky_spectrum_cmf(l, cmf);
        for (int c = 0; c < 3; c++) sun_xyz[c] += e * cmf[c];
    }
    sky_spectrum_xyz_to_linear_srgb(sun_xyz, sun_rgb);
    static float table[HALO_TEXELS][3];
    float peak = 0.0f;
    for (int t = 0; t < HALO_TEXELS; t++) {
        double rho = t / (double)(HALO_TEXELS - 1) * HALO_RHO_MAX_DEG * SKY_PI / 180.0, xyz[3] = {0.0, 0.0, 0.0};
        for (int w = 0; w < SKY_SPECTRUM_SAMPLES; w++) {
            double l = sky_spectrum_wavelength_nm(w), n = halo_ice_index(l), e = sky_spectrum_solar_irradiance(l), cmf[3];
            double p = 0.0;
            for (int k = 0; k < 2; k++)
                p += share[k] * halo_profile_at(profiles + k * PROFILE_BINS, rho - halo_minimum_deviation(n, apex[k]));
            sky_spectrum_cmf(l, cmf);
            for (int c = 0; c < 3; c++) xyz[c] += e * p * cmf[c];
        }
        double rgb[3];
        sky_spectrum_xyz_to_linear_srgb(xyz, rgb);
        for (int c = 0; c < 3; c++) {
            table[t][c] = (float)fmax(rgb[c] / sun_rgb[c], 0.0);
            peak = fmaxf(peak, table[t][c]);
        }
    }
    free(profiles);
    st->scale = peak > 0.0f ? peak : 1.0f;
    unsigned char texels[HALO_TEXELS * 4];
    for (int t = 0; t < HALO_TEXELS; t++) {
        for (int c = 0; c < 3; c++) texels[4 * t + c] = (unsigned char)(255.0 * sqrt(table[t][c] / st->scale) + 0.5);
        texels[4 * t + 3] = 255;
    }
    st->texture = sky_texture_register(s);
    if (st->texture < 0 || sky_snippet_bind(s, &halo_snippet, state)) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    return sky_texture_create(s, (sky_texture_id)st->texture, s->creating_layer, texels, 4, HALO_TEXELS, 1, 0, err,
                              err_len);
}

/* The parhelia of a light at altitude h (radians): their distance in
 * azimuth per channel (650, 550 and 450 nm), and their strength, which
 * fades as the light climbs past 40 degrees and is gone by 61. */
static void halo_parhelia(double h, float out[4])
{
    static const double channel_nm[3] = {650.0, 550.0, 450.0};
    double ch = cos(h), sh = sin(h);
    out[3] = 0.0f;
    for (int c = 0; c < 3; c++) {
        double n = halo_ice_index(channel_nm[c]), np = sqrt(n * n - sh * sh) / fmax(ch, 1e-6);
        if (np * 0.5 >= 1.0) return;
        out[c] = (float)halo_minimum_deviation(np, SKY_PI / 3.0);
    }
    out[3] = (float)(1.0 - sky_smoothstep(35.0, 60.0, h * 180.0 / SKY_PI));
}

static void halo_frame(sky_core *s, void *state)
{
    halo_state *st = state;
    const sky_frame *f = &s->frame;
    memset(st->halo, 0, sizeof st->halo);
    memset(st->dogs, 0, sizeof st->dogs);
    st->light[0] = st->light[2] = 0.0f;
    st->light[1] = st->light[3] = 1.0f;
    st->light_y = 0.0f;
    /* the thin upper layer's ice: the weather's, or the sliders' 0.35 of cover */
    double tau = HALO_ICE_DEPTH * sky_clampd(f->upper_cover, 0.0, 1.0) * (f->cover > 0.0f || s->weather.set);
    if (!(tau > 0.0)) return;
    /* the light of the brighter halo, above the horizon */
    double scale = tau * st->scale;
    int by_moon;
    double y = sky_optics_light(s, f->sun_dir[1] > -0.01f, f->moon_dir[1] > -0.01f, st->halo, st->light, &by_moon);
    for (int i = 0; i < 3; i++) st->halo[i] = (float)(st->halo[i] * scale);
    st->halo[3] = by_moon ? 1.0f : 0.0f;
    double h = asin(sky_clampd(st->light[1], -1.0, 1.0));
    st->light[3] = (float)(1.0 / fmax(cos(h), 1e-3));
    halo_parhelia(h, st->dogs);
    st->light_y = (float)(y * scale);
}

/* In the optics variant while a halo would add a quarter of an 8-bit step
 * at its peak, its light above the horizon */
static int halo_visible(const sky_core *s, const void *state)
{
    const halo_state *st = state;
    return st->light_y * s->frame.exposure >= 1.0 / 1024.0;
}

const sky_layer_class sky_halo_layer = {
    .name = "halo",
    .slot = SKY_LAYER_NEXT,
    .feature = SKY_HALO,
    .state_size = sizeof(halo_state),
    .dome_role = SKY_DOME_OPTICS,
    .dome_snippet = &halo_snippet,
    .create = halo_create,
    .frame = halo_frame,
    .visible = halo_visible,
};
