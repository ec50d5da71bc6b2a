/*
 * The planets (Night sky II): positions and magnitudes against PyEphem's
 * (tests/data/planets_reference.txt, written by tools/planet-reference.py
 * with Debian's python3-ephem), magnitudes against Mallama & Hilton's own
 * test values, and the state's Taylor step against the full series.
 */
#include "test.h"
#include "astro.h"

#include "cli.h"
#include "sky_internal.h"

#include <math.h>
#include <string.h>

#define DEG (3.14159265358979323846 / 180.0)
#define ARCSEC_PER_RAD 206264.806

static double angle_between(const double u[3], const double v[3])
{
    double c[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    return atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), u[0] * v[0] + u[1] * v[1] + u[2] * v[2]);
}

static int planet_index(const char *name)
{
    for (int i = 0; i < SKY_ASTRO_PLANETS; i++)
        if (!strcmp(name, sky_astro_planet_name(i))) return i;
    return -1;
}

/* Issue: "Planet positions ... over 1 000 instants 1800-2200: <= 20"
 * (alt/az, topocentric); magnitudes within 0.1 of the published formulas'
 * values". Each row is one planet at one instant and place; both sides
 * turn the Earth with PyEphem's Delta T. */
TEST(planets_vs_pyephem)
{
    FILE *f = fopen("tests/data/planets_reference.txt", "r");
    CHECK(f != NULL, "tests/data/planets_reference.txt is missing (tools/planet-reference.py writes it)");
    if (!f) return;
    char line[512];
    int rows[SKY_ASTRO_PLANETS] = {0}, bad_rows = 0;
    double worst_pos[SKY_ASTRO_PLANETS] = {0}, sum_pos[SKY_ASTRO_PLANETS] = {0};
    double worst_mag[SKY_ASTRO_PLANETS] = {0}, worst_dist[SKY_ASTRO_PLANETS] = {0};
    double worst_lit[SKY_ASTRO_PLANETS] = {0}, sum_own[SKY_ASTRO_PLANETS] = {0};
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#') continue;
        double jd, dt, lat, lon, elev, alt, az, dist, vmag, phase, vmag_mh;
        char name[16];
        if (sscanf(line, "%lf %lf %lf %lf %lf %15s %lf %lf %lf %lf %lf %lf", &jd, &dt, &lat, &lon, &elev, name, &alt,
                   &az, &dist, &vmag, &phase, &vmag_mh) != 12) {
            bad_rows++;
            continue;
        }
        int p = planet_index(name);
        sky_astro_observer obs = {lat * DEG, lon * DEG, elev};
        sky_astro a;
        char err[128];
        if (p < 0 || sky_astro_compute_dt(jd, dt, &obs, &a, err, sizeof err)) {
            bad_rows++;
            continue;
        }
        sky_planet_state st;
        sky_planet_state_at(p, a.jd_tt, &st);
        sky_astro_planet pl;
        sky_astro_planet_place(&a, p, &st, &pl);
        double want[3], got[3];
        sky_horizon_vector(alt * DEG, az * DEG, want);
        sky_horizon_vector(pl.body.alt_geometric, pl.body.az, got);
        double e = angle_between(want, got) * ARCSEC_PER_RAD;
        rows[p]++;
        sum_pos[p] += e;
        worst_pos[p] = fmax(worst_pos[p], e);
        worst_mag[p] = fmax(worst_mag[p], fabs(pl.vmag - vmag_mh));
        worst_dist[p] = fmax(worst_dist[p], fabs(pl.distance_au / dist - 1.0));
        worst_lit[p] = fmax(worst_lit[p], fabs(pl.illuminated - phase / 100.0));
        sum_own[p] += pl.vmag - vmag;
    }
    fclose(f);
    CHECK(bad_rows == 0, "%d unreadable rows", bad_rows);
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++) {
        const char *n = sky_astro_planet_name(p);
        CHECK(rows[p] == 1000, "%s: %d rows, want 1000", n, rows[p]);
        if (!rows[p]) continue;
        NOTE("%-8s position worst %.2f\" mean %.2f\"; magnitude worst %.3f; distance %.1e; lit fraction %.4f; "
             "mean minus PyEphem's own (Harris 1961) magnitude %+.3f",
             n, worst_pos[p], sum_pos[p] / rows[p], worst_mag[p], worst_dist[p], worst_lit[p], sum_own[p] / rows[p]);
        CHECK(worst_pos[p] <= 20.0, "%s: %.2f\" from PyEphem (limit 20\")", n, worst_pos[p]);
        CHECK(worst_mag[p] <= 0.1, "%s: magnitude %.3f from Mallama & Hilton on PyEphem's geometry (limit 0.1)", n,
              worst_mag[p]);
        /* PyEphem's distance is the planet's at the instant, ours where the
         * light left it: they differ by the light time's motion */
        CHECK(worst_dist[p] <= 5e-4, "%s: distance %.1e relative from PyEphem's", n, worst_dist[p]);
        CHECK(worst_lit[p] <= 1e-3, "%s: illuminated fraction %.4f from PyEphem's", n, worst_lit[p]);
    }
}

