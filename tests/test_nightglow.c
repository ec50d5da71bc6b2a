/*
 * The night's own light (Night sky II): airglow, zodiacal light and light
 * pollution. The zenith's brightness at a dark site and under each Bortle
 * class, the zodiacal light against Leinert et al.'s table, the CPU twin
 * (sky_atmosphere_radiance, which the lighting queries use) against the
 * rendered dome, and what the layers cost.
 */
#include "test.h"
#include "catalog.h"
#include "cli.h"
#include "sky_internal.h"
#include "atmosphere/atmosphere.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)

/* 2024-06-14 23:50 UTC at 45 N 10 E: local sidereal time 18 h, so the
 * zenith is 22 degrees from the north ecliptic pole (the zodiacal light
 * at its faintest there), the sun 21 degrees down; no moon in the scene. */
static sky_observer dark_site(void)
{
    sky_observer o = {sky_julian_day(2024, 6, 14, 23, 50, 0.0), 45.0, 10.0, 0.0, 0};
    return o;
}

/* The zenith's luminance (kcd/m^2) of an HDR render looking straight up. */
static double zenith_luminance(unsigned features, float bortle, float activity, const sky_observer *o)
{
    scene sc = scene_default();
    sc.cfg.features = features;
    sc.cfg.bortle = bortle;
    sc.cfg.solar_activity_manual = 1;
    sc.cfg.solar_activity = activity;
    sc.params.cover = 0.0f;
    sc.has_observer = 1;
    sc.observer = *o;
    sc.w = sc.h = 32;
    sc.fov = 5.0;
    sc.pitch = 90.0;
    image im;
    if (render_scene(&sc, 1, SKY_GL_AUTO, &im)) return -1.0;
    double l = image_luminance(&im, 16, 16);
    image_free(&im);
    return l;
}

/* Issue: "Night zenith brightness with airglow and zodiacal light at a
 * dark site: 21.5-22.3 mag/arcsec^2", at solar minimum and maximum; and
 * left out, a darker sky. */
TEST(nightglow_dark_site_zenith)
{
    sky_observer o = dark_site();
    const unsigned glows = SKY_AIRGLOW | SKY_ZODIACAL;
    double lmin = zenith_luminance(glows, 0.0f, 0.0f, &o), lmax = zenith_luminance(glows, 0.0f, 1.0f, &o);
    double lnone = zenith_luminance(SKY_FEATURES_NONE, 0.0f, 0.0f, &o);
    double mmin = sky_kcd_to_mag_arcsec2(lmin), mmax = sky_kcd_to_mag_arcsec2(lmax);
    double mnone = sky_kcd_to_mag_arcsec2(lnone);
    NOTE("dark-site zenith: %.2f (solar minimum), %.2f (maximum) mag/arcsec^2; without the glows %.2f", mmin, mmax,
         mnone);
    CHECK(lmin > 0.0 && mmin >= 21.5 && mmin <= 22.3, "solar minimum: %.2f mag/arcsec^2 (21.5-22.3)", mmin);
    CHECK(lmax > 0.0 && mmax >= 21.5 && mmax <= 22.3, "solar maximum: %.2f mag/arcsec^2 (21.5-22.3)", mmax);
    CHECK(mmax < mmin - 0.2, "the airglow follows the solar cycle (%.2f vs %.2f)", mmax, mmin);
    CHECK(mnone > mmin + 1.0, "without airglow and zodiacal light the sky is darker (%.2f)", mnone);
}

/* Issue: "with Bortle 1...9 the zenith follows the class's published
 * range". The natural sky of this scene (about 21.9 at solar minimum)
 * bounds how dark a class can be: class 1's 21.99-22.00 lies under it. */
TEST(nightglow_bortle_classes)
{
    static const double lo[9] = {21.99, 21.89, 21.69, 20.49, 19.50, 18.94, 18.38, 17.80, 17.0};
    static const double hi[9] = {22.00, 21.99, 21.89, 21.69, 20.49, 19.50, 18.94, 18.38, 17.80};
    sky_observer o = dark_site();
    double natural = sky_kcd_to_mag_arcsec2(zenith_luminance(SKY_AIRGLOW | SKY_ZODIACAL, 0.0f, 0.0f, &o));
    double prev = 99.0;
    for (int b = 1; b <= 9; b++) {
        double l = zenith_luminance(SKY_AIRGLOW | SKY_ZODIACAL, (float)b, 0.0f, &o);
        double m = sky_kcd_to_mag_arcsec2(l);
        NOTE("Bortle %d: zenith %.2f mag/arcsec^2 (published %.2f-%.2f)", b, m, lo[b - 1], hi[b - 1]);
        if (b == 1)
            CHECK(fabs(m - natural) < 0.01, "class 1 adds no glow to the natural %.2f (%.2f)", natural, m);
        else
            CHECK(m >= lo[b - 1] - 0.05 && m <= hi[b - 1] + 0.05, "Bortle %d: %.2f outside %.2f-%.2f", b, m,
                  lo[b - 1], hi[b - 1]);
        CHECK(m <= prev + 1e-3, "a higher class is never darker (%d: %.2f after %.2f)", b, m, prev);
        prev = m;
    }
}

