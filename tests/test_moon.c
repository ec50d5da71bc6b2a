/*
 * Moon tests (Mueller sec. 2-3): phase and bright limb measured on the
 * rendered disc against the astronomy, earthshine, lunar eclipses, the
 * rising moon flattened by refraction, and the moon left out below the
 * horizon or out of the scene.
 */
#include "test.h"
#include "sky_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)

typedef struct closeup {
    image im;
    double cx, cy, radius_px; /* the disc in the image */
    sky_astronomy a;
} closeup;

/* Renders the moon centred and magnified: a 256x256 view whose field is
 * three drawn disc diameters. */
static int moon_closeup(const sky_observer *o, unsigned features, float moon_scale, int hdr, closeup *c)
{
    memset(c, 0, sizeof *c);
    if (sky_compute_astronomy(o, 0.0f, NULL, 0, NULL, &c->a, NULL, 0) != SKY_OK) return -1;
    scene sc = scene_default();
    sc.cfg.features = features;
    sc.cfg.moon_scale = moon_scale;
    sc.params.cover = 0.0f;
    sc.w = sc.h = 256;
    sc.yaw = c->a.moon.az_deg;
    sc.pitch = c->a.moon.alt_deg;
    sc.has_observer = 1;
    sc.observer = *o;
    double disc = tan(moon_scale * asin(1737.4 / c->a.moon.distance_km)); /* tangent-plane radius */
    sc.fov = 2.0 * atan(3.0 * disc) / DEG;
    c->cx = c->cy = 128.0;
    c->radius_px = disc / tan(sc.fov * DEG / 2) * 128.0;
    return render_scene(&sc, hdr, SKY_GL_AUTO, &c->im);
}

/* Lit fraction of the disc and the direction (image angle from up,
 * counter-clockwise) of the lit part's centroid. */
static double lit_fraction(const closeup *c, double *limb_angle)
{
    double peak = 0;
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++)
            if (hypot(x + 0.5 - c->cx, y + 0.5 - c->cy) < 0.95 * c->radius_px) peak = fmax(peak, image_luminance(&c->im, x, y));
    int disc = 0, lit = 0;
    double sx = 0, sy = 0;
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++) {
            double dx = x + 0.5 - c->cx, dy = y + 0.5 - c->cy;
            if (hypot(dx, dy) >= c->radius_px) continue;
            disc++;
            if (image_luminance(&c->im, x, y) > 0.04 * peak) lit++, sx += dx, sy += dy;
        }
    /* image y grows downward: up is -y; counter-clockwise from up is toward -x */
    *limb_angle = atan2(-sx, -sy);
    return disc ? (double)lit / disc : 0.0;
}

TEST(moon_phase_and_bright_limb)
{
    const struct {
        const char *name;
        int y, m, d, hh, mm;
        double lat, lon;
    } cases[4] = {
        {"first quarter 2024-06-14", 2024, 6, 14, 20, 0, 45.0, 10.0},
        {"waning gibbous 2024-06-25", 2024, 6, 25, 2, 0, 45.0, 10.0},
        {"full 2024-06-22", 2024, 6, 22, 0, 0, -30.0, 20.0},
        {"crescent 2024-06-10", 2024, 6, 10, 21, 0, 40.0, 0.0},
    };
    for (int i = 0; i < 4; i++) {
        sky_observer o = {sky_julian_day(cases[i].y, cases[i].m, cases[i].d, cases[i].hh, cases[i].mm, 0.0), cases[i].lat,
                          cases[i].lon, 0.0, 0};
        closeup c;
        if (moon_closeup(&o, SKY_MOON, 1.0f, 1, &c)) {
            CHECK(0, "%s: render failed", cases[i].name);
            continue;
        }
        CHECK(c.a.moon.alt_deg > 5.0, "%s: moon up (%.1f)", cases[i].name, c.a.moon.alt_deg);
        double limb, k = lit_fraction(&c, &limb);
        /* the image's up is the zenith: position angles are measured from
         * north, which lies the parallactic angle clockwise from up */
        double expect = (c.a.moon_bright_limb_deg - c.a.moon_parallactic_deg) * DEG;
        double dlimb = fabs(remainder(limb - expect, 2 * 3.14159265358979323846)) / DEG;
        NOTE("%s: lit fraction %.3f (astro %.3f); bright limb %.1f deg from up (astro %.1f): %.1f deg off", cases[i].name,
             k, c.a.moon_illuminated_fraction, limb / DEG, remainder(expect, 2 * 3.14159265358979323846) / DEG, dlimb);
        CHECK(fabs(k - c.a.moon_illuminated_fraction) <= 0.03, "%s: lit fraction %.3f vs %.3f", cases[i].name, k,
              c.a.moon_illuminated_fraction);
        if (c.a.moon_illuminated_fraction < 0.97) /* at full the limb has no direction */
            CHECK(dlimb <= 5.0, "%s: bright limb %.1f deg off", cases[i].name, dlimb);
        image_free(&c.im);
    }
}

