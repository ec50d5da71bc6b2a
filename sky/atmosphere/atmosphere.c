/*
 * What every atmosphere path shares: the night sky's own light, the per-
 * frame dispatch to the selected path, and the CPU summary of a physical
 * path's sky (its mean luminance for the automatic exposure, the
 * irradiance it casts on the ground, the horizon's colour for fog).
 */
#include "atmosphere.h"
#include "../layer.h"
#include "../moonlight.h"
#include "../solar_eclipse.h"
#include "spectrum.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const sky_uniform_desc atmosphere_uniforms[] = {
    SKY_UL("u_night_floor", SKY_U_F3, night_floor, SKY_RGB),
    SKY_UL("u_artificial_glow", SKY_U_F3, artificial_glow, SKY_RGB),
    SKY_UF("u_night_depth", SKY_U_F3, night_depth),
    SKY_UF("u_night_air", SKY_U_F3, night_air),
    SKY_UF("u_eclipse_sky", SKY_U_F4, eclipse_sky),
    SKY_UL("u_ground", SKY_U_F3, ground_rgb, SKY_RGB),
    SKY_UL("u_horizon", SKY_U_F3, fog_rgb, SKY_RGB),
    SKY_UL("u_moonlit_light", SKY_U_F3, moonlit_light, SKY_RGB),
};
/* in both stages: pure arithmetic, which a path evaluated per vertex needs */
const sky_snippet sky_atmosphere_snippet = {"SKY_HAS_ATMOSPHERE", "atmosphere.glsl", atmosphere_uniforms,
                                            SKY_UNIFORM_COUNT(atmosphere_uniforms), "atmosphere.glsl", NULL, NULL};

/* A physical path's sky in a few numbers: the mean luminance over the
 * upper hemisphere, the irradiance on an upward surface and the horizon's
 * luminance, without the night sky's own light. */
typedef struct sky_summary {
    double mean, irradiance[3], fog[3];
} sky_summary;

struct sky_atmosphere_state {
    sky_hillaire_state *hillaire; /* HILLAIRE, BLEND                         */
    sky_summary summary;          /* of the last table rebuild               */
    int summary_valid;            /* 0: the tables changed since             */
    /* the physical paths' moonlit sky (moonlit_frame), per unit of the
     * moon's illuminance, for the moon's place rounded */
    int moon_valid;
    double moon_key[4];           /* rounded altitude, azimuth (deg), the
                                     observer's altitude (m), blend weight */
    double moon_dir[3];           /* the rounded place, horizon frame       */
    double moon_zenith[3];        /* the zenith's radiance, 1/sr            */
    sky_summary moon_summary;
    sky_frame moon_frame;         /* Rayleigh's frame lit by the moon       */
};

static const sky_uniform_desc blend_uniforms[] = {
    SKY_UF("u_blend_weight", SKY_U_F1, blend_weight),
};
const sky_snippet sky_blend_snippet = {"SKY_HAS_BLEND", "blend.glsl", blend_uniforms,
                                       SKY_UNIFORM_COUNT(blend_uniforms), NULL, NULL, NULL};

sky_atmosphere_path sky_blend_partner(sky_atmosphere_path requested)
{
    return requested == SKY_ATMOSPHERE_PREETHAM ? SKY_ATMOSPHERE_PREETHAM : SKY_ATMOSPHERE_RAYLEIGH;
}

