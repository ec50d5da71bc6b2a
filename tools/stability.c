/*
 * The numerical-stability suite: every case sweeps the public API (or, for
 * two formulas the shaders are fed from, the library's internal function)
 * over an extreme and keeps the worst value of one property. A row passes when
 * that worst value is within its tolerance; tolerances come from physics
 * (how fast the sky can move in a step), not from a previous run.
 */
#include "stability.h"

#include "cli.h"
#include "osmesa_ctx.h"
#include "sky.h"
#include "sky_internal.h" /* the formulas behind the shaders' uniforms */
#include "atmosphere/hillaire.h"
#include "atmosphere/reference.h"

#include <GL/gl.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#ifndef _WIN32
#include <unistd.h>
#endif

typedef struct suite {
    sky_stability_row *rows;
    int count;
    sky_stability_row spill; /* a case beyond SKY_STABILITY_MAX_ROWS runs here, unreported */
} suite;

static sky_stability_row *add_row(suite *st, const char *name, const char *property, const char *unit,
                                  double tolerance)
{
    sky_stability_row *r = st->count < SKY_STABILITY_MAX_ROWS ? &st->rows[st->count++] : &st->spill;
    memset(r, 0, sizeof *r);
    r->name = name;
    r->property = property;
    r->unit = unit;
    r->tolerance = tolerance;
    return r;
}

static void keep_worst(sky_stability_row *r, double v)
{
    /* a NaN is the worst value there is */
    if (!(v <= r->worst)) r->worst = isnan(v) ? INFINITY : v;
    r->samples++;
}

static void finish(sky_stability_row *r) { r->pass = r->worst <= r->tolerance; }

/* How far one evaluation's outputs fall outside their ranges (0 inside;
 * a non-finite output is infinitely far). */
static double out_of_range(const sky_astronomy *a)
{
    const double *fields[] = {&a->julian_day_ut, &a->delta_t_s, &a->lmst_deg, &a->sun.distance_km,
                              &a->moon.distance_km, &a->moon_bright_limb_deg, &a->moon_libration_lat_deg,
                              &a->moon_libration_lon_deg, &a->moon_axis_angle_deg, &a->moon_parallactic_deg,
                              &a->sun.ra_deg, &a->moon.ra_deg};
    for (size_t i = 0; i < sizeof fields / sizeof fields[0]; i++)
        if (!isfinite(*fields[i])) return INFINITY;
    double excess = 0.0;
    const sky_body_place *bodies[2] = {&a->sun, &a->moon};
    for (int b = 0; b < 2; b++) {
        const sky_body_place *p = bodies[b];
        double v[4] = {fabs(p->alt_deg) - 90.0, fabs(p->alt_geometric_deg) - 90.0, fabs(p->dec_deg) - 90.0,
                       fabs(p->az_deg - 180.0) - 180.0};
        for (int k = 0; k < 4; k++) {
            if (!isfinite(v[k])) return INFINITY;
            if (v[k] > excess) excess = v[k];
        }
    }
    double unit[5] = {a->moon_illuminated_fraction, a->star_visibility, a->moon_phase_angle_deg / 180.0,
                      a->solar_obscuration, a->solar_flux_fraction};
    if (!isfinite(a->solar_magnitude)) return INFINITY;
    for (int k = 0; k < 5; k++) {
        if (!isfinite(unit[k])) return INFINITY;
        double e = unit[k] < 0.0 ? -unit[k] : unit[k] - 1.0;
        if (e > excess) excess = e;
    }
    /* Mueller's moon factor spans 0.5 (day) .. 0.5 + 1/sqrt 2 (night) */
    double mv = a->moon_visibility, mv_excess = mv < 0.5 ? 0.5 - mv : mv - (0.5 + 1.0 / sqrt(2.0));
    if (!isfinite(mv)) return INFINITY;
    if (mv_excess > excess) excess = mv_excess;
    if (!isfinite(a->umbral_magnitude) || !isfinite(a->penumbral_magnitude)) return INFINITY;
    return excess;
}

/* Latitudes ±90 exactly and the antimeridian, over two days in 10-minute
 * steps, in four seasons: every output finite and in its range. */
static void case_poles(suite *st)
{
    sky_stability_row *r = add_row(st, "poles and antimeridian", "outputs finite, in range", "deg", 0.0);
    const double lats[] = {-90.0, -89.9999, 0.0, 89.9999, 90.0}, lons[] = {-180.0, 0.0, 180.0};
    for (int season = 0; season < 4; season++)
        for (int i = 0; i < 5; i++)
            for (int j = 0; j < 3; j++)
                for (int m = 0; m < 2 * 144; m++) {
                    sky_observer o = {sky_julian_day(2026, 3 + 3 * season, 20, 0, 0, 0.0) + m / 144.0, lats[i],
                                      lons[j], 0.0, 0};
                    sky_astronomy a;
                    if (sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) != SKY_OK)
                        keep_worst(r, INFINITY);
                    else
                        keep_worst(r, out_of_range(&a));
                }
    finish(r);
}

/* The supported years -1999..3000 give finite results at every decade;
 * years outside them are refused. Worst: failures of either kind. */