TEST(moon_earthshine_on_a_crescent)
{
    /* a two-day crescent in deep twilight */
    sky_observer o = {sky_julian_day(2024, 6, 8, 20, 30, 0.0), 45.0, 10.0, 0.0, 0};
    closeup c;
    if (moon_closeup(&o, SKY_MOON, 2.5f, 1, &c)) {
        CHECK(0, "render failed");
        return;
    }
    double limb, k = lit_fraction(&c, &limb);
    /* dark side: disc pixels on the side away from the bright limb */
    double dark = 0, sky_l = 0;
    int nd = 0, ns = 0;
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++) {
            double dx = x + 0.5 - c.cx, dy = y + 0.5 - c.cy, r = hypot(dx, dy);
            double toward_limb = (-sin(limb) * dx - cos(limb) * dy) / (r > 0 ? r : 1);
            if (r < 0.8 * c.radius_px && toward_limb < -0.3) dark += image_luminance(&c.im, x, y), nd++;
            if (r > 1.35 * c.radius_px * 4.0 / 1.5 && x > 2 && y > 2) sky_l += image_luminance(&c.im, x, y), ns++;
        }
    dark /= nd ? nd : 1;
    sky_l /= ns ? ns : 1;
    NOTE("crescent %.3f lit: dark side %.3g kcd/m^2 (earthshine), sky %.3g kcd/m^2", k, dark, sky_l);
    CHECK(k < 0.15 && nd > 100, "a thin crescent (%.3f lit)", k);
    CHECK(dark > 2.0 * sky_l, "earthshine makes the dark side brighter than the sky (%.3g vs %.3g)", dark, sky_l);
    image_free(&c.im);
}

static double disc_mean(const closeup *c, double rgb[3])
{
    double sum = 0;
    int n = 0;
    rgb[0] = rgb[1] = rgb[2] = 0;
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++)
            if (hypot(x + 0.5 - c->cx, y + 0.5 - c->cy) < 0.9 * c->radius_px) {
                const float *p = c->im.px + 3 * (y * 256 + x);
                for (int k = 0; k < 3; k++) rgb[k] += p[k];
                sum += image_luminance(&c->im, x, y);
                n++;
            }
    for (int k = 0; k < 3; k++) rgb[k] /= n ? n : 1;
    return n ? sum / n : 0.0;
}

TEST(moon_total_eclipse_is_dark_and_red)
{
    /* greatest eclipse of 2011-06-15 (20:12:37 TD), seen from where the
     * moon stands high (Madagascar region) */
    double jd = sky_julian_day(2011, 6, 15, 20, 12, 37.0);
    sky_observer o = {jd - sky_delta_t(jd) / 86400.0, -20.0, 57.0, 0.0, 0};
    closeup ecl, plain;
    if (moon_closeup(&o, SKY_MOON | SKY_ECLIPSE, 2.5f, 1, &ecl) || moon_closeup(&o, SKY_MOON, 2.5f, 1, &plain)) {
        CHECK(0, "render failed");
        return;
    }
    double rgb[3], rgb_plain[3];
    double l_ecl = disc_mean(&ecl, rgb), l_full = disc_mean(&plain, rgb_plain);
    NOTE("2011-06-15 at greatest eclipse: disc %.3g kcd/m^2 vs %.3g uneclipsed (x%.2g); rgb %.3g %.3g %.3g", l_ecl,
         l_full, l_ecl / l_full, rgb[0], rgb[1], rgb[2]);
    CHECK(ecl.a.umbral_magnitude > 1.6, "total (%.3f)", ecl.a.umbral_magnitude);
    CHECK(l_ecl < 0.01 * l_full, "the eclipsed disc is far darker than the full moon");
    CHECK(rgb[0] > 2.0 * rgb[1] && rgb[0] > 2.0 * rgb[2], "red dominates the eclipsed moon");
    image_free(&ecl.im);
    image_free(&plain.im);
}