int sky_atmosphere_snippets(sky_atmosphere_path path, sky_atmosphere_path blend_partner, int encoded_tables,
                            const sky_snippet **out)
{
    const sky_snippet *tables = encoded_tables ? &sky_hillaire_encoded_snippet : &sky_hillaire_snippet;
    int n = 0;
    out[n++] = &sky_atmosphere_snippet;
    switch (path) {
    case SKY_ATMOSPHERE_PREETHAM: out[n++] = &sky_preetham_snippet; break;
    case SKY_ATMOSPHERE_RAYLEIGH:
        out[n++] = &sky_extinction_snippet;
        out[n++] = &sky_rayleigh_snippet;
        break;
    case SKY_ATMOSPHERE_HILLAIRE:
        out[n++] = &sky_extinction_snippet;
        out[n++] = tables;
        break;
    case SKY_ATMOSPHERE_BLEND:
        /* the extinction serves Hillaire's night layers and the sun's beam
         * whichever analytic path is mixed in (blend.glsl picks it) */
        out[n++] = &sky_extinction_snippet;
        out[n++] = sky_blend_partner(blend_partner) == SKY_ATMOSPHERE_PREETHAM ? &sky_preetham_snippet
                                                                                : &sky_rayleigh_snippet;
        out[n++] = tables;
        out[n++] = &sky_blend_snippet;
        break;
    default: out[n++] = &sky_gradient_snippet; break;
    }
    return n;
}

/* The night sky. Its light above the air comes from the layers that draw
 * it (airglow.c, zodiacal.c); what no layer draws is atmosphere.glsl's
 * floor:
 * - the stars fainter than the star map's V 8 and the diffuse galactic
 *   light, about 25 S10 at high galactic latitude (Leinert et al. 1998,
 *   sec. 5; Roach & Gordon 1973), in the stars' mean colour (B - V 0.7);
 * - with the moon in the scene, its light scattered by the air: some 5
 *   mcd/m^2 at full moon high in the sky, falling faster than the phase
 *   (the opposition surge) and fading as the moon sets, blue;
 * and the artificial glow of light pollution (cfg.bortle): the zenith of
 * the class's published brightness less a natural dark sky's 22.0
 * mag/arcsec^2 (what airglow.c and zodiacal.c give at solar minimum far
 * from the ecliptic; Benn & Ellison 1998 measured 21.9), rising toward the horizon as
 * (1.15 / (sin h + 0.15))^0.7, about 4 times the zenith's at the horizon
 * (Garstang's models of a site among its lights give 3 to 6), in the warm
 * white of a mix of sodium and LED lighting (B - V 1.0).
 * night_luminance is the whole night sky's zenith, these and the layers'
 * glows through the air: what the exposure adapts to. */
#define FAINT_STARS_S10 25.0
#define FAINT_STARS_BV 0.7
#define DARK_SKY_ZENITH_MAG 22.0
#define ARTIFICIAL_BV 1.0
/* the zenith's brightness of each Bortle class, V mag/arcsec^2: the middle
 * of the sky-quality ranges tabulated with Bortle's classes (Bortle 2001,
 * Sky & Telescope 101(2), 126; the SQM chart that goes with it: 1
 * 21.99-22.00, 2 21.89-21.99, 3 21.69-21.89, 4 20.49-21.69, 5
 * 19.50-20.49, 6 18.94-19.50, 7 18.38-18.94, 8 below 18.38, taken as
 * 17.80-18.38, and 9 brighter still, taken as 17.0-17.8) */
static const double bortle_zenith_mag[9] = {21.995, 21.94, 21.79, 21.09, 19.995, 19.22, 18.66, 18.09, 17.4};

double sky_bortle_zenith_mag(double bortle)
{
    double b = sky_clampd(bortle, 1.0, 9.0) - 1.0;
    int i = (int)b < 8 ? (int)b : 7;
    return bortle_zenith_mag[i] + (b - i) * (bortle_zenith_mag[i + 1] - bortle_zenith_mag[i]);
}

static double luminance(const double rgb[3]) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

int sky_atmosphere_is_physical(sky_atmosphere_path path)
{
    return path == SKY_ATMOSPHERE_RAYLEIGH || path == SKY_ATMOSPHERE_HILLAIRE || path == SKY_ATMOSPHERE_BLEND;
}

/* ---- the physical paths' moonlit sky ------------------------------------------- */