static void case_date_range(suite *st)
{
    sky_stability_row *r = add_row(st, "dates -4000..+4000", "finite inside -1999..3000, error outside", "cases", 0.0);
    for (int year = -4000; year <= 4000; year += 10) {
        sky_observer o = {sky_julian_day(year, 6, 1, 12, 0, 0.0), 45.0, 10.0, 0.0, 0};
        sky_astronomy a;
        sky_result rc = sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0);
        int inside = year >= -1999 && year <= 3000;
        int bad = inside ? (rc != SKY_OK || out_of_range(&a) > 0.0) : rc == SKY_OK;
        keep_worst(r, r->worst + bad);
    }
    /* the last hour on each side of both edges: year, month, day, hour, accepted */
    const int edges[4][5] = {{-2000, 12, 31, 23, 0}, {-1999, 1, 1, 0, 1}, {3000, 12, 31, 23, 1}, {3001, 1, 1, 0, 0}};
    for (int k = 0; k < 4; k++) {
        sky_observer o = {sky_julian_day(edges[k][0], edges[k][1], edges[k][2], edges[k][3], 0, 0.0), 0.0, 0.0,
                          0.0, 0};
        sky_astronomy a;
        int ok = sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) == SKY_OK;
        keep_worst(r, r->worst + (ok != edges[k][4]));
    }
    finish(r);
}

/* The sun's apparent altitude minute by minute across sunrise and sunset,
 * at the equator (fastest), mid-latitude and the poles: no jump bigger
 * than the sky's rotation allows. The sun moves at most 0.25 deg per
 * minute; refraction adds at most its slope (~0.2 deg per deg, Meeus
 * 16.4 at the horizon), so 0.3 deg per minute bounds an honest step.
 * The same sweep drives Mueller's day-night fades (sec. 5), powers x^32 of
 * the sun's up component s_z: the star fade's steepest slope,
 * 16 x^31 (1 + x^32)^-1.5, is 6.04 per unit s_z (at x^32 = 31/17; the
 * moon's is 4.3); s_z moves at most 0.0044 a minute, and the refraction
 * taper between -1 and -6 degrees speeds the apparent sun by up to 13 %:
 * 0.030 a minute, held to 0.031. */
static void case_sun_continuity(suite *st)
{
    sky_stability_row *r =
        add_row(st, "sun altitude through the horizon", "largest step per minute (refracted)", "deg", 0.30);
    sky_stability_row *fades = add_row(st, "Mueller day-night fades (x^32)",
                                       "star and moon fades: largest step per minute", "", 0.031);
    const double lats[] = {0.0, 45.0, 89.9999, 90.0, -90.0};
    for (int i = 0; i < 5; i++) {
        double prev = NAN, prev_star = NAN, prev_moon = NAN;
        for (int m = 0; m < 3 * 1440; m++) {
            /* the equinox, when the polar sun grazes the horizon */
            sky_observer o = {sky_julian_day(2026, 3, 19, 0, 0, 0.0) + m / 1440.0, lats[i], 0.0, 0.0, 0};
            sky_astronomy a;
            if (sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) != SKY_OK) {
                keep_worst(r, INFINITY);
                continue;
            }
            if (m > 0) {
                keep_worst(r, fabs(a.sun.alt_deg - prev));
                keep_worst(fades, fabs(a.star_visibility - prev_star));
                keep_worst(fades, fabs(a.moon_visibility - prev_moon));
            }
            prev = a.sun.alt_deg;
            prev_star = a.star_visibility;
            prev_moon = a.moon_visibility;
        }
    }
    finish(r);
    finish(fades);
}

/* Phase through the instants of new and full moon (2024-04-08 18:21 and
 * 2024-04-23 23:49 UTC), 2 hours each side in 10-second steps: phase
 * angle in 0..180 and the illuminated fraction continuous. The fraction
 * changes by at most ~0.0001 per 10 s (a 29.5-day cycle), so 0.001 is a
 * generous bound that still catches a flip at phase 0 or 180. */
static void case_new_and_full_moon(suite *st)
{
    sky_stability_row *r =
        add_row(st, "new and full moon instants", "illuminated fraction: largest step per 10 s", "", 0.001);
    const double centres[2] = {sky_julian_day(2024, 4, 8, 18, 21, 0.0), sky_julian_day(2024, 4, 23, 23, 49, 0.0)};
    for (int c = 0; c < 2; c++) {
        double prev = NAN;
        for (int k = -720; k <= 720; k++) {
            sky_observer o = {centres[c] + k * 10.0 / 86400.0, 30.0, -100.0, 0.0, 0};
            sky_astronomy a;
            if (sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) != SKY_OK || out_of_range(&a) > 0.0) {
                keep_worst(r, INFINITY);
                continue;
            }
            if (k > -720) keep_worst(r, fabs(a.moon_illuminated_fraction - prev));
            prev = a.moon_illuminated_fraction;
        }
    }
    finish(r);
}