TEST(moon_penumbral_eclipse_is_slightly_darker)
{
    /* the penumbral eclipse of 2020-01-10, greatest at 19:10 UT */
    sky_observer o = {sky_julian_day(2020, 1, 10, 19, 10, 0.0), 20.0, 80.0, 0.0, 0};
    closeup ecl, plain;
    if (moon_closeup(&o, SKY_MOON | SKY_ECLIPSE, 2.5f, 1, &ecl) || moon_closeup(&o, SKY_MOON, 2.5f, 1, &plain)) {
        CHECK(0, "render failed");
        return;
    }
    double rgb[3];
    double ratio = disc_mean(&ecl, rgb) / disc_mean(&plain, rgb);
    NOTE("penumbral 2020-01-10 (penumbral magnitude %.3f): disc at %.2f of its uneclipsed brightness",
         ecl.a.penumbral_magnitude, ratio);
    CHECK(ratio > 0.4 && ratio < 0.97, "a penumbral eclipse only dims the moon somewhat (%.2f)", ratio);
    image_free(&ecl.im);
    image_free(&plain.im);
}

TEST(moon_left_out_when_not_needed)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_MOON | SKY_CLOUDS;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "fixture");
        return;
    }
    sky_stats with;
    sky_layer_stats moon_with;
    sky_get_stats(f.s, &with);
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_MOON, &moon_with) == SKY_OK, "the moon's row");
    /* moon below the horizon: no draw */
    sky_observer below = {sky_julian_day(2024, 6, 22, 12, 0, 0.0), 45.0, 10.0, 0.0, 0}; /* full moon, local noon */
    sky_astronomy a;
    sky_compute_astronomy(&below, 0.0f, NULL, 0, NULL, &a, NULL, 0);
    CHECK(a.moon.alt_deg < -10.0, "the full moon is down at noon (%.1f)", a.moon.alt_deg);
    sky_set_observer(f.s, &below);
    sky_draw_fisheye(f.s);
    sky_layer_stats moon;
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_MOON, &moon) == SKY_OK && moon.enabled && moon.draws == 0,
          "no moon draw when it is down");
    sky_observer up = below;
    up.julian_day_utc = sky_julian_day(2024, 6, 22, 0, 0, 0.0);
    sky_set_observer(f.s, &up);
    sky_draw_fisheye(f.s);
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_MOON, &moon) == SKY_OK && moon.draws == 1, "one moon draw when it is up");
    fixture_close(&f);
    /* a scene without the moon has no moon texture */
    cfg.features = SKY_CLOUDS;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg) == 0) {
        sky_stats without;
        sky_get_stats(f.s, &without);
        NOTE("GPU bytes with the moon %zu, without %zu (moon layer %zu)", with.gpu_bytes, without.gpu_bytes,
             moon_with.bytes);
        CHECK(with.gpu_bytes - without.gpu_bytes == moon_with.bytes && moon_with.bytes >= 256 * 128 * 4,
              "leaving the moon out saves exactly its texture and buffer");
        CHECK(without.textures == with.textures - 1, "one texture fewer");
        fixture_close(&f);
    }
    /* an eclipse without a moon is a configuration error */
    char err[256];
    sky_osmesa ctx;
    if (sky_osmesa_create(&ctx, 16, 16, SKY_GL_AUTO, 0, err, sizeof err) == 0) {
        cfg.features = SKY_ECLIPSE;
        cfg.get_proc_address = sky_osmesa_loader();
        CHECK(sky_create(&cfg, err, sizeof err) == NULL && strstr(err, "SKY_MOON"), "SKY_ECLIPSE alone: %s", err);
        sky_osmesa_destroy(&ctx);
    }
}