/* The zodiacal light where the table has it: along the ecliptic at 60
 * degrees from the sun (505 units), at latitude 60 (104), the gegenschein
 * (230 at 180 degrees, 179 at 150), each through the 8-bit logarithmic
 * encoding within 2.5 %; mirror images east and west of the sun. */
TEST(nightglow_zodiacal_follows_the_table)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_ZODIACAL;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "fixture");
        return;
    }
    sky_observer o = dark_site();
    sky_set_observer(f.s, &o);
    const sky_core *c = &f.s->core;
    /* the frame's rotation: rows are the ecliptic axes (x at the sun, z at
     * the north pole) in the horizon frame */
    const void *zodiacal = f.s->layer_state[SKY_LAYER_ZODIACAL];
    const sky_layer_class *layer = NULL; /* its class, found in the table by name */
    for (int row = 0; row < sky_layer_table_size; row++)
        if (!strcmp(sky_layer_table[row]->name, "zodiacal")) layer = sky_layer_table[row];
    CHECK(layer && layer->glow_at, "the zodiacal layer is a night glow in the table");
    if (!layer || !layer->glow_at) {
        fixture_close(&f);
        return;
    }
    const float *r = sky_zodiacal_rotation(zodiacal);
    double ex[3] = {r[0], r[4], r[8]}, ey[3] = {r[1], r[5], r[9]}, ez[3] = {r[2], r[6], r[10]};
    double unit = sky_mag_arcsec2_to_kcd(27.78) / 1.28;
    float colour[3];
    sky_star_color(0.65, colour);
    static const struct {
        double lon, lat, units;
    } cases[] = {{60, 0, 505}, {-60, 0, 505}, {60, 60, 104}, {150, 0, 179}, {180, 0, 230}, {90, 30, 132}};
    int checked = 0;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double cl = cos(cases[i].lon * DEG), sl = sin(cases[i].lon * DEG), cb = cos(cases[i].lat * DEG),
               sb = sin(cases[i].lat * DEG), d[3], rgb[3];
        for (int k = 0; k < 3; k++) d[k] = cb * cl * ex[k] + cb * sl * ey[k] + sb * ez[k];
        if (d[1] <= 0.05) continue; /* below the horizon here */
        layer->glow_at(c, zodiacal, d, rgb);
        double want = cases[i].units * unit * colour[1];
        CHECK(fabs(rgb[1] / want - 1.0) < 0.025, "(%g, %g): %.4g kcd/m^2, table %.4g", cases[i].lon, cases[i].lat,
              rgb[1], want);
        checked++;
    }
    NOTE("%d table points above the horizon checked", checked);
    CHECK(checked >= 3, "enough of the table above the horizon (%d)", checked);
    fixture_close(&f);
}

/* The CPU twin that the lighting queries use (sky_atmosphere_radiance:
 * floor, light pollution, airglow and zodiacal light through the air)
 * against the rendered dome, at night on two paths, within 3 %. */
TEST(nightglow_cpu_matches_render)
{
    const sky_atmosphere_path paths[2] = {SKY_ATMOSPHERE_GRADIENT, SKY_ATMOSPHERE_HILLAIRE};
    for (int p = 0; p < 2; p++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.features = SKY_AIRGLOW | SKY_ZODIACAL;
        cfg.atmosphere = paths[p];
        cfg.output = SKY_OUTPUT_HDR;
        cfg.bortle = 4.0f;
        const int n = 128;
        fixture f;
        if (fixture_open_sized(&f, n, n, 1, SKY_GL_AUTO, &cfg)) {
            CHECK(0, "fixture");
            return;
        }
        sky_observer o = dark_site();
        sky_set_observer(f.s, &o);
        sky_result rc = sky_draw_fisheye(f.s);
        CHECK(rc == SKY_OK, "sky_draw_fisheye: %s", sky_last_error(f.s));
        sky_osmesa_finish(&f.ctx);
        double worst = 0.0;
        /* the fisheye (common.glsl's sky_fisheye_ndc, inverted): rows
         * bottom first, zenith at the centre, north up, east left */
        for (int y = 4; y < n; y += 8)
            for (int x = 4; x < n; x += 8) {
                double u = (x + 0.5) / n * 2.0 - 1.0, v = (y + 0.5) / n * 2.0 - 1.0, r = hypot(u, v);
                double theta = r * 0.5 * 3.14159265358979323846;
                if (theta > 80.0 * DEG || r < 1e-6) continue;
                double d[3] = {-u / r * sin(theta), cos(theta), -v / r * sin(theta)}, rgb[3];
                sky_atmosphere_radiance(&f.s->core, d, rgb);
                const float *px = (const float *)f.ctx.pixels + 4 * (y * n + x);
                double got = 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2];
                double want = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
                worst = fmax(worst, fabs(got / want - 1.0));
            }
        NOTE("%s: rendered night sky against the CPU twin within %.2f %%", p ? "hillaire" : "gradient",
             100.0 * worst);
        CHECK(worst < 0.03, "%s: %.2f %%", p ? "hillaire" : "gradient", 100.0 * worst);
        fixture_close(&f);
    }
}

