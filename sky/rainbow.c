/*
 * Rainbows (SKY_RAINBOW): sunlight (and a full moon's) refracted and
 * reflected once (the primary bow) and twice (the secondary) inside the
 * drops of rain in sunlight, seen around the point opposite the light;
 * and the fogbow, the same in the tiny drops of fog, broad and nearly
 * white. Dome role OPTICS: its light lies over the sky and the clouds in
 * the dome's optics variant (rainbow.glsl), drawn while a bow shows.
 *
 * The table: Airy's theory of the rainbow (Airy 1838; as set out by
 * Nussenzveig 1977, "The theory of the rainbow", Sci. Am. 236(4), and
 * Lee 1998, "Mie theory, Airy theory, and the natural rainbow", Appl.
 * Opt. 37, 1506). Near the rainbow ray the exit angle of a ray of impact
 * parameter x = sin(i) (drop radius 1) is Theta_R + C (x - x0)^2, so the
 * outgoing wavefront is a cubic and the scattered intensity
 *   dsigma/dOmega / (pi a^2) = 2 x0 F (ka)^(1/3) C^(-2/3) Ai(-z)^2 / sin Theta_R,
 *   z = eps (ka)^(2/3) C^(-1/3),
 * eps the angle from the bow toward its lit side (inside the primary,
 * outside the secondary), k = 2 pi / lambda, a the drop's radius, F the
 * Fresnel power of the ray's two refractions and its reflections (the
 * mean of the two polarisations). The factor is the one whose mean over
 * Ai's fringes is geometric optics' two rays, a^2 x0 F / (sin Theta_R
 * sqrt(C eps)) (derived in the comment of bow_airy_phase). Water's index by
 * wavelength: Bashkatov & Genina 2003 (Proc. SPIE 5068, 393), at 20 C.
 * Each value is averaged over the sun's disc (0.53 degrees), where the
 * fringes are finer than the disc over the fringes, and over the drops'
 * sizes: a row's radius from half to twice it (real rain and fog mix
 * sizes, which washes out the fringes of the larger drops and whitens the
 * fogbow: Lee 1998's "natural rainbow").
 *
 * The light: L = E_beam tau p(rho), E_beam the sun's beam at the observer
 * (sky_get_lighting's sun_color, per channel), tau = 1 - exp(-1.5 P) the
 * share of the view the rain of precipitation P fills (P 1: 0.78), p the
 * table's value per steradian at rho from the antisolar point, its
 * spectrum (the sun's, 400..700 nm) through the CIE matching functions in
 * each channel over the sun's own. Drawn below the rain's top, the
 * clouds' base seen 3 km off, fading into the distance at the horizon
 * (a fogbow all around).
 */
#include "layer.h"
#include "atmosphere/spectrum.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BOW_TEXELS 256        /* rho, 0..BOW_RHO_MAX_DEG                     */
#define BOW_ROWS 8            /* drop radius, 0.01 .. 2 mm, evenly in log    */
#define BOW_RHO_MAX_DEG 64.0  /* past the secondary's lit side's first fringes */
#define BOW_RADIUS_MIN_MM 0.01
#define BOW_RADIUS_MAX_MM 2.0
#define BOW_FOG_RADIUS_MM 0.01 /* fog's drops: some 20 um across          */
#define BOW_FOG_RANGE_KM 1.0   /* fog (a fogbow) below this visibility     */
#define BOW_RAIN_DEPTH 1.5     /* the view's optical depth in rain of precipitation 1 */
#define BOW_RAIN_DISTANCE_M 3000.0 /* how far off the rain's top is seen   */
#define SUN_RADIUS_RAD 0.00465
#define DISC_SAMPLES 7
/* Ai(x)^2 tabulated for the table's build, x from AIRY_X0 by AIRY_STEP
 * (linear between: within 1e-4 of its peak), the asymptotic forms beyond */
#define AIRY_X0 (-40.0)
#define AIRY_X1 6.0
#define AIRY_STEP 0.005
#define AIRY_SAMPLES ((int)((AIRY_X1 - AIRY_X0) / AIRY_STEP) + 2)