/* Through the total lunar eclipse of 2022-11-08 (greatest 10:59 UTC),
 * 4 hours each side in 10-second steps: the magnitudes continuous across
 * the edges of penumbra and umbra, and the umbral never above the
 * penumbral. The moon crosses the shadow at ~0.55 deg/h, about 0.003
 * lunar diameters per 10 s; 0.01 allows three times that. */
static void case_eclipse_edges(suite *st)
{
    sky_stability_row *r = add_row(st, "lunar eclipse edges (2022-11-08)",
                                   "magnitudes: largest step per 10 s; umbral <= penumbral", "", 0.01);
    double centre = sky_julian_day(2022, 11, 8, 10, 59, 0.0), prev_u = NAN, prev_p = NAN;
    for (int k = -1440; k <= 1440; k++) {
        sky_observer o = {centre + k * 10.0 / 86400.0, 40.0, -100.0, 0.0, 0};
        sky_astronomy a;
        if (sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) != SKY_OK || out_of_range(&a) > 0.0) {
            keep_worst(r, INFINITY);
            continue;
        }
        /* umbral above penumbral is a failure of any size */
        if (a.umbral_magnitude > a.penumbral_magnitude + 1e-12) keep_worst(r, INFINITY);
        if (k > -1440) {
            keep_worst(r, fabs(a.umbral_magnitude - prev_u));
            keep_worst(r, fabs(a.penumbral_magnitude - prev_p));
        }
        prev_u = a.umbral_magnitude;
        prev_p = a.penumbral_magnitude;
    }
    finish(r);
}

/* Through the total solar eclipse of 2024-04-08 seen near Nazas, Durango
 * (greatest 18:17:20 UT), from before first contact to after last, one
 * second at a time: obscuration and light left continuous across the four
 * contacts. The moon moves against the sun at about 0.5 arcsec/s, which
 * changes the covered fraction by at most 2 v / (pi r_sun) = 3.3e-4 a
 * second (the lens grows by its chord), and the light left at most
 * 1 / (1 - u/3) = 1.25 times that where the bright centre is covered,
 * 4.2e-4; 5e-4 allows a fifth more. */
static void case_solar_eclipse_contacts(suite *st)
{
    sky_stability_row *r = add_row(st, "solar eclipse contacts (2024-04-08)",
                                   "obscuration and light left: largest step per second", "", 5e-4);
    double start = sky_julian_day(2024, 4, 8, 16, 50, 0.0), prev_o = NAN, prev_f = NAN;
    for (int k = 0; k <= 10200; k++) {
        sky_observer o = {start + k / 86400.0, 25.29, -104.14, 0.0, 0};
        sky_astronomy a;
        if (sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) != SKY_OK || out_of_range(&a) > 0.0) {
            keep_worst(r, INFINITY);
            continue;
        }
        if (k > 0) {
            keep_worst(r, fabs(a.solar_obscuration - prev_o));
            keep_worst(r, fabs(a.solar_flux_fraction - prev_f));
        }
        prev_o = a.solar_obscuration;
        prev_f = a.solar_flux_fraction;
    }
    finish(r);
}

/* ---- formulas the frame is built from ------------------------------------------------------ */

/* B-V from -0.5 to +3 (past both ends of real stars, which the colour
 * clamps to -0.4..2.5) in steps of 0.001: every colour finite,
 * non-negative and of unit luminance, as the star shader assumes. */
static void case_star_colour(suite *st)
{
    sky_stability_row *r = add_row(st, "star colour, B-V -0.5..+3", "luminance error; components finite, >= 0", "", 1e-5);
    for (int k = 0; k <= 3500; k++) {
        float rgb[3];
        sky_star_color(-0.5 + k * 0.001, rgb);
        double lum = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
        int sane = isfinite(rgb[0]) && isfinite(rgb[1]) && isfinite(rgb[2]) && rgb[0] >= 0.0f && rgb[1] >= 0.0f &&
                   rgb[2] >= 0.0f;
        keep_worst(r, sane ? fabs(lum - 1.0) : INFINITY);
    }
    finish(r);
}

/* The sun's transmittance (Kasten & Young air mass, whose pole sits at
 * -6.08 degrees) from the nadir to the zenith in 0.001-degree steps: in
 * 0..1 and never falling as the sun rises. Worst: the largest fall. */
static void case_sun_transmittance(suite *st)
{
    sky_stability_row *r =
        add_row(st, "sun transmittance, altitude -90..90", "in 0..1; largest fall as the sun rises", "", 0.0);
    float prev[3] = {0.0f, 0.0f, 0.0f};
    for (int k = -90000; k <= 90000; k++) {
        float t[3];
        sky_sun_transmittance(k * 0.001 * SKY_PI / 180.0, t);
        for (int c = 0; c < 3; c++) {
            if (!(t[c] >= 0.0f && t[c] <= 1.0f)) keep_worst(r, INFINITY);
            keep_worst(r, prev[c] - t[c] > 0.0f ? prev[c] - t[c] : 0.0);
            prev[c] = t[c];
        }
    }
    finish(r);
}

/* ---- render cases: linear HDR output, every pixel finite and >= 0 ------------------------- */

