/*
 * Catalogue star tests (Mueller sec. 4): positions in the image against
 * the astronomy, brightness control, colour, scintillation, and leaving
 * the stars out by day.
 */
#include "test.h"
#include "sky_internal.h"
#include "cli.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)

/* Winter evening at 60 N: Orion in the south, Vega low in the north,
 * Polaris at 60 degrees, all five test stars above the horizon. */
static sky_observer winter_evening(void)
{
    sky_observer o = {sky_julian_day(2024, 1, 15, 21, 0, 0.0), 60.0, 10.0, 0.0, 0};
    return o;
}

static scene star_scene(void)
{
    scene sc = scene_default();
    sc.cfg.features = SKY_STARS;
    sc.params.cover = 0.0f;
    return sc;
}

/* Renders a scene as the observer sees it. */
static int render_with_observer(const scene *sc, const sky_observer *o, int hdr, image *out)
{
    scene with = *sc;
    with.has_observer = 1;
    with.observer = *o;
    return render_scene(&with, hdr, SKY_GL_AUTO, out);
}

TEST(stars_where_astronomy_puts_them)
{
    const struct {
        const char *name;
        int hip;
    } stars[5] = {{"Sirius", 32349}, {"Betelgeuse", 27989}, {"Rigel", 24436}, {"Vega", 91262}, {"Polaris", 11767}};
    sky_observer o = winter_evening();
    int hips[5];
    for (int i = 0; i < 5; i++) hips[i] = stars[i].hip;
    sky_star_place places[5];
    sky_astronomy a;
    char err[256];
    if (sky_compute_astronomy(&o, 0.0f, hips, 5, places, &a, err, sizeof err) != SKY_OK) {
        CHECK(0, "%s", err);
        return;
    }
    for (int i = 0; i < 5; i++) {
        CHECK(places[i].found && places[i].alt_deg > 3.0, "%s above the horizon (%.1f)", stars[i].name,
              places[i].alt_deg);
        /* point the camera a little off the star, so the projection is
         * exercised, and find the star where its alt/az projects */
        scene sc = star_scene();
        sc.w = sc.h = 200;
        sc.fov = 20.0;
        sc.yaw = places[i].az_deg + 3.0;
        sc.pitch = fmin(places[i].alt_deg - 2.0, 80.0);
        image im;
        if (render_with_observer(&sc, &o, 1, &im)) {
            CHECK(0, "render failed");
            return;
        }
        double px = -1.0, py = -1.0, bx, by;
        scene_project(&sc, places[i].alt_deg, places[i].az_deg, &px, &py);
        double peak = image_blob(&im, px, py, 6, &bx, &by);
        double err_px = hypot(bx - px, by - py);
        NOTE("%-10s alt %6.2f az %6.2f: expected (%.2f, %.2f), found (%.2f, %.2f): %.2f px", stars[i].name,
             places[i].alt_deg, places[i].az_deg, px, py, bx, by, err_px);
        CHECK(peak > 0.0 && err_px <= 1.5, "%s %.2f px from its astronomical place", stars[i].name, err_px);
        image_free(&im);
    }
}

/* Point sources in an LDR fisheye (inside the circle). */
static int count_stars(const image *im, float contrast)
{
    int n = 0;
    double r_max = 0.95 * 0.5 * im->w;
    for (int y = 1; y < im->h - 1; y++)
        for (int x = 1; x < im->w - 1; x++) {
            if (hypot(x + 0.5 - 0.5 * im->w, y + 0.5 - 0.5 * im->h) > r_max) continue;
            float c = image_luminance(im, x, y), around = 0.0f;
            int higher = 0;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++)
                    if (dx || dy) {
                        float v = image_luminance(im, x + dx, y + dy);
                        higher |= v > c;
                        around += v;
                    }
            n += !higher && c - around / 8.0f > contrast;
        }
    return n;
}