TEST(moon_rising_is_flattened)
{
    /* The full moon rising on 2024-06-21 at 45 N 10 E: the instant its
     * centre stands 0.55 degree up (apparent), found by bisection */
    sky_observer o = {0.0, 45.0, 10.0, 0.0, 0};
    double lo = sky_julian_day(2024, 6, 21, 19, 0, 0.0), hi = sky_julian_day(2024, 6, 21, 20, 0, 0.0);
    sky_astronomy a;
    for (int i = 0; i < 40; i++) {
        o.julian_day_utc = 0.5 * (lo + hi);
        if (sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) != SKY_OK) {
            CHECK(0, "astronomy failed");
            return;
        }
        if (a.moon.alt_deg < 0.55) lo = o.julian_day_utc;
        else hi = o.julian_day_utc;
    }
    /* the moon alone: a render with it less one without it (the twilight
     * sky cancels), at its true size, a 1.5-degree field */
    scene sc = scene_default();
    sc.cfg.features = SKY_MOON;
    sc.cfg.moon_scale = 1.0f;
    sc.params.cover = 0.0f;
    sc.w = sc.h = 256;
    sc.yaw = a.moon.az_deg;
    sc.pitch = a.moon.alt_deg;
    sc.fov = 1.5;
    sc.has_observer = 1;
    sc.observer = o;
    scene bare = sc;
    bare.cfg.features = 0;
    image with, without;
    if (render_scene(&sc, 1, SKY_GL_AUTO, &with) || render_scene(&bare, 1, SKY_GL_AUTO, &without)) {
        CHECK(0, "render failed");
        return;
    }
    const int c = 128; /* the centre falls on the corner of four pixels */
#define MOON_PX(x, y) (image_luminance(&with, (x), (y)) - image_luminance(&without, (x), (y)))
    double centre = 0.25 * (MOON_PX(c - 1, c - 1) + MOON_PX(c, c - 1) + MOON_PX(c - 1, c) + MOON_PX(c, c));
    double edge = 0.2 * centre;
    int up = 0, down = 0, left = 0, right = 0;
    while (up < c && MOON_PX(c, c - 1 - up) > edge) up++;
    while (down < c && MOON_PX(c, c + down) > edge) down++;
    while (left < c && MOON_PX(c - 1 - left, c) > edge) left++;
    while (right < c && MOON_PX(c + right, c) > edge) right++;
#undef MOON_PX
    /* the prediction: each limb lifted by the refraction at its own true
     * altitude (astro.c's formula at sea level) */
    sky_astro as;
    sky_astro_observer ao = {45.0 * DEG, 10.0 * DEG, 0.0};
    sky_astro_compute(o.julian_day_utc, &ao, &as, NULL, 0);
    double r = as.moon_topo_semidiameter, ht = as.moon.alt_geometric, pf = as.pressure_factor;
    double top = ht + r + sky_refraction(ht + r, pf), bottom = ht - r + sky_refraction(ht - r, pf);
    double measured = (up + down) / (double)(left + right), expected = (top - bottom) / (2.0 * r);
    NOTE("moon centre %.2f deg apparent (%.2f true), %d/%d px up/down, %d/%d left/right: height/width %.3f, "
         "predicted %.3f", a.moon.alt_deg, ht / DEG, up, down, left, right, measured, expected);
    CHECK(fabs(measured - expected) <= 0.05 && expected < 0.95, "moon flattening %.3f, predicted %.3f", measured,
          expected);
    image_free(&with);
    image_free(&without);
}

TEST(moon_hides_the_stars_behind_it)
{
    /* A crescent at the end of twilight (2024-06-08 21:30 UT, 45 N 10 E,
     * the sun 17.6 degrees down), where the disc only adds light: HIP
     * 35253 (V 6.38) stands behind its dark side, 0.4 of its drawn radius
     * from the centre, and stars of V 5.75 around it. With the catalogue
     * on, nothing may change inside the disc, while stars still show
     * around it; without the moon, that star shows there (within the
     * naked eye's limit, which the moonless sky raises a little). */
    sky_observer o = {sky_julian_day(2024, 6, 8, 21, 30, 0.0), 45.0, 10.0, 0.0, 0};
    closeup with, without, stars_only, none;
    if (moon_closeup(&o, SKY_MOON | SKY_STARS, 2.5f, 1, &with) || moon_closeup(&o, SKY_MOON, 2.5f, 1, &without) ||
        moon_closeup(&o, SKY_STARS, 2.5f, 1, &stars_only) || moon_closeup(&o, SKY_FEATURES_NONE, 2.5f, 1, &none)) {
        CHECK(0, "render failed");
        return;
    }
    double inside = 0.0, outside = 0.0, unhidden = 0.0;
    for (int y = 0; y < 256; y++)
        for (int x = 0; x < 256; x++) {
            double r = hypot(x + 0.5 - with.cx, y + 0.5 - with.cy) / with.radius_px;
            double added = image_luminance(&with.im, x, y) - image_luminance(&without.im, x, y);
            double bare = image_luminance(&stars_only.im, x, y) - image_luminance(&none.im, x, y);
            if (r < 0.97) {
                inside = fmax(inside, added);
                unhidden = fmax(unhidden, bare);
            } else if (r > 1.1) {
                outside = fmax(outside, added);
            }
        }
    NOTE("largest luminance the stars add: %.3g kcd/m^2 on the disc, %.3g around it; %.3g there without the moon",
         inside, outside, unhidden);
    CHECK(inside <= 1e-9, "a star shows through the moon (%.3g kcd/m^2)", inside);
    CHECK(outside > 1e-6, "no star around the moon either (%.3g): the test sees nothing", outside);
    CHECK(unhidden > 1e-9, "no star behind the disc to hide (%.3g): the test proves nothing", unhidden);
    image_free(&with.im);
    image_free(&without.im);
    image_free(&stars_only.im);
    image_free(&none.im);
}