/* Jensen et al. (2001): the moonlit sky is the day sky's own model lit by
 * the moon. The physical paths evaluate theirs on the CPU per unit of the
 * moon's illuminance, from the moon's place rounded to MOONLIT_STEP_DEG
 * (so a frame stays a function of its inputs): Rayleigh's closed form
 * (rayleigh.c, its frame computed for the moon), Hillaire's ray march
 * through his tables (sky_hillaire_ray), the blend's mix of the two. The
 * dome carries it per vertex (dome.c) and u_moonlit_light, the moon's light
 * above the air (phase, distance, colour), scales it: a step costs the
 * upper dome's 1537 vertices of the model (milliseconds of CPU:
 * docs/validation.md), once for every quarter degree the moon moves (a
 * minute of its motion). Only while the sun is
 * down (faded in over its last 5 degrees): by day it is a millionth of
 * the sky. */
#define MOONLIT_STEP_DEG 0.25

static void hillaire_moonlit(const sky_core *s, const double d[3], double rgb[3])
{
    const sky_hillaire_tables *t = sky_atmosphere_tables(s);
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!t || !t->transmittance || !t->multiscatter) return;
    double top = t->atm.top_radius_km - t->atm.planet_radius_km;
    double km = sky_clampd(s->observer.altitude_m / 1000.0, 0.0, top);
    sky_hillaire_ray(t, km, d, s->atmosphere_state->moon_dir, rgb);
}

void sky_atmosphere_moonlit_unit(const sky_core *s, const double d[3], double rgb[3])
{
    const struct sky_atmosphere_state *st = s->atmosphere_state;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    if (!st || !st->moon_valid || d[1] < 0.0) return; /* (below: the ground's rule) */
    double w = s->atmosphere == SKY_ATMOSPHERE_HILLAIRE ? 1.0
               : s->atmosphere == SKY_ATMOSPHERE_BLEND  ? st->moon_key[3]
                                                        : 0.0;
    double a[3] = {0, 0, 0}, h[3] = {0, 0, 0};
    if (w < 1.0) sky_rayleigh_eval(&st->moon_frame, d, a);
    if (w > 0.0) hillaire_moonlit(s, d, h);
    for (int i = 0; i < 3; i++) rgb[i] = a[i] + (h[i] - a[i]) * w;
}

static void summarise(const sky_core *s, void (*eval)(const sky_core *, const double d[3], double rgb[3]),
                      sky_summary *out);
static float blend_weight(const sky_core *s);

/* The moon's light into the frame, and the moonlit sky for its rounded
 * place when that moved (a new generation for the dome's vertices).
 * Returns 1 while the moonlit sky shows. */
static int moonlit_frame(sky_core *s)
{
    sky_frame *f = &s->frame;
    struct sky_atmosphere_state *st = s->atmosphere_state;
    for (int i = 0; i < 3; i++) f->moonlit_light[i] = 0.0f;
    double night = 1.0 - sky_smoothstep(0.0, 5.0, f->sun_altitude * 180.0 / SKY_PI);
    if (!(s->features & SKY_MOON) || !sky_atmosphere_is_physical(s->atmosphere) || night <= 0.0) return 0;
    double top[3];
    sky_moon_light_above_air(s, top);
    for (int i = 0; i < 3; i++) f->moonlit_light[i] = (float)(top[i] * night);
    double step = MOONLIT_STEP_DEG;
    double key[4] = {round(s->astro.moon.alt * 180.0 / SKY_PI / step) * step,
                     round(s->astro.moon.az * 180.0 / SKY_PI / step) * step, s->observer.altitude_m,
                     s->atmosphere == SKY_ATMOSPHERE_BLEND ? blend_weight(s) : 0.0};
    if (st->moon_valid && !memcmp(key, st->moon_key, sizeof key)) return 1;
    memcpy(st->moon_key, key, sizeof key);
    sky_horizon_vector(key[0] * SKY_PI / 180.0, key[1] * SKY_PI / 180.0, st->moon_dir);
    if (s->atmosphere != SKY_ATMOSPHERE_HILLAIRE) {
        /* (Rayleigh's sky is linear in its light: a unit irradiance) */
        st->moon_frame = *f;
        for (int i = 0; i < 3; i++) st->moon_frame.sun_dir[i] = (float)st->moon_dir[i];
        sky_rayleigh_light_frame(s, &st->moon_frame);
        for (int i = 0; i < 3; i++) st->moon_frame.sun_irradiance[i] = 1.0f;
    }
    st->moon_valid = 1;
    static const double zenith[3] = {0.0, 1.0, 0.0};
    sky_atmosphere_moonlit_unit(s, zenith, st->moon_zenith);
    summarise(s, sky_atmosphere_moonlit_unit, &st->moon_summary);
    f->moonlit_generation++;
    return 1;
}