/* The authors' own test values (Mallama & Hilton 2018, Ap_Mag_Input_V3 of
 * their reference code: distances and phase angles from JPL Horizons, and
 * the magnitude their equations give), to 0.001 as their code checks; Mars
 * to 0.03, since its rotation term is left out. */
TEST(planets_magnitudes_published)
{
    static const struct {
        int planet;
        double r, delta, alpha_deg, want, tolerance;
    } cases[] = {
        {SKY_ASTRO_MERCURY, 0.310295423552, 1.32182643625754, 1.1677, -2.477, 0.001},
        {SKY_ASTRO_MERCURY, 0.413629222334, 0.92644808718613, 90.1662, 0.181, 0.001},
        {SKY_ASTRO_MERCURY, 0.448947624811, 0.56004973217883, 178.7284, 7.167, 0.001},
        {SKY_ASTRO_VENUS, 0.722722540169, 1.71607489554051, 1.3232, -3.917, 0.001},
        {SKY_ASTRO_VENUS, 0.721480714554, 0.37762511206278, 124.1348, -4.916, 0.001},
        {SKY_ASTRO_VENUS, 0.726166592736, 0.28889582420642, 179.1845, -3.090, 0.001},
        {SKY_ASTRO_JUPITER, 5.446231815414, 6.44985867459088, 0.2446, -1.667, 0.001},
        {SKY_ASTRO_JUPITER, 4.957681473205, 3.95393078136013, 0.3431, -2.934, 0.001},
        {SKY_ASTRO_JUPITER, 5.227587855371, 5.23501920009381, 147.0989, 0.790, 0.001},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double v = sky_astro_planet_magnitude(cases[i].planet, cases[i].r, cases[i].delta, cases[i].alpha_deg * DEG,
                                              0.0, 0.0);
        CHECK(fabs(v - cases[i].want) <= cases[i].tolerance + 5e-4, "%s at phase %.1f: %.4f, published %.3f",
              sky_astro_planet_name(cases[i].planet), cases[i].alpha_deg, v, cases[i].want);
    }
    /* Mars at its 2003 August 28 opposition: heliocentric longitude
     * 334.4996, published -2.862 with both of Mallama 2007's terms */
    double mars = sky_astro_planet_magnitude(SKY_ASTRO_MARS, 1.381191244505, 0.37274381097911, 4.8948 * DEG, 0.0,
                                             334.4996 * DEG);
    CHECK(fabs(mars - (-2.862)) <= 0.03, "Mars 2003-08-28: %.3f, published -2.862", mars);
    /* every phase angle gives a finite magnitude, out to 180 degrees */
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++)
        for (int a = 0; a <= 180; a += 5) {
            double v = sky_astro_planet_magnitude(p, 1.0, 1.0, a * DEG, 0.3, 1.0);
            CHECK(isfinite(v), "%s at phase %d: %g", sky_astro_planet_name(p), a, v);
        }
}