TEST(stars_control_magnitude_and_twilight)
{
    sky_observer o = winter_evening();
    int counts[3];
    const float ma[3] = {2.5f, 4.0f, 6.0f};
    for (int k = 0; k < 3; k++) {
        scene sc = star_scene();
        sc.fisheye = 1;
        sc.w = sc.h = 512;
        sc.cfg.star_control_magnitude = ma[k];
        image im;
        if (render_with_observer(&sc, &o, 0, &im)) {
            CHECK(0, "render failed");
            return;
        }
        counts[k] = count_stars(&im, 0.06f);
        image_free(&im);
    }
    NOTE("visible stars at m_a 2.5 / 4 / 6: %d / %d / %d", counts[0], counts[1], counts[2]);
    CHECK(counts[0] < counts[1] && counts[1] < counts[2], "more stars with a higher control magnitude");
    /* and fewer with less exposure: -2 and +2 stops at m_a 4 */
    int by_ev[2];
    for (int k = 0; k < 2; k++) {
        scene sc = star_scene();
        sc.fisheye = 1;
        sc.w = sc.h = 512;
        sc.exposure_bias = k ? 2.0f : -2.0f;
        image im;
        if (render_with_observer(&sc, &o, 0, &im)) {
            CHECK(0, "render failed");
            return;
        }
        by_ev[k] = count_stars(&im, 0.06f);
        image_free(&im);
    }
    NOTE("visible stars at -2 / 0 / +2 stops: %d / %d / %d", by_ev[0], counts[1], by_ev[1]);
    CHECK(by_ev[0] < counts[1] && counts[1] < by_ev[1], "fewer stars with less exposure");
    /* and fewer as the sky brightens: the same night at dusk */
    sky_observer dusk = o;
    dusk.julian_day_utc = sky_julian_day(2024, 1, 15, 15, 30, 0.0); /* sun a few degrees down */
    scene sc = star_scene();
    sc.fisheye = 1;
    sc.w = sc.h = 512;
    image im;
    if (render_with_observer(&sc, &dusk, 0, &im)) {
        CHECK(0, "render failed");
        return;
    }
    int dusk_count = count_stars(&im, 0.06f);
    image_free(&im);
    NOTE("visible stars at dusk: %d (night: %d)", dusk_count, counts[1]);
    CHECK(dusk_count < counts[1] / 2, "a brighter sky hides most stars (%d vs %d)", dusk_count, counts[1]);
}

TEST(stars_colour_follows_bv)
{
    float blue[3], red[3], sun[3];
    sky_star_color(-0.03, blue); /* Rigel */
    sky_star_color(1.85, red);   /* Betelgeuse */
    sky_star_color(0.65, sun);   /* a G2 star like the sun: near white */
    CHECK(blue[2] / blue[0] > 1.2 * red[2] / red[0], "a B-V < 0 star is bluer than a B-V > 1.3 one");
    CHECK(red[0] > red[2], "Betelgeuse is red (%.2f %.2f %.2f)", red[0], red[1], red[2]);
    CHECK(fabs(sun[0] - sun[2]) < 0.35 * sun[1], "a solar-type star is nearly white (%.2f %.2f %.2f)", sun[0], sun[1],
          sun[2]);
    for (double bv = -0.5; bv <= 3.0; bv += 0.05) {
        float c[3];
        sky_star_color(bv, c);
        double y = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        if (!(fabs(y - 1.0) < 1e-3 && c[0] >= 0 && c[1] >= 0 && c[2] >= 0)) {
            CHECK(0, "B-V %.2f: colour (%g %g %g) must be non-negative with unit luminance", bv, c[0], c[1], c[2]);
            break;
        }
    }
    /* in the image: Rigel's pixels bluer than Betelgeuse's */
    sky_observer o = winter_evening();
    int hips[2] = {24436, 27989};
    sky_star_place p[2];
    sky_astronomy a;
    sky_compute_astronomy(&o, 0.0f, hips, 2, p, &a, NULL, 0);
    double ratio[2];
    for (int i = 0; i < 2; i++) {
        scene sc = star_scene();
        sc.w = sc.h = 64;
        sc.fov = 5.0;
        sc.yaw = p[i].az_deg;
        sc.pitch = p[i].alt_deg;
        image im;
        if (render_with_observer(&sc, &o, 1, &im)) {
            CHECK(0, "render failed");
            return;
        }
        double r = 0, b = 0;
        for (int y = 24; y < 40; y++)
            for (int x = 24; x < 40; x++) r += im.px[3 * (y * 64 + x)], b += im.px[3 * (y * 64 + x) + 2];
        ratio[i] = b / (r + 1e-30);
        image_free(&im);
    }
    NOTE("blue/red in the image: Rigel %.2f, Betelgeuse %.2f", ratio[0], ratio[1]);
    CHECK(ratio[0] > 1.5 * ratio[1], "Rigel renders bluer than Betelgeuse");
}