/* The worst pixel of the frame in ctx: INFINITY for a non-finite value,
 * else the most negative component's magnitude. */
static double frame_worst(sky_osmesa *ctx)
{
    sky_osmesa_finish(ctx);
    const float *px = ctx->pixels;
    double worst = 0.0;
    for (size_t i = 0; i < 4u * (size_t)ctx->width * (size_t)ctx->height; i++) {
        if (i % 4 == 3) continue; /* alpha is not light */
        if (!isfinite(px[i])) return INFINITY;
        if (-px[i] > worst) worst = -px[i];
    }
    return worst;
}

/* Draws one frame with sliders p at elapsed time seconds, through the
 * camera at yaw/pitch (or the fisheye), and returns its worst pixel. */
static double worst_pixel(sky_osmesa *ctx, sky *s, const sky_params *p, double seconds, int fisheye, double yaw,
                          double pitch)
{
    float view[16], proj[16];
    sky_cli_camera_at(yaw, pitch, 90.0, ctx->width, ctx->height, view, proj);
    if (sky_set_params(s, p) < 0 || sky_set_elapsed(s, seconds) != SKY_OK) return INFINITY;
    if ((fisheye ? sky_draw_fisheye(s) : sky_draw(s, view, proj)) != SKY_OK) return INFINITY;
    return frame_worst(ctx);
}

/* A sky with every feature in a fresh float context of that profile. */
static sky *open_sky(sky_osmesa *ctx, sky_gl_profile gl, char *err, size_t err_len)
{
    if (sky_osmesa_create(ctx, 48, 32, gl, 1, err, err_len)) return NULL;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.gl_profile = gl;
    cfg.get_proc_address = sky_headless_loader(ctx);
    cfg.output = SKY_OUTPUT_HDR;
    cfg.features = SKY_FEATURES_AVAILABLE;
    sky *s = sky_create(&cfg, err, err_len);
    if (!s) sky_osmesa_destroy(ctx);
    return s;
}

/* All 64 corners of the six sliders (the cloud shader divides by cover;
 * density and sunset drive powers), looking at the horizon, straight up,
 * straight down and as a fisheye. */
static void case_slider_corners(suite *st, sky *s, sky_osmesa *ctx)
{
    sky_stability_row *r =
        add_row(st, "sliders at exactly 0 and 1 (64 corners x 4 views)", "HDR pixels finite, >= 0", "", 0.0);
    const double views[4][3] = {{0, 0, 5}, {0, 90, 90}, {0, 0, -90}, {1, 0, 0}}; /* fisheye, yaw, pitch */
    for (int corner = 0; corner < 64; corner++) {
        sky_params p = sky_default_params();
        p.cover = (float)(corner & 1);
        p.height = (float)((corner >> 1) & 1);
        p.density = (float)((corner >> 2) & 1);
        p.sunset = (float)((corner >> 3) & 1);
        p.speed = (float)((corner >> 4) & 1);
        p.time = (float)((corner >> 5) & 1);
        for (int v = 0; v < 4; v++)
            keep_worst(r, worst_pixel(ctx, s, &p, 0.0, (int)views[v][0], views[v][1], views[v][2]));
    }
    finish(r);
}

/* Stars the catalogue does not hold: V -30 (the sun's magnitude) to +15,
 * B-V -0.5 to +3, placed at the zenith and the nadir (their J2000 places
 * for the default observer at midnight, within the 0.4 degree of
 * precession since), seen straight up, straight down and in a fisheye:
 * the point sizes, glare, extinction over Mueller's optical path (0/0 at
 * the zenith, beyond 90 degrees at the nadir) and scintillation stay
 * finite. The catalogue's first 46 stars stand in for them and come back
 * afterwards. */
static void case_star_extremes(suite *st, sky *s, sky_osmesa *ctx)
{
    sky_stability_row *r = add_row(st, "stars V -30..+15, B-V -0.5..+3, at zenith and nadir",
                                   "HDR pixels finite, >= 0 (3 views); the V -30 star drawn", "", 0.0);
    enum { N = 46 };
    void *stars = s->layer_state[SKY_LAYER_STARS];
    sky_catalog *catalog = stars ? sky_stars_catalog(stars) : NULL;
    if (!catalog || catalog->count < N) {
        keep_worst(r, INFINITY);
        finish(r);
        return;
    }
    sky_star saved[N];
    memcpy(saved, catalog->stars, sizeof saved);
    sky_params night = sky_default_params();
    night.time = 0.0f;
    night.cover = 0.0f;
    sky_set_params(s, &night);
    sky_astronomy a;
    sky_observer o;
    sky_get_astronomy(s, &a);
    sky_get_observer(s, &o);
    double lst = a.lmst_deg * SKY_PI / 180.0, lat = o.latitude_deg * SKY_PI / 180.0;
    for (int i = 0; i < N; i++) {
        sky_star *star = &catalog->stars[i];
        int up = i % 2 == 0;
        star->ra = fmod(lst + (up ? 0.0 : SKY_PI) + 2.0 * SKY_PI, 2.0 * SKY_PI);
        star->dec = up ? lat : -lat;
        star->pm_ra = star->pm_dec = 0.0;
        star->vmag = (float)(-30 + i);
        star->bv = (float)(-0.5 + 3.5 * i / (N - 1));
    }
    sky_stars_reload(stars); /* the next frame uploads them */
    const double views[3][3] = {{0, 0, 90}, {0, 0, -90}, {1, 0, 0}}; /* fisheye, yaw, pitch */
    for (int v = 0; v < 3; v++) {
        keep_worst(r, worst_pixel(ctx, s, &night, 5.0, (int)views[v][0], views[v][1], views[v][2]));
        /* looking up, the V -30 star must be there: brighter than any
         * night sky (1 kcd/m^2), else the sweep tested nothing */
        double brightest = 0.0;
        const float *px = ctx->pixels;
        for (int i = 0; i < ctx->width * ctx->height * 4; i++) brightest = fmax(brightest, px[i]);
        if (v == 0 && !(brightest > 1.0)) keep_worst(r, INFINITY);
    }
    memcpy(catalog->stars, saved, sizeof saved);
    sky_stars_reload(stars);
    finish(r);
}