/* A state serves SKY_PLANET_STATE_DAYS either side of its instant: the
 * Taylor step against the full series, at Mercury's and Venus's closest
 * approaches (where their geocentric motion is fastest) and elsewhere. */
TEST(planets_state_serves_its_window)
{
    double worst[SKY_ASTRO_PLANETS] = {0};
    sky_astro_observer obs = {45.0 * DEG, 10.0 * DEG, 0.0};
    for (int k = 0; k < 200; k++) {
        double jd = 2451545.0 + k * 37.3; /* 20 years, every synodic phase */
        for (int side = -1; side <= 1; side += 2) {
            sky_astro a;
            char err[64];
            if (sky_astro_compute(jd + side * SKY_PLANET_STATE_DAYS, &obs, &a, err, sizeof err)) continue;
            for (int p = 0; p < SKY_ASTRO_PLANETS; p++) {
                sky_planet_state exact, old;
                sky_planet_state_at(p, a.jd_tt, &exact);
                sky_planet_state_at(p, a.jd_tt - side * SKY_PLANET_STATE_DAYS, &old);
                sky_astro_planet want, got;
                sky_astro_planet_place(&a, p, &exact, &want);
                sky_astro_planet_place(&a, p, &old, &got);
                worst[p] = fmax(worst[p], angle_between(want.body.dir_geometric, got.body.dir_geometric) * ARCSEC_PER_RAD);
            }
        }
    }
    for (int p = 0; p < SKY_ASTRO_PLANETS; p++) {
        NOTE("%-8s %.3f\" after %.1f days", sky_astro_planet_name(p), worst[p], SKY_PLANET_STATE_DAYS);
        CHECK(worst[p] <= 0.5, "%s: %.3f\" after %.1f days (limit 0.5\")", sky_astro_planet_name(p), worst[p],
              SKY_PLANET_STATE_DAYS);
    }
}

static sky_observer observer_at(int y, int mo, int d, int h, int mi)
{
    sky_observer o = {sky_julian_day(y, mo, d, h, mi, 0.0), 48.1, 11.6, 500.0, 0};
    return o;
}

/* The observer of that instant (observer_at) and its astronomy; 0, or -1
 * with a failed check. */
static int astronomy_at(int y, int mo, int d, int h, int mi, sky_observer *o, sky_astronomy *a)
{
    *o = observer_at(y, mo, d, h, mi);
    int rc = sky_compute_astronomy(o, 0.0f, NULL, 0, NULL, a, NULL, 0) == SKY_OK ? 0 : -1;
    CHECK(rc == 0, "sky_compute_astronomy");
    return rc;
}

/* Venus and Jupiter half a degree apart in the evening twilight of
 * 2023-03-01 (Munich, sun 8.8 degrees down): each drawn where the
 * astronomy puts it, and nothing there without SKY_PLANETS. */