/* ---- photometry: the drawn disc against the moonlight ---------------------- */

/* Illuminance, klx (luminance-weighted), a closeup's layer adds: each
 * pixel's luminance minus the same view's without the moon (clouds at
 * cover 0: the same dome), times the pixel's solid angle. On a perspective
 * image plane at distance 1 a pixel is s = 2 tan(fov / 2) / h wide and
 * subtends s^2 cos^3 of its angle off the axis. */
static double closeup_flux(const closeup *with, const closeup *without, double fov_deg)
{
    int w = with->im.w, h = with->im.h;
    double s = 2.0 * tan(fov_deg * DEG / 2.0) / h, sum = 0.0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double u = (x + 0.5 - w / 2.0) * s, v = (y + 0.5 - h / 2.0) * s;
            double omega = s * s / pow(1.0 + u * u + v * v, 1.5);
            sum += (image_luminance(&with->im, x, y) - image_luminance(&without->im, x, y)) * omega;
        }
    return sum;
}

/* The moonlight sky_get_lighting reports for the closeup's sky, klx of
 * luminance (0.2126 R + 0.7152 G + 0.0722 B). */
static double moonlight(const sky_observer *o, float moon_scale)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_MOON;
    cfg.moon_scale = moon_scale;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) return -1.0;
    sky_params p = sky_default_params();
    p.cover = 0.0f;
    sky_lighting l;
    memset(&l, 0, sizeof l);
    if (sky_set_params(f.s, &p) < 0 || sky_set_observer(f.s, o) != SKY_OK || sky_get_lighting(f.s, &l) != SKY_OK)
        l.moon_color[0] = l.moon_color[1] = l.moon_color[2] = -1.0f;
    fixture_close(&f);
    return 0.2126 * l.moon_color[0] + 0.7152 * l.moon_color[1] + 0.0722 * l.moon_color[2];
}

/* The drawn disc's flux and the moonlight for one observer and scale. */
static int disc_and_light(const sky_observer *o, float moon_scale, double *disc, double *light, sky_astronomy *a)
{
    closeup with, without;
    if (moon_closeup(o, SKY_MOON, moon_scale, 1, &with)) return -1;
    if (moon_closeup(o, SKY_CLOUDS, moon_scale, 1, &without)) {
        image_free(&with.im);
        return -1;
    }
    /* the closeup's field: three drawn disc radii either side */
    double r = tan(moon_scale * asin(1737.4 / with.a.moon.distance_km));
    *disc = closeup_flux(&with, &without, 2.0 * atan(3.0 * r) / DEG);
    *light = moonlight(o, moon_scale);
    *a = with.a;
    image_free(&with.im);
    image_free(&without.im);
    return 0;
}

/* Krisciunas & Schaefer (1991) eq. 8: the moon's brightness relative to
 * full at phase angle a (degrees). */
static double ks_phase(double a) { return pow(10.0, -0.4 * (0.026 * fabs(a) + 4e-9 * a * a * a * a)); }