/* The time slider through sunrise and sunset in steps of 1e-4 (8.6 s),
 * where the day-night fades and the sun quad cross the horizon. */
static void case_sun_at_horizon(suite *st, sky *s, sky_osmesa *ctx)
{
    sky_stability_row *r = add_row(st, "sun crossing the horizon (time slider)", "HDR pixels finite, >= 0", "", 0.0);
    const float centres[2] = {0.25f, 0.75f};
    for (int c = 0; c < 2; c++)
        for (int k = -100; k <= 100; k++) {
            sky_params p = sky_default_params();
            p.cover = 0.5f;
            p.time = centres[c] + (float)k * 1e-4f;
            keep_worst(r, worst_pixel(ctx, s, &p, 0.0, 0, c ? 270.0 : 90.0, 2.0));
            keep_worst(r, worst_pixel(ctx, s, &p, 0.0, 1, 0.0, 0.0));
        }
    finish(r);
}

/* The sunlight a game gets (sky_get_lighting) as the sun sets, time
 * slider steps of 1e-5 (0.86 s): no jump. In 0.86 s the sun sinks
 * 0.0036 deg, 1.4 % of its radius, so at most ~1 % of the disc sets
 * (and the horizon's beam is about 1.2 klx in red): 0.05 klx is a step
 * no honest sunset takes, and the old all-or-nothing cut-off took 1.2. */
static void case_sunset_light(suite *st, sky *s)
{
    sky_stability_row *r = add_row(st, "sunlight through sunset (sky_get_lighting)",
                                   "largest step of sun_color per 0.86 s; rises count", "klx", 0.05);
    sky_params p = sky_default_params();
    double prev[3] = {NAN, NAN, NAN};
    for (int k = 0; k <= 2000; k++) {
        p.time = 0.74f + (float)k * 1e-5f;
        sky_lighting light;
        if (sky_set_params(s, &p) < 0 || sky_update(s, 0.0) != SKY_OK || sky_get_lighting(s, &light) != SKY_OK) {
            keep_worst(r, INFINITY);
            continue;
        }
        for (int c = 0; c < 3; c++) {
            double v = light.sun_color[c];
            if (!isfinite(v) || v < 0.0) keep_worst(r, INFINITY);
            if (k > 0) keep_worst(r, v > prev[c] + 1e-6 ? INFINITY : prev[c] - v); /* the sun is sinking */
            prev[c] = v;
        }
    }
    finish(r);
}

/* Elapsed time far from zero: 1e9 s (32 years of running) and the
 * largest doubles the API accepts stay finite. */
static void case_long_elapsed(suite *st, sky *s, sky_osmesa *ctx)
{
    sky_stability_row *r = add_row(st, "elapsed 1e3 .. 1e12 s", "HDR pixels finite, >= 0", "", 0.0);
    sky_params p = sky_default_params();
    p.speed = 1.0f;
    p.time = 0.9f; /* night: flicker stars and clouds both at work */
    for (double t = 1e3; t <= 1e12; t *= 10.0) keep_worst(r, worst_pixel(ctx, s, &p, t, 1, 0.0, 0.0));
    finish(r);
}

/* Huge, repeated time steps: the clocks must wrap before they overflow.
 * dt up to the largest double, each applied twice, then a night frame. */
static void case_huge_steps(suite *st, sky *s, sky_osmesa *ctx)
{
    sky_stability_row *r = add_row(st, "sky_update dt 1e6 .. DBL_MAX, twice", "HDR pixels finite, >= 0", "", 0.0);
    const double steps[] = {1e6, 1e12, 1e100, 1e300, DBL_MAX};
    sky_params p = sky_default_params();
    p.speed = 1.0f;
    p.time = 0.95f;
    float view[16], proj[16];
    sky_cli_camera_at(0.0, 60.0, 90.0, ctx->width, ctx->height, view, proj);
    for (size_t k = 0; k < sizeof steps / sizeof steps[0]; k++) {
        if (sky_set_params(s, &p) < 0 || sky_set_elapsed(s, 0.0) != SKY_OK) {
            keep_worst(r, INFINITY);
            continue;
        }
        int ok = sky_update(s, steps[k]) == SKY_OK && sky_update(s, steps[k]) == SKY_OK;
        keep_worst(r, ok && sky_draw(s, view, proj) == SKY_OK ? frame_worst(ctx) : INFINITY);
        keep_worst(r, ok && sky_draw_fisheye(s) == SKY_OK ? frame_worst(ctx) : INFINITY);
    }
    finish(r);
}