static void night_frame(sky_core *s)
{
    sky_frame *f = &s->frame;
    /* every path draws its own moonlit sky (the physical ones per vertex,
     * moonlit_frame), whose zenith the night's adaptation takes */
    double moon_sky = 0.0;
    if (s->atmosphere == SKY_ATMOSPHERE_GRADIENT)
        moon_sky = sky_gradient_moon(s);
    else if (s->atmosphere == SKY_ATMOSPHERE_PREETHAM)
        moon_sky = sky_preetham_moon(s);
    else if (moonlit_frame(s)) {
        const double *z = s->atmosphere_state->moon_zenith;
        double zenith[3];
        for (int i = 0; i < 3; i++) zenith[i] = z[i] * f->moonlit_light[i];
        moon_sky = luminance(zenith);
    }
    float stars[3], glow[3];
    sky_star_color(FAINT_STARS_BV, stars);
    double faint = FAINT_STARS_S10 * sky_mag_arcsec2_to_kcd(27.78);
    for (int i = 0; i < 3; i++) f->night_floor[i] = (float)(faint * stars[i]);
    /* the air between the observer and what shines above it (the night
     * glows here, the stars and planets in stars.vert): Mueller eq. 11's
     * shell of 8 km */
    double depth[3];
    sky_atmosphere_zenith_depth(s, depth);
    const double re = 6371.0, te = 8.0;
    double h = sky_clampd(s->observer.altitude_m / 1000.0, 0.0, te - 0.5);
    for (int i = 0; i < 3; i++) f->night_depth[i] = (float)depth[i];
    f->night_shell[0] = (float)(re + h);
    f->night_shell[1] = (float)(re + te);
    f->night_shell[2] = (float)(te - h);
    f->night_air[0] = (float)((te - h) * (2.0 * (re + h) + te - h) / ((re + h) * (re + h)));
    f->night_air[1] = (float)(2.0 + (te - h) / (re + h));
    f->night_air[2] = (float)((re + h) / (te - h));
    double artificial = 0.0;
    if (s->cfg.bortle > 0.0f)
        artificial = fmax(sky_mag_arcsec2_to_kcd(sky_bortle_zenith_mag(s->cfg.bortle)) -
                              sky_mag_arcsec2_to_kcd(DARK_SKY_ZENITH_MAG), 0.0);
    sky_star_color(ARTIFICIAL_BV, glow);
    for (int i = 0; i < 3; i++) f->artificial_glow[i] = (float)(artificial * glow[i]);
    double glows[3] = {0.0, 0.0, 0.0}, floor_rgb[3] = {f->night_floor[0], f->night_floor[1], f->night_floor[2]};
    for (int g = 0; g < s->glow_count; g++) {
        double rgb[3];
        s->glows[g].layer->glow_zenith(s, s->glows[g].state, rgb);
        for (int i = 0; i < 3; i++) glows[i] += rgb[i];
    }
    double through[3];
    for (int i = 0; i < 3; i++) through[i] = glows[i] * exp(-depth[i]);
    f->night_luminance = (float)(luminance(floor_rgb) + luminance(through) + artificial + moon_sky);
    f->moon_sky_luminance = (float)moon_sky;
}