/* Layers of their own: the zodiacal light's 64 x 32 RGBA8 table is its
 * only GPU memory, the airglow has none; both are in the dome's night
 * variant at night and not by day. */
TEST(nightglow_layer_costs)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_AIRGLOW | SKY_ZODIACAL;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "fixture");
        return;
    }
    sky_layer_stats airglow, zodiacal;
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_AIRGLOW, &airglow) == SKY_OK &&
              sky_get_layer_stats(f.s, SKY_LAYER_ZODIACAL, &zodiacal) == SKY_OK,
          "the airglow's and the zodiacal light's rows");
    CHECK(zodiacal.enabled && zodiacal.bytes == 64 * 32 * 4, "the zodiacal table is 8192 bytes (%zu)", zodiacal.bytes);
    CHECK(airglow.enabled && airglow.bytes == 0, "the airglow has no GPU memory");
    sky_params p = sky_default_params();
    for (int k = 0; k < 2; k++) {
        p.time = k ? 0.5f : 0.0f;
        sky_set_params(f.s, &p);
        sky_draw_fisheye(f.s);
        sky_get_layer_stats(f.s, SKY_LAYER_AIRGLOW, &airglow);
        sky_get_layer_stats(f.s, SKY_LAYER_ZODIACAL, &zodiacal);
        int a = airglow.drawn, z = zodiacal.drawn;
        CHECK(k ? (!a && !z) : (a && z), "%s: airglow %d, zodiacal light %d in the dome", k ? "noon" : "midnight", a, z);
    }
    fixture_close(&f);
}

/* Schaefer (1990, PASP 102, 212), written out again: the faintest V the
 * naked eye sees against a sky of b mag/arcsec^2. Threshold illuminance
 * c1 (1 + sqrt(c2 B))^2 foot-candles for B nanolamberts, the rods'
 * constants (10^-9.8, 10^-1.9) below 1500 nL and the cones' (10^-8.35,
 * 10^-5.9) above; V = -16.57 - 2.5 log10 of it. 0 mag/arcsec^2 is
 * 108 000 cd/m^2, 1 nL 3.183e-6 cd/m^2. */
static double schaefer_limit(double b)
{
    double nl = 1.08e5 * pow(10.0, -0.4 * b) / 3.183e-6;
    int rods = nl < 1500.0;
    double c1 = pow(10.0, rods ? -9.8 : -8.35), c2 = pow(10.0, rods ? -1.9 : -5.9);
    return -16.57 - 2.5 * log10(c1 * pow(1.0 + sqrt(c2 * nl), 2.0));
}

/* Issue: "the faintest drawn star follows the naked-eye limit for that
 * brightness (Schaefer's formula) within 0.5 mag". At each Bortle class,
 * the catalogue stars above 45 degrees that the view shows (a render with
 * them against one without; only stars with no other within 3 pixels,
 * whose light the test can tell apart), the faintest of them against
 * Schaefer's limit for the zenith's brightness measured in the render.
 * The catalogue stops at V 6.5: under classes 1-3 its limit is the
 * catalogue's. */