typedef struct rainbow_state {
    int texture;       /* BOW_TEXELS x BOW_ROWS RGBA8: sqrt(p / p_max)   */
    float scale;       /* p_max, per steradian                          */
    float bow[4];      /* rgb: the bow at the table's 1, kcd/m^2; a: the drops' row (t) */
    float light[4];    /* xyz: toward the bow's light (the sun or the moon,
                          whichever makes the brighter bow); w: 1 grey      */
    float rain[2];     /* the sines of the rain's bottom and top in view  */
    float light_y;     /* the bow's luminance at its peak, kcd/m^2 (visible) */
} rainbow_state;

static const sky_uniform_desc rainbow_uniforms[] = {
    SKY_UTS("u_rainbow_tex", rainbow_state, texture),
    SKY_USL("u_rainbow", SKY_U_F4, rainbow_state, bow, SKY_RGB),
    SKY_US("u_rainbow_light", SKY_U_F4, rainbow_state, light),
    SKY_US("u_rainbow_rain", SKY_U_F2, rainbow_state, rain),
};
static const sky_snippet rainbow_snippet = {"SKY_HAS_RAINBOW", "rainbow.glsl", rainbow_uniforms,
                                            SKY_UNIFORM_COUNT(rainbow_uniforms), NULL, NULL, "sky_rainbow"};

/* ---- Airy's rainbow ----------------------------------------------------------- */

/* Ai(x): its Maclaurin series inside |x| < 6 (terms up to some 1e4 there:
 * ten digits left), the asymptotic forms outside (Abramowitz & Stegun
 * 10.4.59 and 10.4.60, their first terms: within 1e-4 at |x| = 6). */
static double bow_airy_ai(double x)
{
    if (x >= 6.0) {
        double zeta = 2.0 / 3.0 * x * sqrt(x);
        return exp(-zeta) / (2.0 * sqrt(SKY_PI) * pow(x, 0.25)) * (1.0 - 5.0 / (72.0 * zeta));
    }
    if (x <= -6.0) {
        double z = -x, zeta = 2.0 / 3.0 * z * sqrt(z);
        return sin(zeta + SKY_PI / 4.0) / (sqrt(SKY_PI) * pow(z, 0.25));
    }
    /* Ai = c1 f - c2 g (A&S 10.4.2) */
    const double c1 = 0.355028053887817239, c2 = 0.258819403792806798;
    double x3 = x * x * x, f = 1.0, g = x, tf = 1.0, tg = x;
    for (int k = 1; k < 60; k++) {
        tf *= x3 / ((3.0 * k - 1.0) * (3.0 * k));
        tg *= x3 / ((3.0 * k) * (3.0 * k + 1.0));
        f += tf;
        g += tg;
        if (fabs(tf) + fabs(tg) < 1e-17 * (fabs(f) + fabs(g))) break;
    }
    return c1 * f - c2 * g;
}

/* Water's refractive index at lambda_nm, 20 C (Bashkatov & Genina 2003:
 * 1.3199 + 6878 / l^2 - 1.132e9 / l^4 + 1.11e14 / l^6, l in nm). */
static double bow_water_index(double l)
{
    double l2 = l * l;
    return 1.3199 + 6878.0 / l2 - 1.132e9 / (l2 * l2) + 1.11e14 / (l2 * l2 * l2);
}

/* A bow of k internal reflections for index n: its angle from the
 * antisolar point rho_r, the rainbow ray's impact parameter x0, the
 * curvature c of the exit angle in x there (Theta - Theta_R = c (x -
 * x0)^2), and F, the Fresnel power along the ray. */
typedef struct bow_ray {
    double rho_r, x0, c, fresnel, sin_theta;
} bow_ray;

static double bow_deviation(double x, double n, int k)
{
    double i = asin(sky_clampd(x, -1.0, 1.0)), r = asin(sky_clampd(x / n, -1.0, 1.0));
    return 2.0 * (i - r) + k * (SKY_PI - 2.0 * r);
}