SLOW_TEST(stars_scintillate_more_near_horizon)
{
    /* brightness of every catalogue star over 24 frames, in a fisheye;
     * relative variance averaged for low (5..15 deg) and high (70..90 deg) */
    sky_observer o = winter_evening();
    enum { FRAMES = 24, W = 512 };
    sky_catalog cat;
    if (sky_catalog_load(&cat, NULL, 0)) {
        CHECK(0, "catalogue");
        return;
    }
    sky_astro a;
    sky_observer_astro(&o, 0.0, NULL, &a, NULL, 0);
    int n = cat.count < 3000 ? cat.count : 3000; /* the brightest 3000 */
    double *sum = calloc((size_t)n, sizeof(double)), *sum2 = calloc((size_t)n, sizeof(double));
    int *px = calloc((size_t)n * 2, sizeof(int));
    double *alt = calloc((size_t)n, sizeof(double));
    for (int i = 0; i < n; i++) {
        double al, ag, az, d[3];
        sky_astro_star(&a, &cat.stars[i], &al, &ag, &az, d);
        alt[i] = al / DEG;
        double theta = acos(d[1]), hl = hypot(d[0], d[2]), r = theta / (3.14159265358979323846 / 2);
        px[2 * i] = hl > 0 ? (int)((1.0 - r * d[0] / hl) * 0.5 * W) : W / 2;
        px[2 * i + 1] = hl > 0 ? (int)((1.0 + r * d[2] / hl) * 0.5 * W) : W / 2;
    }
    for (int f = 0; f < FRAMES; f++) {
        scene sc = star_scene();
        sc.fisheye = 1;
        sc.w = sc.h = W;
        sc.seconds = f * 0.37; /* independent scintillation values */
        image im;
        if (render_with_observer(&sc, &o, 1, &im)) {
            CHECK(0, "render failed");
            break;
        }
        for (int i = 0; i < n; i++) {
            double s = 0;
            for (int dy = -2; dy <= 2; dy++)
                for (int dx = -2; dx <= 2; dx++) {
                    int x = px[2 * i] + dx, y = px[2 * i + 1] + dy;
                    if (x >= 0 && y >= 0 && x < W && y < W) s += image_luminance(&im, x, y);
                }
            sum[i] += s;
            sum2[i] += s * s;
        }
        image_free(&im);
    }
    double low = 0, high = 0;
    int nl = 0, nh = 0;
    for (int i = 0; i < n; i++) {
        double m = sum[i] / FRAMES;
        if (m <= 0) continue;
        double rel_var = (sum2[i] / FRAMES - m * m) / (m * m);
        if (alt[i] > 5 && alt[i] < 15) low += rel_var, nl++;
        if (alt[i] > 70) high += rel_var, nh++;
    }
    low /= nl > 0 ? nl : 1;
    high /= nh > 0 ? nh : 1;
    NOTE("relative brightness variance over %d frames: %.2e at 5-15 deg (%d stars), %.2e above 70 deg (%d stars)",
         FRAMES, low, nl, high, nh);
    CHECK(nl > 20 && nh > 20, "enough stars low and high");
    CHECK(low > 1e-6 && low > 10.0 * high, "scintillation grows toward the horizon (%.2e vs %.2e)", low, high);
    free(sum);
    free(sum2);
    free(px);
    free(alt);
    sky_catalog_free(&cat);
}