/* CPU twins of the paths' shaders, radiance in kcd/m^2 without the night
 * floor (Preetham's with its moonlit sky, the blend's partner without).
 * The blend weighs the analytic sky (RAYLEIGH or PREETHAM,
 * cfg.blend_partner) by day (where it is cheapest) and hands the horizon
 * band and twilight, where single scattering from one column falls short,
 * to Hillaire's tables. */
static void eval_preetham(const sky_core *s, const double d[3], double rgb[3])
{
    double moon[3];
    sky_preetham_eval(&s->frame, d, rgb);
    sky_preetham_moon_eval(&s->frame, d, moon);
    for (int i = 0; i < 3; i++) rgb[i] += moon[i];
}
static void eval_rayleigh(const sky_core *s, const double d[3], double rgb[3]) { sky_rayleigh_eval(&s->frame, d, rgb); }
static void eval_hillaire(const sky_core *s, const double d[3], double rgb[3])
{
    sky_hillaire_eval(s, s->atmosphere_state->hillaire, d, rgb);
}
static void eval_blend(const sky_core *s, const double d[3], double rgb[3])
{
    double a[3], b[3], w = s->frame.blend_weight;
    if (sky_blend_partner(s->cfg.blend_partner) == SKY_ATMOSPHERE_PREETHAM)
        sky_preetham_eval(&s->frame, d, a);
    else
        sky_rayleigh_eval(&s->frame, d, a);
    eval_hillaire(s, d, b);
    for (int i = 0; i < 3; i++) rgb[i] = a[i] + (b[i] - a[i]) * w;
}

/* gradient.glsl's sky_atmosphere above the horizon, without its night
 * floor: the day gradient by elevation (sky_gradient_vertex, as the dome's
 * vertices carry it) tinted toward the horizon, and the aureole; the
 * moonlit gradient and its aureole (sky_gradient_moon). */
static double gradient_aureole(double mu, double e)
{
    double mu8 = pow(mu, 8.0);
    return (0.25 * mu8 + 0.6 * pow(mu8, 4.0)) * (1.0 + 1.5 * (1.0 - e));
}

static void eval_gradient(const sky_core *s, const double d[3], double rgb[3])
{
    const sky_frame *f = &s->frame;
    float df[3] = {(float)d[0], (float)d[1], (float)d[2]}, day[3];
    sky_gradient_vertex(s->gradient_texels, df, day);
    double e = sky_clampd(d[1], 0.0, 1.0);
    double mu = fmax(d[0] * f->sun_dir[0] + d[1] * f->sun_dir[1] + d[2] * f->sun_dir[2], 0.0);
    double aureole = gradient_aureole(mu, e), low = (1.0 - e) * (1.0 - e) * (0.6 + 0.4 * mu);
    double mm = fmax(d[0] * f->moon_dir[0] + d[1] * f->moon_dir[1] + d[2] * f->moon_dir[2], 0.0);
    double moon_aureole = gradient_aureole(mm, e);
    for (int i = 0; i < 3; i++)
        rgb[i] = f->day_luminance * (day[i] * (1.0 + (f->horizon_tint[i] - 1.0) * low) +
                                     aureole * f->sun_transmittance[i]) +
                 f->moon_sky[i] * (day[i] + moon_aureole * f->moon_beam[i]);
}