TEST(moon_disc_sums_to_moonlight)
{
    /* the perigee and apogee full moons of 2024-10-17 and 2025-04-13 high
     * in a dark sky, then the phases of test_moon_phase_and_bright_limb */
    const struct {
        const char *name;
        sky_observer o;
    } cases[] = {
        {"full at perigee 2024-10-17", {sky_julian_day(2024, 10, 17, 0, 0, 0.0), 10.0, 0.0, 0.0, 0}},
        {"full at apogee 2025-04-13", {sky_julian_day(2025, 4, 13, 0, 0, 0.0), -10.0, 0.0, 0.0, 0}},
        {"waning gibbous 2024-06-25", {sky_julian_day(2024, 6, 25, 2, 0, 0.0), 45.0, 10.0, 0.0, 0}},
        {"first quarter 2024-06-14", {sky_julian_day(2024, 6, 14, 20, 0, 0.0), 45.0, 10.0, 0.0, 0}},
        {"crescent 2024-06-10", {sky_julian_day(2024, 6, 10, 21, 0, 0.0), 40.0, 0.0, 0.0, 0}},
    };
    double per_ks[2] = {0, 0}, dist[2] = {0, 0};
    for (int i = 0; i < (int)(sizeof cases / sizeof cases[0]); i++) {
        double disc, light;
        sky_astronomy a;
        if (disc_and_light(&cases[i].o, 1.0f, &disc, &light, &a)) {
            CHECK(0, "%s: render failed", cases[i].name);
            continue;
        }
        NOTE("%s: phase %.1f deg, %.0f km, alt %.1f: disc %.4g lx, moonlight %.4g lx (%+.1f %%)", cases[i].name,
             a.moon_phase_angle_deg, a.moon.distance_km, a.moon.alt_deg, disc * 1e3, light * 1e3,
             100.0 * (disc / light - 1.0));
        CHECK(light > 0.0 && fabs(disc / light - 1.0) <= 0.05, "%s: the true-size disc sums to %.4g lx, moonlight %.4g lx",
              cases[i].name, disc * 1e3, light * 1e3);
        if (i < 2) per_ks[i] = light / ks_phase(a.moon_phase_angle_deg), dist[i] = a.moon.distance_km;
    }
    /* both high (79 and 89 degrees: extinction within 0.5 %), the phase
     * law divided out: what is left is 1 / r^2, +29 % from apogee to
     * perigee (topocentric and geocentric phase angles differ by up to a
     * degree near full: 2.4 % in the law) */
    double expect = (dist[1] / dist[0]) * (dist[1] / dist[0]);
    NOTE("perigee / apogee moonlight, phase law divided out: %.3f (1 / r^2: %.3f)", per_ks[0] / per_ks[1], expect);
    CHECK(per_ks[1] > 0.0 && fabs(per_ks[0] / per_ks[1] / expect - 1.0) <= 0.04, "perigee / apogee %.3f vs %.3f",
          per_ks[0] / per_ks[1], expect);
    /* the published full moon: about 0.24-0.27 lx at the zenith, 0.32 lx
     * above the air (K&S's -12.73 mag); the apogee moon stands at 89 deg */
    CHECK(per_ks[1] * 1e3 > 0.21 && per_ks[1] * 1e3 < 0.29, "the high apogee full moon gives %.3f lx",
          per_ks[1] * 1e3);
}

TEST(moon_scale_keeps_luminance)
{
    /* moon_scale draws a bigger moon of the same surface brightness (a
     * telephoto view), so its disc carries scale^2 times the flux, while
     * the host's moonlight stays the true moon's */
    sky_observer o = {sky_julian_day(2024, 10, 17, 0, 0, 0.0), 10.0, 0.0, 0.0, 0};
    double disc1, light1, disc25, light25;
    sky_astronomy a;
    if (disc_and_light(&o, 1.0f, &disc1, &light1, &a) || disc_and_light(&o, 2.5f, &disc25, &light25, &a)) {
        CHECK(0, "render failed");
        return;
    }
    NOTE("moon_scale 2.5: disc %.4g lx (%.3f x the true-size disc), moonlight %.4g lx (scale 1: %.4g)", disc25 * 1e3,
         disc25 / disc1, light25 * 1e3, light1 * 1e3);
    CHECK(light25 == light1, "the moonlight does not depend on moon_scale (%.5g vs %.5g lx)", light25 * 1e3, light1 * 1e3);
    CHECK(fabs(disc25 / disc1 / 6.25 - 1.0) <= 0.05, "the 2.5x disc carries %.3f x the flux (6.25 expected)",
          disc25 / disc1);
}