/* Cameras at the edges: fields of view 0.1..179 degrees, viewports from
 * 1x1 to 8192x8192 (the billboard and moon size math scales with them),
 * looking at the zenith, the nadir and the horizon, at night with every
 * layer on. A degenerate camera (near = far, a collapsed rotation) must be
 * refused; it then counts as handled. */
static void case_camera_extremes(suite *st, sky *s, sky_osmesa *ctx)
{
    sky_stability_row *r =
        add_row(st, "fov 0.1..179, viewport 1x1..8192^2, zenith/nadir", "HDR pixels finite, >= 0", "", 0.0);
    const double fovs[] = {0.1, 1.0, 60.0, 150.0, 179.0}, pitches[] = {90.0, -90.0, 0.5};
    const int sizes[][2] = {{1, 1}, {ctx->width, ctx->height}, {8192, 8192}};
    sky_params p = sky_default_params();
    p.time = 0.0f;
    p.cover = 0.3f;
    if (sky_set_params(s, &p) < 0 || sky_set_elapsed(s, 100.0) != SKY_OK) keep_worst(r, INFINITY);
    for (int v = 0; v < 3; v++)
        for (int f = 0; f < 5; f++)
            for (int k = 0; k < 3; k++) {
                float view[16], proj[16];
                sky_cli_camera_at(0.0, pitches[k], fovs[f], sizes[v][0], sizes[v][1], view, proj);
                glViewport(0, 0, sizes[v][0], sizes[v][1]);
                keep_worst(r, sky_draw(s, view, proj) == SKY_OK ? frame_worst(ctx) : INFINITY);
            }
    glViewport(0, 0, ctx->width, ctx->height);
    /* refused, not drawn: near = far, and a view matrix with no rotation */
    float view[16], proj[16];
    sky_cli_camera_at(0.0, 0.0, 60.0, ctx->width, ctx->height, view, proj);
    float flat[16];
    memcpy(flat, view, sizeof flat);
    for (int i = 0; i < 3; i++) flat[i * 4 + 1] = flat[i * 4 + 0]; /* two equal axes */
    float same_planes[16];
    memcpy(same_planes, proj, sizeof same_planes);
    same_planes[10] = 0.0f; /* (far + near) / (near - far) with near = far, after the 0/0 is caught */
    same_planes[14] = 0.0f;
    keep_worst(r, sky_draw(s, flat, proj) == SKY_OK ? frame_worst(ctx) : 0.0);
    keep_worst(r, sky_draw(s, view, same_planes) == SKY_OK ? frame_worst(ctx) : 0.0);
    finish(r);
}

/* ---- the atmosphere's stiff cases ------------------------------------------------------------- */

/* Exact Chapman integral (in scale heights) by Simpson's rule on
 * t = e^v - 1: dense near the observer, out to 1e5 scale heights. */
static double chapman_exact(double X, double mu)
{
    const int n = 20000;
    double vmax = log(1.0 + 1e5), h = vmax / n, sum = 0.0;
    for (int i = 0; i <= n; i++) {
        double v = i * h, t = exp(v) - 1.0;
        double r = sqrt(X * X + t * t + 2.0 * X * t * mu);
        double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        sum += w * exp(-(r - X)) * exp(v);
    }
    return sum * h / 3.0;
}

/* The closed-form air mass the analytic path and the night layers' extinction
 * use: against the exact integral above the horizon and just below it,
 * then finite, positive and non-decreasing down to the nadir. */
static void case_chapman(suite *st)
{
    sky_stability_row *r = add_row(st, "Chapman air mass, X 300..5300, mu 1..-1",
                                   "relative error (mu >= -0.03); finite, rising as the sun sinks", "", 0.01);
    static const double Xs[] = {300.0, 795.0, 5300.0};
    static const double mus[] = {1.0, 0.7, 0.4, 0.2, 0.1, 0.05, 0.02, 0.01, 0.0, -0.01, -0.03};
    for (size_t i = 0; i < sizeof Xs / sizeof Xs[0]; i++) {
        for (size_t j = 0; j < sizeof mus / sizeof mus[0]; j++, r->samples++)
            keep_worst(r, fabs(sky_chapman(Xs[i], mus[j]) / chapman_exact(Xs[i], mus[j]) - 1.0));
        double prev = sky_chapman(Xs[i], 0.0);
        for (int k = 1; k <= 900; k++, r->samples++) {
            double c = sky_chapman(Xs[i], -sin(k * 0.1 * SKY_PI / 180.0));
            if (!isfinite(c) || c <= 0.0 || c < prev) keep_worst(r, INFINITY);
            prev = c;
        }
    }
    finish(r);
}