void sky_atmosphere_radiance(const sky_core *s, const double d[3], double rgb[3])
{
    const sky_frame *f = &s->frame;
    if (d[1] < 0.0) { /* sky_ground: the horizon's haze fading into the ground */
        double t = sky_smoothstep(0.0, 0.035, -d[1]);
        for (int i = 0; i < 3; i++) rgb[i] = f->fog_rgb[i] + (f->ground_rgb[i] - f->fog_rgb[i]) * t;
        return;
    }
    switch (s->atmosphere) {
    case SKY_ATMOSPHERE_PREETHAM: eval_preetham(s, d, rgb); break;
    case SKY_ATMOSPHERE_RAYLEIGH: eval_rayleigh(s, d, rgb); break;
    case SKY_ATMOSPHERE_HILLAIRE: eval_hillaire(s, d, rgb); break;
    case SKY_ATMOSPHERE_BLEND: eval_blend(s, d, rgb); break;
    default: eval_gradient(s, d, rgb); break;
    }
    /* the physical paths' moonlit sky (its vertices' values, exactly) */
    if (sky_atmosphere_is_physical(s->atmosphere) && f->moonlit_light[1] > 0.0f) {
        double m[3];
        sky_atmosphere_moonlit_unit(s, d, m);
        for (int i = 0; i < 3; i++) rgb[i] += m[i] * f->moonlit_light[i];
    }
    /* sky_eclipse_dim and sky_night_floor, then what the night layers add
     * through the air (dome.frag) */
    double e = 1.0 - sky_clampd(d[1], 0.0, 1.0), e8 = pow(e, 8.0), y = 1.0 - e;
    int polluted = f->artificial_glow[0] > 0.0f || f->artificial_glow[1] > 0.0f || f->artificial_glow[2] > 0.0f;
    double artificial = polluted ? pow(1.15 / (y + 0.15), 0.7) : 0.0;
    /* the night glows (the layers with glow functions), through the air */
    double glow[3] = {0.0, 0.0, 0.0}, t[3] = {0.0, 0.0, 0.0};
    for (int g = 0; g < s->glow_count; g++) {
        double one[3];
        s->glows[g].layer->glow_at(s, s->glows[g].state, d, one);
        for (int i = 0; i < 3; i++) glow[i] += one[i];
    }
    if (glow[0] + glow[1] + glow[2] > 0.0) sky_night_extinction(s, d, t);
    for (int i = 0; i < 3; i++)
        rgb[i] = rgb[i] * (f->eclipse_sky[0] + f->eclipse_sky[1 + i] * e8) + f->night_floor[i] * (2.0 - y) +
                 f->artificial_glow[i] * artificial + glow[i] * t[i];
}

/* A physical path's sky summarised from its own CPU twin: Gauss-Legendre
 * in the elevation sine (4 nodes on 0..1) times 8 azimuths. The irradiance
 * on an upward surface is 2 pi int L mu dmu; the mean luminance is the
 * solid-angle mean over the upper hemisphere; fog takes the lowest ring. */
static const double mu_node[4] = {0.0694318442, 0.3300094782, 0.6699905218, 0.9305681558};
static void summarise(const sky_core *s, void (*eval)(const sky_core *, const double d[3], double rgb[3]),
                      sky_summary *out)
{
    static const double mu_weight[4] = {0.1739274226, 0.3260725774, 0.3260725774, 0.1739274226};
    memset(out, 0, sizeof *out);
    for (int k = 0; k < 4; k++) {
        double ring[3] = {0, 0, 0};
        double c = sqrt(1.0 - mu_node[k] * mu_node[k]);
        for (int a = 0; a < 8; a++) {
            double az = 2.0 * SKY_PI * (a + 0.5) / 8.0, d[3] = {c * sin(az), mu_node[k], -c * cos(az)}, rgb[3];
            eval(s, d, rgb);
            for (int i = 0; i < 3; i++) ring[i] += rgb[i] / 8.0;
        }
        for (int i = 0; i < 3; i++) out->irradiance[i] += 2.0 * SKY_PI * mu_weight[k] * mu_node[k] * ring[i];
        out->mean += mu_weight[k] * (0.2126 * ring[0] + 0.7152 * ring[1] + 0.0722 * ring[2]);
        if (k == 0)
            for (int i = 0; i < 3; i++) out->fog[i] = ring[i];
    }
}