TEST(stars_skipped_at_noon)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_STARS | SKY_SUN;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "fixture");
        return;
    }
    sky_params p = sky_default_params();
    sky_layer_stats stars;
    float view[16], proj[16];
    scene sc = scene_default();
    scene_camera(&sc, view, proj);
    p.time = 0.5f;
    sky_set_params(f.s, &p);
    sky_draw(f.s, view, proj);
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_STARS, &stars) == SKY_OK && stars.enabled && !stars.drawn &&
              stars.draws == 0,
          "no star draw at noon");
    p.time = 0.0f;
    sky_set_params(f.s, &p);
    sky_draw(f.s, view, proj);
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_STARS, &stars) == SKY_OK && stars.draws == 1, "one star draw at midnight");
    CHECK(stars.bytes > 8000 * 9 * sizeof(float), "the star buffer is counted (%zu bytes)", stars.bytes);
    fixture_close(&f);
    /* and no star pixel at noon: the image equals one without stars */
    scene with = star_scene(), without = scene_default();
    with.params.time = without.params.time = 0.5f;
    with.params.cover = without.params.cover = 0.0f;
    without.cfg.features = SKY_FEATURES_NONE;
    image a, b;
    if (render_scene(&with, 1, SKY_GL_AUTO, &a) || render_scene(&without, 1, SKY_GL_AUTO, &b)) {
        CHECK(0, "render failed");
        return;
    }
    double worst = 0;
    for (size_t i = 0; i < 3u * (size_t)a.w * (size_t)a.h; i++) worst = fmax(worst, fabs((double)a.px[i] - b.px[i]));
    CHECK(worst == 0.0, "noon with catalogue stars equals noon without (max difference %g)", worst);
    image_free(&a);
    image_free(&b);
}

/* Fisheye pixel of a horizon direction (sky.h's equidistant mapping). */
static void fisheye_pixel(const double d[3], int n, double *x, double *y)
{
    double theta = acos(d[1]), hl = hypot(d[0], d[2]), r = theta / (3.14159265358979323846 / 2);
    *x = hl > 0 ? (1.0 - r * d[0] / hl) * 0.5 * n : 0.5 * n;
    *y = hl > 0 ? (1.0 + r * d[2] / hl) * 0.5 * n : 0.5 * n;
}

TEST(starmap_shows_the_milky_way)
{
    /* An August night at 45 N: the galactic centre (Sgr A*) low in the
     * south, the galactic north pole (in Coma) in the west. */
    sky_observer o = {sky_julian_day(2024, 8, 10, 21, 0, 0.0), 45.0, 10.0, 0.0, 0};
    sky_astro a;
    sky_observer_astro(&o, 0.0, NULL, &a, NULL, 0);
    const sky_star gc = {0, 266.417 * DEG, -29.008 * DEG, 0, 0, 0, 0}, gnp = {0, 192.859 * DEG, 27.128 * DEG, 0, 0, 0, 0};
    double alt, alt_geo, az, d_gc[3], d_gnp[3];
    sky_astro_star(&a, &gc, &alt, &alt_geo, &az, d_gc);
    double alt_gc = alt;
    sky_astro_star(&a, &gnp, &alt, &alt_geo, &az, d_gnp);
    CHECK(alt_gc > 10 * DEG && alt > 10 * DEG, "both above the horizon (%.1f, %.1f deg)", alt_gc / DEG, alt / DEG);
    scene sc = scene_default();
    sc.cfg.features = SKY_STARMAP;
    sc.fisheye = 1;
    sc.w = sc.h = 256;
    image im;
    if (render_with_observer(&sc, &o, 1, &im)) {
        CHECK(0, "render failed");
        return;
    }
    double x, y, l_gc = 0, l_gnp = 0;
    fisheye_pixel(d_gc, 256, &x, &y);
    for (int dy = -2; dy <= 2; dy++)
        for (int dx = -2; dx <= 2; dx++) l_gc += image_luminance(&im, (int)x + dx, (int)y + dy);
    fisheye_pixel(d_gnp, 256, &x, &y);
    for (int dy = -2; dy <= 2; dy++)
        for (int dx = -2; dx <= 2; dx++) l_gnp += image_luminance(&im, (int)x + dx, (int)y + dy);
    image_free(&im);
    /* the same place without the star map: what the map adds */
    sc.cfg.features = SKY_FEATURES_NONE;
    if (render_with_observer(&sc, &o, 1, &im)) {
        CHECK(0, "render failed");
        return;
    }
    double b_gc = 0, b_gnp = 0;
    fisheye_pixel(d_gc, 256, &x, &y);
    for (int dy = -2; dy <= 2; dy++)
        for (int dx = -2; dx <= 2; dx++) b_gc += image_luminance(&im, (int)x + dx, (int)y + dy);
    fisheye_pixel(d_gnp, 256, &x, &y);
    for (int dy = -2; dy <= 2; dy++)
        for (int dx = -2; dx <= 2; dx++) b_gnp += image_luminance(&im, (int)x + dx, (int)y + dy);
    image_free(&im);
    double add_gc = (l_gc - b_gc) / 25, add_gnp = (l_gnp - b_gnp) / 25;
    NOTE("star map adds %.3g kcd/m^2 at the galactic centre, %.3g at the galactic pole", add_gc, add_gnp);
    CHECK(add_gc > 3.0 * add_gnp && add_gc > 0, "the Milky Way's core outshines the galactic pole");

    /* by day the map is not evaluated at all */
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_STARMAP;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg) == 0) {
        sky_params p = sky_default_params();
        sky_layer_stats map;
        p.time = 0.5f;
        sky_set_params(f.s, &p);
        sky_draw_fisheye(f.s);
        CHECK(sky_get_layer_stats(f.s, SKY_LAYER_STARMAP, &map) == SKY_OK && map.enabled && !map.drawn,
              "no star map at noon");
        /* the 512x256 image, resampled into a cube map of the same
         * resolution at the faces' centres (starmap.c) */
        CHECK(map.bytes == 6 * 128 * 128 * 4, "the map is six 128x128 RGBA8 faces (%zu bytes)", map.bytes);
        p.time = 0.0f;
        sky_set_params(f.s, &p);
        sky_draw_fisheye(f.s);
        CHECK(sky_get_layer_stats(f.s, SKY_LAYER_STARMAP, &map) == SKY_OK && map.drawn, "the star map at midnight");
        fixture_close(&f);
    }
}