/* An Earth whose scatterers are scaled by k (each coefficient held at the
 * description's limit, 10/km) and whose Mie asymmetry is g. */
static sky_atmosphere_params scaled_earth(double k, float g)
{
    sky_atmosphere_params a;
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &a);
    for (int c = 0; c < 3; c++) {
        a.rayleigh_scattering[c] = (float)fmin(a.rayleigh_scattering[c] * k, 10.0);
        a.mie_scattering[c] = (float)fmin(a.mie_scattering[c] * k, 10.0);
        a.mie_extinction[c] = (float)fmin(a.mie_extinction[c] * k, 10.0);
        a.ozone_absorption[c] = (float)fmin(a.ozone_absorption[c] * k, 10.0);
    }
    a.mie_g = g;
    return a;
}

/* The reference's transmittance on grazing paths whose optical depth
 * passes 100: in 0..1 and falling as the ray lowers (a longer path),
 * however thick the air. */
static void case_grazing_transmittance(suite *st)
{
    sky_stability_row *r = add_row(st, "grazing paths, densities x1e-3..x1e3 (tau > 100)",
                                   "transmittance in 0..1; largest rise as the ray lowers (rounding: 1e-12)", "", 1e-12);
    static const double scales[] = {1e-3, 1.0, 1e3};
    static const double altitudes[] = {0.0, 0.001, 8.0, 100.0, 150.0};
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; i++) {
        sky_atmosphere_params a = scaled_earth(scales[i], 0.8f);
        for (size_t j = 0; j < sizeof altitudes / sizeof altitudes[0]; j++) {
            double prev[SKY_REF_WAVELENGTHS];
            for (int k = 0; k <= 90; k++, r->samples++) {
                /* elevation 90 .. -2 degrees, finest near the horizon */
                double e = (90.0 - 92.0 * pow(k / 90.0, 0.5)) * SKY_PI / 180.0, d[3] = {cos(e), sin(e), 0.0}, t[SKY_REF_WAVELENGTHS];
                sky_ref_transmittance(&a, altitudes[j], d, t);
                for (int w = 0; w < SKY_REF_WAVELENGTHS; w++) {
                    if (!(t[w] >= 0.0 && t[w] <= 1.0)) keep_worst(r, INFINITY);
                    if (k > 0) keep_worst(r, t[w] - prev[w]);
                    prev[w] = t[w];
                }
            }
        }
    }
    finish(r);
}

/* Hillaire's tables for stiff atmospheres: thin and 1000 times thick air,
 * Mie g at +-0.999, the sun from the zenith to the nadir. Every table
 * value finite and >= 0, transmittance <= 1, and the sky's irradiance on
 * the ground no more than the sun supplies (per unit solar illuminance,
 * at most 1 + the ground's bounce, 1 / (1 - albedo)). */
static void case_stiff_tables(suite *st)
{
    sky_stability_row *r = add_row(st, "Hillaire tables: densities x1e-3..x1e3, g +-0.999",
                                   "finite, >= 0, T <= 1; sky irradiance over what the sun gives", "", 1.0 / 0.7);
    static const double scales[] = {1e-3, 1.0, 1e3};
    static const float gs[] = {-0.999f, 0.0f, 0.999f};
    sky_lut_settings small = {64, 16, 20, 16, 32, 10, 48, 28, 15};
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; i++)
        for (size_t j = 0; j < sizeof gs / sizeof gs[0]; j++) {
            sky_atmosphere_params a = scaled_earth(scales[i], gs[j]);
            sky_hillaire_tables t;
            if (sky_hillaire_init(&t, &a, &small, NULL, 0)) {
                keep_worst(r, INFINITY);
                continue;
            }
            sky_hillaire_build_transmittance(&t);
            if (sky_hillaire_build_multiscatter(&t)) keep_worst(r, INFINITY);
            for (int k = 0; k < 64 * 16 * 3; k++)
                if (!(t.transmittance[k] >= 0.0f && t.transmittance[k] <= 1.0f)) keep_worst(r, INFINITY);
            for (int k = 0; k < 16 * 16 * 3; k++)
                if (!(t.multiscatter[k] >= 0.0f) || !isfinite(t.multiscatter[k])) keep_worst(r, INFINITY);
            for (int e = 90; e >= -90; e -= 30) {
                double mu = sin(e * SKY_PI / 180.0), sun[3] = {sqrt(1.0 - mu * mu), mu, 0.0};
                sky_hillaire_build_skyview(&t, 0.0, mu);
                for (int k = 0; k < 48 * 28 * 3; k++)
                    if (!(t.skyview[k] >= 0.0f) || !isfinite(t.skyview[k])) keep_worst(r, INFINITY);
                /* irradiance on the ground: 2 pi int L mu dmu (8 rings x
                 * 16 azimuths), over the sun's own (1 at normal incidence) */
                double irradiance = 0.0;
                for (int ring = 0; ring < 8; ring++) {
                    double vm = (ring + 0.5) / 8.0, c = sqrt(1.0 - vm * vm);
                    for (int az = 0; az < 16; az++) {
                        double phi = 2.0 * SKY_PI * (az + 0.5) / 16.0, v[3] = {c * cos(phi), vm, c * sin(phi)}, rgb[3];
                        sky_hillaire_sky(&t, v, sun, rgb);
                        irradiance += 2.0 * SKY_PI * vm * (1.0 / 8.0) * (1.0 / 16.0) * rgb[1];
                    }
                }
                keep_worst(r, irradiance);
                r->samples++;
            }
            sky_hillaire_free(&t);
        }
    finish(r);
}