/* The summary into the frame, with the night sky's own light added. */
static void apply_summary(sky_core *s, const sky_summary *sum)
{
    sky_frame *f = &s->frame;
    /* The rest of the frame (clouds, moon, exposure) reads sky_luminance
     * as the gradient path defines it: about 2.5 times the hemisphere's
     * mean luminance. */
    f->sky_luminance = (float)(2.5 * sum->mean);
    /* the night sky's own light, the moonlit sky by its own summary:
     * Preetham's is in its path's (evaluated every frame), the others'
     * per unit of the moon's light (moonlit_frame) */
    const struct sky_atmosphere_state *st = s->atmosphere_state;
    double rest = f->night_luminance - f->moon_sky_luminance;
    int moonlit = sky_atmosphere_is_physical(s->atmosphere) && st->moon_valid;
    for (int i = 0; i < 3; i++) {
        double m = moonlit ? f->moonlit_light[i] : 0.0;
        f->ambient_rgb[i] = (float)(sum->irradiance[i] + st->moon_summary.irradiance[i] * m + SKY_PI * rest);
        f->fog_rgb[i] = (float)(sum->fog[i] + st->moon_summary.fog[i] * m + rest);
    }
}

/* The analytic paths summarise every frame (32 closed-form evaluations);
 * the tables' paths march 32 rays, dearer than a frame should pay (tens
 * of microseconds: docs/validation.md), so their summary is kept
 * until the sky-view table is rebuilt: it depends on the sun's elevation
 * and the observer's altitude alone (azimuthal means), like the table. */
static void summarise_path(sky_core *s, void (*eval)(const sky_core *, const double d[3], double rgb[3]), int cached)
{
    struct sky_atmosphere_state *st = s->atmosphere_state;
    if (!cached || !st->summary_valid) summarise(s, eval, &st->summary);
    st->summary_valid = cached;
    apply_summary(s, &st->summary);
}

/* The blend's automatic weight: Hillaire's tables (1) with the sun below
 * 15 degrees, an even mix above 60. */
static float blend_weight(const sky_core *s)
{
    if (s->cfg.blend_manual) return s->cfg.blend_weight;
    double h_deg = s->frame.sun_altitude * 180.0 / SKY_PI;
    return (float)(1.0 - 0.5 * sky_smoothstep(15.0, 60.0, h_deg));
}

void sky_atmosphere_zenith_depth(const sky_core *s, double depth[3])
{
    const sky_frame *f = &s->frame;
    if (sky_atmosphere_is_physical(s->atmosphere)) {
        /* the description's columns above the observer (rayleigh.c) */
        for (int i = 0; i < 3; i++) depth[i] = f->tau_rayleigh[i] + f->tau_mie_ext[i] + f->tau_ozone[i];
        return;
    }
    /* the sun's beam model (sun.c), its air thinning with the observer's
     * altitude over an 8 km scale height */
    float zenith[3];
    sky_sun_transmittance(SKY_PI / 2, zenith);
    double thin = exp(-s->observer.altitude_m / 8000.0);
    for (int i = 0; i < 3; i++) depth[i] = -log(zenith[i]) * thin;
}