/* One star's light in an HDR render centred on it, klx (luminance-weighted):
 * the pixels within `radius` px of the centre, each less the median of a
 * ring just outside (the dome and the faint stars), times the pixel's solid
 * angle (the centre's, pixel_angle^2: the star sits on the axis). expect:
 * its physical illuminance, E0 2.512^-V scaled by the control magnitude
 * (2.512^(m_a - 4)) and the extinction the shader applies (eq. 11-12 over
 * the frame's optical depths, the star's colour weighted); no fade: the
 * sky's own light is what hides the stars by day. */
static double star_flux(const sky_observer *o, const sky_star_place *p, float m_a, int radius, double *expect)
{
    const int n = 256;
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_STARS;
    cfg.output = SKY_OUTPUT_HDR;
    cfg.star_control_magnitude = m_a;
    fixture f;
    if (fixture_open_sized(&f, n, n, 1, SKY_GL_AUTO, &cfg)) return -1.0;
    sky_params prm = sky_default_params();
    prm.cover = 0.0f;
    float view[16], proj[16];
    sky_cli_camera_at(p->az_deg, p->alt_deg, 20.0, n, n, view, proj);
    if (sky_set_params(f.s, &prm) < 0 || sky_set_observer(f.s, o) != SKY_OK || sky_draw(f.s, view, proj) < 0) {
        fixture_close(&f);
        return -1.0;
    }
    sky_osmesa_finish(&f.ctx);
    double sum = image_centre_sum(f.ctx.pixels, n, radius);
    const sky_frame *fr = &f.s->core.frame;
    double pa = fr->pixel_angle;
    float rgb[3];
    sky_star_color(p->bv, rgb);
    double cos_t = sin(p->alt_deg * DEG), a = fr->night_shell[0], b = fr->night_shell[1];
    double airmass = (sqrt(b * b - a * a * (1.0 - cos_t * cos_t)) - a * cos_t) / fr->night_shell[2];
    static const double w[3] = {0.2126, 0.7152, 0.0722};
    double ext = 0.0;
    for (int c = 0; c < 3; c++) ext += w[c] * rgb[c] * exp(-fr->night_depth[c] * airmass);
    *expect = 2.54e-9 * pow(2.512, m_a - 4.0 - p->vmag) * ext;
    fixture_close(&f);
    return sum * pa * pa;
}