TEST(planets_drawn_where_astronomy_puts_them)
{
    sky_observer o;
    sky_astronomy a;
    if (astronomy_at(2023, 3, 1, 17, 45, &o, &a)) return;
    const sky_planet_place *venus = &a.planets[SKY_PLANET_VENUS], *jupiter = &a.planets[SKY_PLANET_JUPITER];
    scene sc = scene_default();
    sc.cfg.features = SKY_PLANETS;
    sc.params.cover = 0.0f;
    sc.has_observer = 1;
    sc.observer = o;
    sc.w = sc.h = 256;
    sc.fov = 4.0;
    sc.yaw = venus->place.az_deg + 0.4;
    sc.pitch = venus->place.alt_deg + 0.3;
    image with, without;
    if (render_scene(&sc, 1, SKY_GL_AUTO, &with)) {
        CHECK(0, "render failed");
        return;
    }
    sc.cfg.features = SKY_FEATURES_NONE;
    if (render_scene(&sc, 1, SKY_GL_AUTO, &without)) {
        CHECK(0, "render failed");
        image_free(&with);
        return;
    }
    const sky_planet_place *pair[2] = {venus, jupiter};
    double peak[2] = {0, 0};
    for (int i = 0; i < 2; i++) {
        double px = -1, py = -1, bx, by, ex, ey;
        scene_project(&sc, pair[i]->place.alt_deg, pair[i]->place.az_deg, &px, &py);
        peak[i] = image_blob(&with, px, py, 5, &bx, &by);
        double bare = image_blob(&without, px, py, 5, &ex, &ey);
        double off = hypot(bx - px, by - py);
        NOTE("%-7s alt %.3f az %.3f: expected (%.2f, %.2f), found (%.2f, %.2f): %.2f px; peak %.3g, sky %.3g kcd/m^2",
             i ? "Jupiter" : "Venus", pair[i]->place.alt_deg, pair[i]->place.az_deg, px, py, bx, by, off, peak[i], bare);
        CHECK(off <= 1.5, "%s %.2f px from its place", i ? "Jupiter" : "Venus", off);
        CHECK(peak[i] > 5.0 * bare, "%s stands out of the twilight (%.3g vs %.3g)", i ? "Jupiter" : "Venus", peak[i],
              bare);
    }
    /* Venus 1.85 magnitudes brighter: its peak holds the larger share of
     * its light in the glare (stars.vert), so its peak outshines Jupiter's
     * by less than 5.5 but clearly */
    CHECK(peak[0] > 1.5 * peak[1], "Venus brighter than Jupiter (%.3g vs %.3g)", peak[0], peak[1]);
    image_free(&with);
    image_free(&without);
}

/* A planet's light sums to its illuminance: V from Mallama & Hilton, the
 * extinction and colour of a star (stars.vert), no day-night fade. Venus
 * at 15 degrees in the twilight of 2023-06-04, at the default m_a 4 (a
 * glare of 63 px, which carries 84 % of its light). */
TEST(planets_light_sums_to_magnitude)
{
    sky_observer o;
    sky_astronomy a;
    if (astronomy_at(2023, 6, 4, 20, 40, &o, &a)) return;
    const sky_planet_place *v = &a.planets[SKY_PLANET_VENUS];
    const int n = 256, radius = 70;
    const float m_a = 4.0f;
    /* the sky at Venus's altitude outshines Venus's pixels a hundred
     * times: the same view without the planets takes it away exactly */
    double sums[2] = {0, 0};
    sky_frame fr;
    for (int k = 0; k < 2; k++) {
        sky_config cfg;
        memset(&cfg, 0, sizeof cfg);
        cfg.features = k ? SKY_FEATURES_NONE : SKY_PLANETS;
        cfg.output = SKY_OUTPUT_HDR;
        cfg.star_control_magnitude = m_a;
        fixture f;
        if (fixture_open_sized(&f, n, n, 1, SKY_GL_AUTO, &cfg)) {
            CHECK(0, "fixture");
            return;
        }
        sky_params prm = sky_default_params();
        prm.cover = 0.0f;
        float view[16], proj[16];
        sky_cli_camera_at(v->place.az_deg, v->place.alt_deg, 20.0, n, n, view, proj);
        if (sky_set_params(f.s, &prm) < 0 || sky_set_observer(f.s, &o) != SKY_OK || sky_draw(f.s, view, proj) < 0) {
            CHECK(0, "draw");
            fixture_close(&f);
            return;
        }
        sky_osmesa_finish(&f.ctx);
        sums[k] = image_centre_sum(f.ctx.pixels, n, radius);
        if (!k) fr = f.s->core.frame;
        fixture_close(&f);
    }
    double got = (sums[0] - sums[1]) * fr.pixel_angle * fr.pixel_angle;
    float rgb[3];
    sky_star_color(0.82, rgb);
    double cos_t = sin(v->place.alt_deg * DEG), sa = fr.night_shell[0], sb = fr.night_shell[1];
    double airmass = (sqrt(sb * sb - sa * sa * (1.0 - cos_t * cos_t)) - sa * cos_t) / fr.night_shell[2];
    static const double w[3] = {0.2126, 0.7152, 0.0722};
    double ext = 0.0;
    for (int c = 0; c < 3; c++) ext += w[c] * rgb[c] * exp(-fr.night_depth[c] * airmass);
    double expect = 2.54e-9 * pow(2.512, m_a - 4.0 - v->vmag) * ext;
    NOTE("Venus V %.2f at %.1f deg sums to %.4g lx, physical %.4g lx (%+.1f %%)", v->vmag, v->place.alt_deg,
         got * 1e3, expect * 1e3, 100.0 * (got / expect - 1.0));
    CHECK(fabs(got / expect - 1.0) <= 0.03, "Venus's light %.4g lx, its magnitude's %.4g lx", got * 1e3, expect * 1e3);
}