void sky_atmosphere_frame(sky_core *s)
{
    sky_frame *f = &s->frame;
    /* The direct beam (the sun disc, sunlight on clouds and the host's
     * scene): the physical paths send it through their own description
     * (rayleigh.c's closed-form extinction, which Hillaire's and the
     * blend's night layers use too); the others use the sun model. */
    if (sky_atmosphere_is_physical(s->atmosphere)) {
        sky_rayleigh_frame(s);
        for (int i = 0; i < 3; i++) f->sun_transmittance[i] = (float)exp(-f->sun_depth[i]);
    } else {
        sky_sun_transmittance(f->sun_altitude, f->sun_transmittance);
    }
    /* after the path's columns (sky_rayleigh_frame), which dim the glows,
     * and before the summary, which adds the night sky */
    night_frame(s);
    struct sky_atmosphere_state *st = s->atmosphere_state;
    switch (s->atmosphere) {
    case SKY_ATMOSPHERE_PREETHAM:
        sky_preetham_frame(s);
        summarise_path(s, eval_preetham, 0);
        break;
    case SKY_ATMOSPHERE_RAYLEIGH: summarise_path(s, eval_rayleigh, 0); break;
    case SKY_ATMOSPHERE_HILLAIRE:
        if (sky_hillaire_frame(s, st->hillaire)) st->summary_valid = 0; /* the host's lighting follows the table */
        summarise_path(s, eval_hillaire, 1);
        break;
    case SKY_ATMOSPHERE_BLEND:
        if (sky_hillaire_frame(s, st->hillaire)) st->summary_valid = 0;
        /* Preetham's coefficients follow the sun every frame (closed form);
         * the summary mixing them is kept with the table's, as the
         * Rayleigh partner's is: both change slowly with the sun */
        if (sky_blend_partner(s->cfg.blend_partner) == SKY_ATMOSPHERE_PREETHAM) sky_preetham_frame(s);
        f->blend_weight = blend_weight(s);
        summarise_path(s, eval_blend, 1);
        break;
    default: sky_gradient_frame(s); break;
    }
    /* the fog was taken at the summary's lowest ring, or at the horizon
     * itself for the gradient */
    sky_solar_eclipse_sky(s, s->atmosphere == SKY_ATMOSPHERE_GRADIENT ? 0.0 : mu_node[0]);
    /* The ground under every path (atmosphere.glsl): Lambertian, its
     * luminance the albedo over pi times the illuminance on it, the sky's
     * (the summary's irradiance), the sun's beam through the air, with
     * what a solar eclipse leaves of it, and the moon's (what
     * sky_get_lighting reports, on the level), which is all of a moonlit
     * night's ground. */
    double beam = fmax(sin(f->sun_altitude), 0.0) * sky_solar_eclipse_light_left(s);
    float moon[3] = {0.0f, 0.0f, 0.0f};
    if (s->features & SKY_MOON) sky_moon_lighting(s, moon);
    double moon_up = fmax(s->astro.moon.dir[1], 0.0);
    for (int i = 0; i < 3; i++)
        f->ground_rgb[i] = (float)(s->atm.ground_albedo[i] / SKY_PI *
                                   (f->ambient_rgb[i] + s->sun_irradiance_klx[i] * f->sun_transmittance[i] * beam +
                                    moon[i] * moon_up));
}

int sky_atmosphere_create(sky_core *s, char *err, size_t err_len)
{
    s->atmosphere_state = calloc(1, sizeof *s->atmosphere_state);
    if (!s->atmosphere_state) {
        sky_format(err, err_len, "out of memory for the atmosphere");
        return -1;
    }
    if (s->atmosphere == SKY_ATMOSPHERE_HILLAIRE || s->atmosphere == SKY_ATMOSPHERE_BLEND)
        return sky_hillaire_create(s, &s->atmosphere_state->hillaire, err, err_len);
    return 0;
}

void sky_atmosphere_destroy(sky_core *s)
{
    if (!s->atmosphere_state) return;
    sky_hillaire_destroy(s, s->atmosphere_state->hillaire);
    free(s->atmosphere_state);
    s->atmosphere_state = NULL;
}

void sky_atmosphere_upload(sky_core *s) { sky_hillaire_upload(s, s->atmosphere_state->hillaire); }

int sky_atmosphere_froxels(sky_core *s, const float clip_to_dir[16], char *err, size_t err_len)
{
    return sky_hillaire_froxels(s, s->atmosphere_state ? s->atmosphere_state->hillaire : NULL, clip_to_dir, err,
                                err_len);
}

sky_hillaire_tables *sky_atmosphere_tables(const sky_core *s)
{
    return s->atmosphere_state ? sky_hillaire_state_tables(s->atmosphere_state->hillaire) : NULL;
}

void sky_atmosphere_skyview_at(const sky_core *s, double *sun_mu, double *altitude_km)
{
    sky_hillaire_skyview_at(s->atmosphere_state ? s->atmosphere_state->hillaire : NULL, sun_mu, altitude_km);
}