TEST(stars_flux_with_and_without_glare)
{
    /* Capella (V 0.08) near the zenith of the winter evening (scintillation
     * there under 1 %): without glare at m_a 1 would need m_a < 0.25, so
     * m_a 1 gives it a 1.5 px glare barely past the PSF's q, 4 an 8 px one,
     * 6.5 a 25 px one; each must carry the star's light, no more */
    sky_observer o = winter_evening();
    int hip = 24608;
    sky_star_place p;
    sky_astronomy a;
    if (sky_compute_astronomy(&o, 0.0f, &hip, 1, &p, &a, NULL, 0) != SKY_OK || !p.found) {
        CHECK(0, "Capella's place");
        return;
    }
    CHECK(p.alt_deg > 60.0, "Capella high (%.1f deg)", p.alt_deg);
    const float ma[3] = {1.0f, 4.0f, 6.5f};
    const int radius[3] = {4, 12, 30};
    for (int i = 0; i < 3; i++) {
        double expect = 0.0, got = star_flux(&o, &p, ma[i], radius[i], &expect);
        NOTE("m_a %.1f: Capella at %.1f deg sums to %.4g lx, physical %.4g lx (%+.1f %%)", ma[i], p.alt_deg, got * 1e3,
             expect * 1e3, 100.0 * (got / expect - 1.0));
        CHECK(expect > 0.0 && fabs(got / expect - 1.0) <= 0.03, "m_a %.1f: %.4g lx vs %.4g lx", ma[i], got * 1e3,
              expect * 1e3);
    }
}

/* The draw takes only the stars of the cells above the horizon and in
 * view (stars.c's STAR_CELLS): against every star through stars.vert, no
 * pixel may change, whatever the camera (near the horizon, at the zenith,
 * narrow and wide, the fisheye), under a dark sky (every star in reach)
 * and a moonlit one (a tenth). */
TEST(stars_cells_lose_no_star)
{
    enum { W = 320, H = 180 };
    static const struct { double yaw, pitch, fov; } views[] = {
        {180.0, 10.0, 60.0}, {30.0, 89.0, 60.0}, {275.0, 35.0, 12.0}, {90.0, -20.0, 110.0}, {0.0, 0.0, 0.0}};
    for (int moon = 0; moon < 2; moon++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.features = SKY_STARS | (moon ? SKY_MOON : 0u);
        cfg.output = SKY_OUTPUT_HDR;
        fixture f;
        if (fixture_open_sized(&f, W, H, 1, SKY_GL_AUTO, &cfg)) {
            CHECK(0, "fixture");
            return;
        }
        /* a winter night at 60 N; with the moon a full one up */
        sky_observer o = winter_evening();
        if (moon) o.julian_day_utc = sky_julian_day(2024, 1, 25, 23, 0, 0.0);
        sky_set_observer(f.s, &o);
        void *stars = f.s->layer_state[SKY_LAYER_STARS];
        for (size_t v = 0; v < sizeof views / sizeof views[0]; v++) {
            float *img[2] = {NULL, NULL};
            for (int whole = 0; whole < 2; whole++) {
                sky_stars_draw_whole(stars, whole);
                float view[16], proj[16];
                sky_cli_camera_at(views[v].yaw, views[v].pitch, views[v].fov > 0.0 ? views[v].fov : 60.0, W, H,
                                  view, proj);
                sky_result r = views[v].fov > 0.0 ? sky_draw(f.s, view, proj) : sky_draw_fisheye(f.s);
                CHECK(r == SKY_OK, "draw: %s", sky_last_error(f.s));
                sky_osmesa_finish(&f.ctx);
                img[whole] = malloc(sizeof(float) * 4 * W * H);
                if (img[whole]) memcpy(img[whole], f.ctx.pixels, sizeof(float) * 4 * W * H);
            }
            sky_stars_draw_whole(stars, 0);
            if (img[0] && img[1]) {
                /* (the light; alpha, which sky.h leaves open, counts the
                 * additive points that reached a pixel, light or none) */
                int changed = 0, lit = 0;
                for (int i = 0; i < W * H * 4; i++)
                    if (i % 4 != 3) {
                        changed += img[0][i] != img[1][i];
                        lit += img[1][i] > 0.0f;
                    }
                NOTE("%s, view %zu: %d lit values, %d changed by the cells", moon ? "moonlit" : "dark", v, lit,
                     changed);
                CHECK(lit > 0 && changed == 0, "%s, view %zu (yaw %.0f pitch %.0f fov %.0f): the cells change %d "
                      "values of the frame", moon ? "moonlit" : "dark", v, views[v].yaw, views[v].pitch,
                      views[v].fov, changed);
            }
            free(img[0]);
            free(img[1]);
        }
        fixture_close(&f);
    }
}