static bow_ray bow_geometry(double n, int k)
{
    bow_ray b;
    /* the stationary ray: cos^2 i = (n^2 - 1) / (k^2 + 2k) */
    double c2 = (n * n - 1.0) / (double)(k * k + 2 * k);
    b.x0 = sqrt(sky_clampd(1.0 - c2, 0.0, 1.0));
    double d0 = bow_deviation(b.x0, n, k), h = 1e-4;
    b.c = 0.5 * fabs(bow_deviation(b.x0 + h, n, k) - 2.0 * d0 + bow_deviation(b.x0 - h, n, k)) / (h * h);
    /* the deviation folded into a scattering angle; rho from the antisolar point */
    double theta = fmod(d0, 2.0 * SKY_PI);
    if (theta > SKY_PI) theta = 2.0 * SKY_PI - theta;
    b.rho_r = SKY_PI - theta;
    b.sin_theta = sin(theta);
    /* Fresnel: in at i, k reflections and out at r (the same on both sides) */
    double cos_i = sqrt(c2), sin_r = b.x0 / n, cos_r = sqrt(sky_clampd(1.0 - sin_r * sin_r, 0.0, 1.0));
    double rs = (cos_i - n * cos_r) / (cos_i + n * cos_r), rp = (n * cos_i - cos_r) / (n * cos_i + cos_r);
    rs *= rs;
    rp *= rp;
    b.fresnel = 0.5 * ((1.0 - rs) * (1.0 - rs) * pow(rs, k) + (1.0 - rp) * (1.0 - rp) * pow(rp, k));
    return b;
}

/* p(eps) per steradian over pi a^2 for a bow, at eps from the bow toward
 * its lit side, averaged over the sun's disc (a uniform disc's chord
 * weights) and, where the fringes are finer than the disc, over them.
 * The factor: geometric optics gives two rays near the bow, of summed
 * a^2 x0 F / (sin Theta_R sqrt(c eps)); Airy's Ai(-z)^2 has the mean
 * 1 / (2 pi sqrt(z)) over its fringes, with sqrt(z) = sqrt(eps) (ka)^(1/3)
 * c^(-1/6): their ratio is 2 pi a^2 x0 F (ka)^(1/3) c^(-2/3) / sin Theta_R. */
/* Ai(x)^2 from the table (inside it) or the asymptotic forms */
static double bow_airy_ai2(const float *table, double x)
{
    if (x <= AIRY_X0 || x >= AIRY_X1) {
        double a = bow_airy_ai(x);
        return a * a;
    }
    double u = (x - AIRY_X0) / AIRY_STEP;
    int i = (int)u;
    return table[i] + (table[i + 1] - table[i]) * (u - i);
}

static double bow_airy_phase(const float *ai2, const bow_ray *b, double ka, double eps)
{
    double zscale = pow(ka, 2.0 / 3.0) / cbrt(b->c);
    double factor = 2.0 * b->x0 * b->fresnel * cbrt(ka) / pow(b->c, 2.0 / 3.0) / b->sin_theta;
    double z = eps * zscale;
    /* Past the first fringes, their mean: the drops' sizes (half to twice
     * the row's: 2.5 times in z) put several fringes across the mix from z
     * 3.5 on (the first supernumerary and a half stay), and a sum over a
     * few sizes would instead beat into rings; and
     * where a fringe is narrower than the sun's disc (pi / sqrt(z) of z),
     * the disc averages it out. */
    double mean = z > 0.0 ? factor / (2.0 * SKY_PI * sqrt(z)) : 0.0;
    double to_mean = z > 8.0 && SKY_PI / sqrt(z) / zscale < 0.5 * SUN_RADIUS_RAD ? 1.0 : sky_smoothstep(3.5, 7.0, z);
    if (to_mean >= 1.0) return mean;
    double sum = 0.0, weights = 0.0;
    for (int j = 0; j < DISC_SAMPLES; j++) {
        double u = -1.0 + (2.0 * j + 1.0) / DISC_SAMPLES, w = sqrt(1.0 - u * u);
        sum += w * bow_airy_ai2(ai2, -(eps + u * SUN_RADIUS_RAD) * zscale);
        weights += w;
    }
    return factor * sum / weights * (1.0 - to_mean) + mean * to_mean;
}

/* ---- the table ------------------------------------------------------------------- */