/* Venus in a clear afternoon sky (2023-06-04, 17:00 local time, the sun at
 * 38 degrees, Venus 45 degrees east of it, some 2 % of the blue sky's
 * luminance in a 1' PSF: there for an eye that knows where to look):
 * through a 5-degree view, whose pixels are about 1', it is a speck a
 * few 8-bit levels above the blue; through a 60-degree view of 256
 * pixels its light spreads over 14' and it is gone. */
TEST(planets_venus_in_the_afternoon)
{
    sky_observer o;
    sky_astronomy a;
    if (astronomy_at(2023, 6, 4, 15, 0, &o, &a)) return;
    const sky_planet_place *v = &a.planets[SKY_PLANET_VENUS];
    CHECK(a.sun.alt_deg > 30.0 && v->place.alt_deg > 30.0, "sun %.1f, Venus %.1f degrees up", a.sun.alt_deg,
          v->place.alt_deg);
    const double fovs[2] = {5.0, 60.0};
    double step[2] = {0, 0}; /* what Venus adds to its brightest pixel, 8-bit levels */
    for (int k = 0; k < 2; k++) {
        double peak[2];
        for (int with = 0; with < 2; with++) {
            scene sc = scene_default();
            sc.cfg.features = with ? SKY_PLANETS | SKY_SUN : SKY_SUN;
            sc.params.cover = 0.0f;
            sc.has_observer = 1;
            sc.observer = o;
            sc.w = sc.h = 256;
            sc.fov = fovs[k];
            sc.yaw = v->place.az_deg;
            sc.pitch = v->place.alt_deg;
            image im;
            if (render_scene(&sc, 0, SKY_GL_AUTO, &im)) {
                CHECK(0, "render failed");
                return;
            }
            double bx, by;
            peak[with] = image_blob(&im, 128.0, 128.0, 2, &bx, &by);
            image_free(&im);
        }
        step[k] = 255.0 * (peak[1] - peak[0]);
    }
    NOTE("Venus (V %.2f) in the afternoon sky adds %.1f 8-bit levels through 5 degrees, %.1f through 60", v->vmag,
         step[0], step[1]);
    CHECK(step[0] >= 3.0, "Venus shows through a 5-degree view (%.1f levels; the dither moves +-1)", step[0]);
    CHECK(step[1] < 0.5 * step[0], "and far less through a 60-degree one (%.1f levels)", step[1]);
}

/* SKY_PLANETS is a layer of its own: without it nothing is created; with
 * it one program and a 180-byte buffer, and at noon with every planet
 * down, no draw. */