/* Preetham outside its fit: turbidity 1..64 (clamped into 2..10) and the
 * sun 0.01 degree above and below the horizon: the CPU twin of the shader
 * finite, >= 0, and changing by no more than the fit's own slope there
 * plus the twilight scale: at T 10 the zenith luminance of eq. A.2 starts
 * from 0.26 kcd/m^2 at a horizon sun and grows 1.7 % in the first 0.01
 * degree; the measured twilight below falls a decade per 2.7 degrees at
 * the horizon, 0.86 % per 0.01, and the ease above it (preetham.c) climbs
 * at the same rate: 3.4 % in all, held at 4 %. */
static void case_preetham_fit(suite *st)
{
    sky_stability_row *r = add_row(st, "Preetham: turbidity 1..64, sun +-0.01 deg at the horizon",
                                   "finite, >= 0; largest relative change of luminance per 0.01 deg", "", 0.04);
    static const float turbidities[] = {1.0f, 2.0f, 10.0f, 64.0f};
    static sky_core fake; /* the frame fields preetham.c reads, without GL */
    for (size_t i = 0; i < sizeof turbidities / sizeof turbidities[0]; i++) {
        double before[16];
        for (int side = 0; side < 2; side++) {
            double alt = (side ? -0.01 : 0.01) * SKY_PI / 180.0;
            memset(&fake, 0, sizeof fake);
            fake.cfg.turbidity = turbidities[i];
            fake.frame.sun_altitude = (float)alt;
            fake.frame.sun_dir[0] = (float)cos(alt), fake.frame.sun_dir[1] = (float)sin(alt);
            sky_preetham_frame(&fake);
            for (int k = 0; k < 16; k++, r->samples++) {
                double e = (k / 4) * 20.0 * SKY_PI / 180.0 + 0.001, az = (k % 4) * SKY_PI / 2.0, rgb[3];
                double d[3] = {cos(e) * cos(az), sin(e), cos(e) * sin(az)};
                sky_preetham_eval(&fake.frame, d, rgb);
                for (int c = 0; c < 3; c++)
                    if (!(rgb[c] >= 0.0) || !isfinite(rgb[c])) keep_worst(r, INFINITY);
                /* luminance: a channel clipped at 0 out of the sRGB gamut
                 * (blue beside a yellow horizon sun) has no relative change */
                double y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
                if (side) keep_worst(r, fabs(y - before[k]) / fmax(before[k], 1e-12));
                else before[k] = y;
            }
        }
    }
    finish(r);
}

/* The render cases on a context of profile gl. */
static int run_render(suite *st, sky_gl_profile gl, char *err, size_t err_len)
{
    sky_osmesa ctx;
    sky *s = open_sky(&ctx, gl, err, err_len);
    if (!s) return -1;
    case_slider_corners(st, s, &ctx);
    case_sun_at_horizon(st, s, &ctx);
    case_long_elapsed(st, s, &ctx);
    case_huge_steps(st, s, &ctx);
    case_sunset_light(st, s);
    case_camera_extremes(st, s, &ctx);
    case_star_extremes(st, s, &ctx);
    sky_destroy(s);
    sky_osmesa_destroy(&ctx);
    return st->count;
}

int sky_stability_run_render(sky_gl_profile gl, sky_stability_row rows[SKY_STABILITY_MAX_ROWS], char *err,
                             size_t err_len)
{
    suite st = {rows, 0, {0}};
    return run_render(&st, gl, err, err_len);
}

int sky_stability_run(int gpu, sky_stability_row rows[SKY_STABILITY_MAX_ROWS], char *err, size_t err_len)
{
    suite st = {rows, 0, {0}};
    case_poles(&st);
    case_date_range(&st);
    case_sun_continuity(&st);
    case_new_and_full_moon(&st);
    case_eclipse_edges(&st);
    case_solar_eclipse_contacts(&st);
    case_star_colour(&st);
    case_sun_transmittance(&st);
    case_chapman(&st);
    case_grazing_transmittance(&st);
    case_stiff_tables(&st);
    case_preetham_fit(&st);
    return gpu ? run_render(&st, SKY_GL_AUTO, err, err_len) : st.count;
}

long sky_rss_kib(void)
{
#ifdef _WIN32
    return -1; /* (Linux's /proc only) */
#else
    long pages = -1, resident = -1;
    FILE *f = fopen("/proc/self/statm", "r");
    if (!f) return -1;
    if (fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = -1;
    fclose(f);
    return resident < 0 ? -1 : resident * (sysconf(_SC_PAGESIZE) / 1024);
#endif
}