static double bow_row_radius_mm(int row)
{
    return BOW_RADIUS_MIN_MM * pow(BOW_RADIUS_MAX_MM / BOW_RADIUS_MIN_MM, row / (double)(BOW_ROWS - 1));
}

/* The drops' row as a texture coordinate (linear between rows). */
static float bow_row_coordinate(double radius_mm)
{
    double t = log(sky_clampd(radius_mm, BOW_RADIUS_MIN_MM, BOW_RADIUS_MAX_MM) / BOW_RADIUS_MIN_MM) /
               log(BOW_RADIUS_MAX_MM / BOW_RADIUS_MIN_MM);
    return (float)((0.5 + t * (BOW_ROWS - 1)) / BOW_ROWS);
}

/* One row: the primary's and the secondary's light per steradian in each
 * channel over the sun's, at each rho. */
static void bow_table_row(const float *ai2, double radius_mm, float (*rgb)[3])
{
    enum { SIZES = 17 }; /* half to twice the row's radius, evenly in log */
    double size_factor[SIZES];
    for (int j = 0; j < SIZES; j++) size_factor[j] = pow(2.0, (j - (SIZES - 1) / 2) / 8.0);
    double sun_xyz[3] = {0.0, 0.0, 0.0}, sun_rgb[3];
    bow_ray bows[SKY_SPECTRUM_SAMPLES][2];
    double ka[SKY_SPECTRUM_SAMPLES][SIZES], e[SKY_SPECTRUM_SAMPLES], cmf[SKY_SPECTRUM_SAMPLES][3];
    for (int w = 0; w < SKY_SPECTRUM_SAMPLES; w++) {
        double l = sky_spectrum_wavelength_nm(w), n = bow_water_index(l);
        for (int j = 0; j < SIZES; j++) ka[w][j] = 2.0 * SKY_PI * radius_mm * size_factor[j] * 1e6 / l;
        e[w] = sky_spectrum_solar_irradiance(l);
        sky_spectrum_cmf(l, cmf[w]);
        for (int k = 0; k < 3; k++) sun_xyz[k] += e[w] * cmf[w][k];
        bows[w][0] = bow_geometry(n, 1);
        bows[w][1] = bow_geometry(n, 2);
    }
    sky_spectrum_xyz_to_linear_srgb(sun_xyz, sun_rgb);
    for (int t = 0; t < BOW_TEXELS; t++) {
        double rho = t / (double)(BOW_TEXELS - 1) * BOW_RHO_MAX_DEG * SKY_PI / 180.0, xyz[3] = {0.0, 0.0, 0.0};
        for (int w = 0; w < SKY_SPECTRUM_SAMPLES; w++) {
            /* the primary's lit side is inside it, the secondary's outside;
             * the sizes weighted by their cross-sections */
            double p = 0.0, weights = 0.0;
            for (int j = 0; j < SIZES; j++) {
                double area = size_factor[j] * size_factor[j];
                p += area * (bow_airy_phase(ai2, &bows[w][0], ka[w][j], bows[w][0].rho_r - rho) +
                             bow_airy_phase(ai2, &bows[w][1], ka[w][j], rho - bows[w][1].rho_r));
                weights += area;
            }
            p /= weights;
            for (int k = 0; k < 3; k++) xyz[k] += e[w] * p * cmf[w][k];
        }
        double out[3];
        sky_spectrum_xyz_to_linear_srgb(xyz, out);
        /* (spectral colours lie outside sRGB: no channel below 0) */
        for (int k = 0; k < 3; k++) rgb[t][k] = (float)fmax(out[k] / sun_rgb[k], 0.0);
    }
}