TEST(planets_layer_costs)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_STARS;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "fixture");
        return;
    }
    sky_stats without, with;
    sky_layer_stats planets_without, planets;
    sky_get_stats(f.s, &without);
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_PLANETS, &planets_without) == SKY_OK, "the planets' row");
    fixture_close(&f);
    cfg.features = SKY_STARS | SKY_PLANETS;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "fixture");
        return;
    }
    sky_get_stats(f.s, &with);
    CHECK(sky_get_layer_stats(f.s, SKY_LAYER_PLANETS, &planets) == SKY_OK, "the planets' row");
    CHECK(!planets_without.enabled && planets_without.bytes == 0, "no planets layer without the feature");
    CHECK(planets.enabled && planets.bytes == 180, "five points of nine floats (%zu bytes)", planets.bytes);
    CHECK(with.programs == without.programs + 1 && with.buffers == without.buffers + 1,
          "one program and one buffer more (%d/%d programs, %d/%d buffers)", with.programs, without.programs,
          with.buffers, without.buffers);
    /* an hour of 2023-06-04 with every planet below the horizon: nothing
     * to draw; one with Venus up at night: drawn */
    int down_hour = -1, venus_hour = -1;
    for (int h = 0; h < 24; h++) {
        sky_observer o = observer_at(2023, 6, 4, h, 0);
        sky_astronomy a;
        if (sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) != SKY_OK) continue;
        int up = 0;
        for (int i = 0; i < SKY_PLANET_COUNT; i++) up += a.planets[i].place.alt_deg > 0.0;
        if (!up && down_hour < 0) down_hour = h;
        if (a.sun.alt_deg < -12.0 && a.planets[SKY_PLANET_VENUS].place.alt_deg > 5.0) venus_hour = h;
    }
    CHECK(down_hour >= 0 && venus_hour >= 0, "an hour with every planet down (%d), one with Venus up at night (%d)",
          down_hour, venus_hour);
    float view[16], proj[16];
    sky_cli_camera_at(270.0, 30.0, 60.0, 64, 64, view, proj);
    for (int k = 0; k < 2; k++) {
        sky_observer o = observer_at(2023, 6, 4, k ? venus_hour : down_hour, 0);
        sky_set_observer(f.s, &o);
        sky_draw(f.s, view, proj);
        CHECK(sky_get_layer_stats(f.s, SKY_LAYER_PLANETS, &planets) == SKY_OK && planets.drawn == k,
              "%s: planets drawn %d", k ? "Venus up" : "every planet down", planets.drawn);
    }
    fixture_close(&f);
}

/* The layer keeps a planet's geocentric place for 43 s of the clock and
 * turns it with the sky every frame: what sky_get_astronomy reports (the
 * layer's places) stays within 5" of a fresh computation as the clock
 * runs in steps of 5 s, and within 1e-9 degrees right after a jump. */
TEST(planets_layer_follows_the_clock)
{
    sky_config cfg;
    memset(&cfg, 0, sizeof cfg);
    cfg.features = SKY_PLANETS;
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, &cfg)) {
        CHECK(0, "fixture");
        return;
    }
    sky_observer o = observer_at(2023, 3, 1, 17, 45);
    double worst = 0.0, worst_jump = 0.0;
    for (int k = 0; k < 60; k++) {
        o.julian_day_utc += (k % 20 == 0 ? 3.7 : 5.0 / 86400.0); /* a jump every 20 steps */
        sky_set_observer(f.s, &o);
        sky_astronomy layer, fresh;
        sky_get_astronomy(f.s, &layer);
        sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &fresh, NULL, 0);
        for (int p = 0; p < SKY_PLANET_COUNT; p++) {
            double u[3], v[3];
            sky_horizon_vector(layer.planets[p].place.alt_deg * DEG, layer.planets[p].place.az_deg * DEG, u);
            sky_horizon_vector(fresh.planets[p].place.alt_deg * DEG, fresh.planets[p].place.az_deg * DEG, v);
            double e = angle_between(u, v) * ARCSEC_PER_RAD;
            if (k % 20 == 0)
                worst_jump = fmax(worst_jump, e);
            else
                worst = fmax(worst, e);
        }
    }
    fixture_close(&f);
    NOTE("the layer's places against fresh ones: %.3f\" as the clock runs, %.2g\" after a jump", worst, worst_jump);
    CHECK(worst <= 5.0, "%.3f\" while the clock runs (limit 5\")", worst);
    CHECK(worst_jump <= 1e-3, "%.2g\" after a jump", worst_jump);
}