TEST(nightglow_naked_eye_limit)
{
    const int n = 512;
    const float classes[6] = {1.0f, 3.0f, 5.0f, 7.0f, 8.0f, 9.0f};
    for (int k = 0; k < 6; k++) {
        float *img[2] = {NULL, NULL};
        double sky_b = 0.0, faintest = -99.0, brightest_missed = 99.0;
        int drawn = 0;
        for (int with = 0; with < 2; with++) {
            sky_config cfg;
            memset(&cfg, 0, sizeof cfg);
            cfg.features = SKY_AIRGLOW | SKY_ZODIACAL | (with ? SKY_STARS : 0u);
            cfg.output = SKY_OUTPUT_HDR;
            cfg.bortle = classes[k];
            cfg.solar_activity_manual = 1;
            cfg.star_control_magnitude = 1.0f; /* glare for the brightest few only */
            fixture f;
            if (fixture_open_sized(&f, n, n, 1, SKY_GL_AUTO, &cfg)) {
                CHECK(0, "fixture");
                free(img[0]);
                return;
            }
            sky_observer o = dark_site();
            sky_set_observer(f.s, &o);
            float view[16], proj[16];
            sky_cli_camera_at(180.0, 90.0, 90.0, n, n, view, proj);
            sky_draw(f.s, view, proj);
            sky_osmesa_finish(&f.ctx);
            img[with] = malloc(sizeof(float) * 4 * (size_t)n * (size_t)n);
            if (img[with]) memcpy(img[with], f.ctx.pixels, sizeof(float) * 4 * (size_t)n * (size_t)n);
            if (!with) {
                const float *c = (const float *)f.ctx.pixels + 4 * (n / 2 * n + n / 2);
                sky_b = sky_kcd_to_mag_arcsec2(0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]);
            } else if (img[0] && img[1]) {
                const sky_catalog *cat = sky_stars_catalog(f.s->layer_state[SKY_LAYER_STARS]);
                /* every star's pixel, then the ones alone within 3 px
                 * (the test cannot tell whose light a shared pixel holds) */
                int *px = calloc(2 * (size_t)cat->count, sizeof(int));
                for (int i = 0; px && i < cat->count; i++) {
                    double alt, alt_geo, az, dir[3], e[4], cl[4];
                    sky_astro_star(&f.s->core.astro, &cat->stars[i], &alt, &alt_geo, &az, dir);
                    px[2 * i] = px[2 * i + 1] = -1000;
                    if (alt < 0.0) continue;
                    for (int r = 0; r < 4; r++) e[r] = view[r] * dir[0] + view[4 + r] * dir[1] + view[8 + r] * dir[2];
                    for (int r = 0; r < 4; r++) cl[r] = proj[r] * e[0] + proj[4 + r] * e[1] + proj[8 + r] * e[2];
                    if (cl[3] <= 0.0) continue;
                    px[2 * i] = (int)floor((cl[0] / cl[3] + 1.0) * 0.5 * n);
                    px[2 * i + 1] = (int)floor((cl[1] / cl[3] + 1.0) * 0.5 * n);
                }
                for (int i = 0; px && i < cat->count; i++) {
                    int x = px[2 * i], y = px[2 * i + 1], alone = 1;
                    double alt, alt_geo, az, dir[3];
                    sky_astro_star(&f.s->core.astro, &cat->stars[i], &alt, &alt_geo, &az, dir);
                    if (alt < 45.0 * DEG || x < 2 || y < 2 || x >= n - 2 || y >= n - 2) continue;
                    for (int j = 0; j < cat->count && alone; j++)
                        if (j != i && abs(px[2 * j] - x) <= 3 && abs(px[2 * j + 1] - y) <= 3) alone = 0;
                    if (!alone) continue;
                    double diff = 0.0;
                    for (int dy = -1; dy <= 1; dy++)
                        for (int dx = -1; dx <= 1; dx++) {
                            size_t at = 4 * ((size_t)(y + dy) * (size_t)n + (size_t)(x + dx)) + 1;
                            diff = fmax(diff, img[1][at] - img[0][at]);
                        }
                    double v = cat->stars[i].vmag;
                    if (diff > 1e-12) {
                        drawn++;
                        faintest = fmax(faintest, v);
                    } else {
                        brightest_missed = fmin(brightest_missed, v);
                    }
                }
                free(px);
            }
            fixture_close(&f);
        }
        free(img[0]);
        free(img[1]);
        double nelm = schaefer_limit(sky_b);
        double expect = fmin(nelm, 6.5); /* the catalogue's last stars are V 6.5 */
        NOTE("Bortle %.0f: zenith %.2f mag/arcsec^2, Schaefer's limit %.2f; %d stars drawn, the faintest V %.2f, "
             "the brightest left out V %.2f",
             (double)classes[k], sky_b, nelm, drawn, faintest, brightest_missed);
        CHECK(drawn > 0 && fabs(faintest - expect) <= 0.5, "Bortle %.0f: faintest drawn V %.2f, limit %.2f",
              (double)classes[k], faintest, expect);
        CHECK(brightest_missed > expect - 0.5, "Bortle %.0f: a V %.2f star is left out under a limit of %.2f",
              (double)classes[k], brightest_missed, expect);
    }
}