static int rainbow_create(sky_core *s, void *state, char *err, size_t err_len)
{
    rainbow_state *st = state;
    static float table[BOW_ROWS][BOW_TEXELS][3];
    float *ai2 = malloc(sizeof *ai2 * AIRY_SAMPLES), peak = 0.0f;
    if (!ai2) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    for (int i = 0; i < AIRY_SAMPLES; i++) {
        double a = bow_airy_ai(AIRY_X0 + i * AIRY_STEP);
        ai2[i] = (float)(a * a);
    }
    for (int row = 0; row < BOW_ROWS; row++) {
        bow_table_row(ai2, bow_row_radius_mm(row), table[row]);
        for (int t = 0; t < BOW_TEXELS; t++)
            for (int k = 0; k < 3; k++) peak = fmaxf(peak, table[row][t][k]);
    }
    free(ai2);
    st->scale = peak > 0.0f ? peak : 1.0f;
    static unsigned char texels[BOW_ROWS * BOW_TEXELS * 4];
    for (int row = 0; row < BOW_ROWS; row++)
        for (int t = 0; t < BOW_TEXELS; t++) {
            unsigned char *p = texels + 4 * (row * BOW_TEXELS + t);
            for (int k = 0; k < 3; k++) p[k] = (unsigned char)(255.0 * sqrt(table[row][t][k] / st->scale) + 0.5);
            p[3] = 255;
        }
    st->texture = sky_texture_register(s);
    if (st->texture < 0 || sky_snippet_bind(s, &rainbow_snippet, state)) {
        sky_format(err, err_len, "out of memory");
        return -1;
    }
    return sky_texture_create(s, (sky_texture_id)st->texture, s->creating_layer, texels, 4, BOW_TEXELS, BOW_ROWS, 0,
                              err, err_len);
}

/* ---- each frame -------------------------------------------------------------------- */

static void rainbow_frame(sky_core *s, void *state)
{
    rainbow_state *st = state;
    memset(st->bow, 0, sizeof st->bow);
    memset(st->light, 0, sizeof st->light);
    st->rain[0] = st->rain[1] = 0.0f;
    st->light_y = 0.0f;
    if (!s->weather.set) return;
    sky_weather w;
    sky_weather_at(&s->weather, s->running, &w);
    /* rain's drops, or fog's: what the bow is seen in, and how much of the view it fills */
    double radius_mm, fill;
    int fog = 0;
    if (w.precipitation_kind == SKY_PRECIPITATION_RAIN && w.precipitation > 0.0f) {
        radius_mm = 0.5 * w.drop_size_mm;
        fill = 1.0 - exp(-BOW_RAIN_DEPTH * w.precipitation);
    } else if (w.visibility_km < BOW_FOG_RANGE_KM) {
        radius_mm = BOW_FOG_RADIUS_MM;
        fill = 1.0 - w.visibility_km / BOW_FOG_RANGE_KM;
        fog = 1;
    } else {
        return;
    }
    /* the light of the brighter bow, while the point opposite it is less
     * than the secondary's 54 degrees below the horizon */
    double reach = sin(54.0 * SKY_PI / 180.0), scale = fill * st->scale;
    int by_moon;
    double y = sky_optics_light(s, s->frame.sun_dir[1] < reach, s->frame.moon_dir[1] < reach, st->bow, st->light,
                                &by_moon);
    for (int i = 0; i < 3; i++) st->bow[i] = (float)(st->bow[i] * scale);
    st->light[3] = by_moon ? 1.0f : 0.0f;
    st->bow[3] = bow_row_coordinate(radius_mm);
    /* the rain: from the horizon (into the distance) to its top, the
     * clouds' base seen BOW_RAIN_DISTANCE_M away; fog all around */
    st->rain[0] = fog ? -1.0f : 0.0f;
    st->rain[1] = fog ? 1.1f : (float)sin(atan2(sky_cloud_height_m(s), BOW_RAIN_DISTANCE_M));
    st->light_y = (float)(y * scale);
}

/* In the optics variant while the bow would add a quarter of an 8-bit
 * step at its peak somewhere above the horizon (its light's antisolar
 * point less than the secondary's 54 degrees below it: rainbow_frame) */
static int rainbow_visible(const sky_core *s, const void *state)
{
    const rainbow_state *st = state;
    return st->light_y * s->frame.exposure >= 1.0 / 1024.0;
}

const sky_layer_class sky_rainbow_layer = {
    .name = "rainbow",
    .slot = SKY_LAYER_NEXT,
    .feature = SKY_RAINBOW,
    .state_size = sizeof(rainbow_state),
    .dome_role = SKY_DOME_OPTICS,
    .dome_snippet = &rainbow_snippet,
    .create = rainbow_create,
    .frame = rainbow_frame,
    .visible = rainbow_visible,
};
