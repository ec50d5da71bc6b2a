/*
 * Hillaire's LUT atmosphere, the CPU builder (sky/atmosphere/hillaire_cpu.c):
 * its transmittance against an independent quadrature and the reference,
 * its sky against the spectral reference, convergence with table size,
 * finiteness over hostile inputs, and build times.
 */
#include "test.h"
#include "atmosphere/hillaire.h"
#include "atmosphere/reference.h"
#include "atmosphere/spectrum.h"
#include "sky_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static sky_atmosphere_params earth(void)
{
    sky_atmosphere_params a;
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_EARTH, &a);
    return a;
}

/* Hillaire 2020's own constants (AOD 0.0053): what the tables' numerics
 * were first held to */
static sky_atmosphere_params hillaire_2020(void)
{
    sky_atmosphere_params a;
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_HILLAIRE_2020, &a);
    return a;
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

/* elevation el, azimuth az (degrees from +x toward +z), +y up */
static void dir_at(double el, double az, double d[3])
{
    double e = el * M_PI / 180.0, a = az * M_PI / 180.0;
    d[0] = cos(e) * cos(a);
    d[1] = sin(e);
    d[2] = cos(e) * sin(a);
}

static double luminance(const double rgb[3])
{
    return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

static int build_all(sky_hillaire_tables *t, const sky_atmosphere_params *a, const sky_hillaire_settings *s,
                     double alt_km, double sun_mu)
{
    char err[256];
    if (sky_hillaire_init(t, a, s, err, sizeof err) != 0) {
        printf("    init: %s\n", err);
        return -1;
    }
    sky_hillaire_build_transmittance(t);
    sky_hillaire_build_multiscatter(t);
    sky_hillaire_build_skyview(t, alt_km, sun_mu);
    return 0;
}

/* ---- 1. transmittance ------------------------------------------------------------ */

/* Optical depth from radius r along mu to the top at the description's
 * own 680/550/440 nm coefficients, by the composite midpoint rule on a
 * fine grid closing quadratically onto the ray's lowest point: an
 * integration independent of the builder's. */
static void tau_quadrature(const sky_atmosphere_params *a, double r, double mu, double tau[3])
{
    double R = a->planet_radius_km, Rt = a->top_radius_km;
    double L = -r * mu + sqrt(fmax(0.0, r * r * (mu * mu - 1.0) + Rt * Rt));
    double tl = fmin(fmax(-r * mu, 0.0), L);
    double col[3] = {0, 0, 0};
    const int n = 6000;
    for (int side = 0; side < 2; side++) {
        double len = side ? L - tl : tl;
        if (!(len > 0.0)) continue;
        for (int k = 0; k < n; k++) {
            /* t = tl -/+ len s^2 with s at the midpoints: dt = 2 len s ds */
            double s = (k + 0.5) / n, ds = 1.0 / n;
            double t = side ? tl + len * s * s : tl - len * s * s;
            double w = 2.0 * len * s * ds;
            double rr = sqrt(fmax(0.0, r * r + 2.0 * r * mu * t + t * t));
            double h = fmax(rr - R, 0.0);
            double o = 1.0 - fabs(h - a->ozone_peak_km) / a->ozone_half_width_km;
            col[0] += w * exp(-h / a->rayleigh_scale_height_km);
            col[1] += w * exp(-h / a->mie_scale_height_km);
            col[2] += w * (o > 0.0 ? o : 0.0);
        }
    }
    for (int c = 0; c < 3; c++)
        tau[c] = a->rayleigh_scattering[c] * col[0] + a->mie_extinction[c] * col[1] + a->ozone_absorption[c] * col[2];
}

TEST(hillaire_transmittance_table)
{
    /* the table's interpolation on Hillaire's constants, whose bounds are
     * below; the default Earth's denser aerosol near the ground steepens
     * the grazing columns (1.2 % where tau < 7, 16 % at grazing) */
    sky_atmosphere_params a = hillaire_2020();
    sky_hillaire_tables t;
    char err[256];
    CHECK(sky_hillaire_init(&t, &a, NULL, err, sizeof err) == 0, "init: %s", err);
    sky_hillaire_build_transmittance(&t);
    double R = a.planet_radius_km, Rt = a.top_radius_km;

    /* the table's own values in 0..1 */
    int n = t.settings.transmittance_width * t.settings.transmittance_height * 3, in01 = 1;
    for (int i = 0; i < n; i++)
        if (!(t.transmittance[i] >= 0.0f && t.transmittance[i] <= 1.0f)) in01 = 0;
    CHECK(in01, "a transmittance texel outside 0..1");

    /* the test's quadrature agrees with the spectral reference at the two
     * nodes the reference samples (680 nm = sample 14, 440 nm = sample 2) */
    {
        double d[3], tr[SKY_REF_WAVELENGTHS], tau[3], worst = 0.0;
        for (int e = 0; e < 4; e++) {
            const double el[4] = {90.0, 20.0, 3.0, 0.3};
            dir_at(el[e], 0.0, d);
            sky_ref_transmittance(&a, 1.0, d, tr);
            tau_quadrature(&a, R + 1.0, d[1], tau);
            worst = fmax(worst, fabs(exp(-tau[0]) / tr[14] - 1.0));
            worst = fmax(worst, fabs(exp(-tau[2]) / tr[2] - 1.0));
        }
        NOTE("test quadrature vs sky_ref_transmittance at 680/440 nm: max relative difference %.2e", worst);
        CHECK(worst < 1e-4, "the test's quadrature disagrees with the reference: %g", worst);
    }

    /* the lookup against the quadrature: altitudes ground..top, mu from
     * the geometric horizon (grazing) to the zenith */
    const double alts[] = {0.0, 0.3, 1.5, 5.0, 12.0, 25.0, 45.0, 70.0, 99.5};
    const double fr[] = {0.0, 1e-4, 1e-3, 4e-3, 0.015, 0.04, 0.1, 0.25, 0.5, 0.75, 1.0};
    double worst_thin = 0.0, worst_tau = 0.0, worst_tau7 = 0.0, worst_abs = 0.0;
    for (size_t i = 0; i < sizeof alts / sizeof alts[0]; i++) {
        double r = R + alts[i];
        double mu_h = -sqrt(fmax(0.0, r * r - R * R)) / r;
        for (size_t k = 0; k < sizeof fr / sizeof fr[0]; k++) {
            double mu = mu_h + (1.0 - mu_h) * fr[k];
            if (k == 0) mu += 1e-9; /* just above the horizon: a ray to the top */
            double rgb[3], tau[3];
            sky_hillaire_transmittance(&t, r, mu, rgb);
            tau_quadrature(&a, r, mu, tau);
            for (int c = 0; c < 3; c++) {
                double ref = exp(-tau[c]);
                worst_abs = fmax(worst_abs, fabs(rgb[c] - ref));
                if (tau[c] < 1.0) worst_thin = fmax(worst_thin, fabs(rgb[c] / ref - 1.0));
                /* optical depth recovered from the table, relative */
                if (rgb[c] > 1e-30) {
                    double e = fabs(-log(rgb[c]) - tau[c]) / fmax(tau[c], 1e-3);
                    worst_tau = fmax(worst_tau, e);
                    if (tau[c] < 7.0) worst_tau7 = fmax(worst_tau7, e);
                }
            }
        }
        /* below the horizon: the ray meets the ground */
        double rgb[3];
        sky_hillaire_transmittance(&t, r, mu_h - 1e-3, rgb);
        CHECK(rgb[0] == 0.0 && rgb[1] == 0.0 && rgb[2] == 0.0, "a ray into the ground has T %g", rgb[0]);
    }
    NOTE("transmittance lookup vs quadrature: max relative error %.3f %% where tau < 1; optical depth from the "
         "table, max relative error %.3f %% where tau < 7 (T > 1e-3), %.3f %% over all (r, mu) incl. grazing; max "
         "absolute error %.2e",
         100.0 * worst_thin, 100.0 * worst_tau7, 100.0 * worst_tau, worst_abs);
    /* The bounds are what bilinear interpolation of a 256 x 64 table
     * allows: at the grazing columns T changes by orders of magnitude
     * between neighbouring texels (a 1024-wide table halves the error;
     * more steps do not change it). */
    CHECK(worst_thin < 0.005, "transmittance off by %.3f %% where tau < 1", 100.0 * worst_thin);
    CHECK(worst_tau7 < 0.01, "optical depth off by %.3f %% where tau < 7", 100.0 * worst_tau7);
    CHECK(worst_tau < 0.04, "optical depth off by %.3f %% at grazing", 100.0 * worst_tau);
    CHECK(worst_abs < 0.005, "transmittance off by %.4f absolute", worst_abs);

    /* monotone along a ray: the transmittance to the top can only grow as
     * the start moves along the ray */
    int mono = 1;
    for (int e = 0; e < 12 && mono; e++) {
        double r = R + 0.01 + 9.0 * e, mu_h = -sqrt(r * r - R * R) / r;
        for (int q = 0; q < 8; q++) {
            double mu = q == 0 ? mu_h + 1e-6 : mu_h + (1.0 - mu_h) * q / 8.0, prev[3] = {-1, -1, -1};
            double L = -r * mu + sqrt(fmax(0.0, r * r * (mu * mu - 1.0) + Rt * Rt));
            for (int s = 0; s <= 200; s++) {
                double tt = L * s / 200.0, rr = sqrt(r * r + 2.0 * r * mu * tt + tt * tt);
                double mm = (r * mu + tt) / rr, rgb[3];
                if (rr > Rt) rr = Rt;
                sky_hillaire_transmittance(&t, rr, mm, rgb);
                for (int c = 0; c < 3; c++) {
                    /* on the grazing rays high up the true rise between
                     * rows (~1e-5) is below the 40-step quadrature's
                     * error (~1e-4 relative in T, 3e-5 in tau): monotone
                     * to that, and to 1e-7 absolute */
                    if (rgb[c] < prev[c] * (1.0 - 5e-4) - 1e-7) mono = 0;
                    prev[c] = rgb[c];
                }
            }
        }
    }
    CHECK(mono, "transmittance falls somewhere along a ray");

    /* above the top: T is the value at the entry point, 1 if it misses */
    double rgb[3], rgb2[3];
    sky_hillaire_transmittance(&t, Rt + 50.0, 1.0, rgb);
    CHECK(rgb[0] == 1.0 && rgb[2] == 1.0, "a ray from above the top into space: %g", rgb[0]);
    sky_hillaire_transmittance(&t, Rt + 50.0, -1.0, rgb);
    CHECK(rgb[0] == 0.0, "straight down from above the top meets the ground: %g", rgb[0]);
    double tt = 50.0, mu_t = -0.999; /* enters well away from the ground */
    double rr = Rt + tt;
    double disc = rr * rr * (mu_t * mu_t - 1.0) + Rt * Rt;
    (void)disc;
    sky_hillaire_transmittance(&t, rr, -0.2, rgb);
    {
        double b = rr * -0.2, d0 = -b - sqrt(b * b - (rr * rr - Rt * Rt));
        double mu2 = (rr * -0.2 + d0) / Rt;
        sky_hillaire_transmittance(&t, Rt, mu2, rgb2);
        CHECK(fabs(rgb[1] - rgb2[1]) < 1e-9, "above the top: %g vs the entry point %g", rgb[1], rgb2[1]);
    }
    sky_hillaire_free(&t);
}

/* ---- 2. the sky against the reference ----------------------------------------------- */

/* The tables against the reference for one description: the mean
 * |relative luminance error| at four suns within limit. */
static void sky_vs_reference(const sky_atmosphere_params *atm, const char *name, double limit)
{
    /* the reference renders the description's spectrum; the tables take
     * its channel means, as sky_create has them */
    sky_atmosphere_params a = *atm, rgb;
    sky_atmosphere_effective(atm, &rgb);
    double sun_xyz[3], sun_rgb[3];
    sky_spectrum_sun_xyz(sun_xyz);
    sky_xyz_to_linear_srgb(sun_xyz, sun_rgb);
    const double sun_el[4] = {60.0, 30.0, 10.0, 2.0};
    const double els[] = {1.0, 3.0, 8.0, 15.0, 30.0, 50.0, 70.0, 90.0};
    const double azs[] = {0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0};
    sky_ref_options o;
    memset(&o, 0, sizeof o);
    o.view_segments = 128;
    o.sun_segments = 64;
    o.paths = 96;
    double t0 = now_s();
    double all_mean = 0.0;
    for (int s = 0; s < 4; s++) {
        sky_hillaire_tables t;
        double sun[3];
        dir_at(sun_el[s], 0.0, sun);
        if (build_all(&t, &rgb, NULL, 0.0, sun[1]) != 0) {
            CHECK(0, "build failed");
            return;
        }
        double sum = 0.0, worst = 0.0, sum_signed = 0.0, worst_el = 0, worst_az = 0;
        int count = 0;
        for (size_t e = 0; e < sizeof els / sizeof els[0]; e++) {
            for (size_t k = 0; k < sizeof azs / sizeof azs[0]; k++) {
                if (els[e] == 90.0 && k > 0) break; /* the zenith once */
                double v[3], tab[3];
                dir_at(els[e], azs[k], v);
                sky_ref_result ref;
                if (sky_ref_radiance(&a, 0.0, v, sun, &o, &ref) != 0) {
                    CHECK(0, "reference failed");
                    continue;
                }
                sky_hillaire_sky(&t, v, sun, tab);
                for (int c = 0; c < 3; c++) tab[c] *= sun_rgb[c];
                double yr = luminance(ref.rgb), yt = luminance(tab);
                double rel = (yt - yr) / yr;
                sum += fabs(rel);
                sum_signed += rel;
                if (fabs(rel) > worst) {
                    worst = fabs(rel);
                    worst_el = els[e];
                    worst_az = azs[k];
                }
                count++;
            }
        }
        double mean = sum / count;
        all_mean += mean / 4.0;
        NOTE("sun %4.0f deg: %d directions, mean |relative luminance error| %.2f %% (signed mean %+.2f %%), max "
             "%.2f %% at el %.0f az %.0f",
             sun_el[s], count, 100.0 * mean, 100.0 * sum_signed / count, 100.0 * worst, worst_el, worst_az);
        CHECK(mean <= limit, "%s, sun %.0f deg: mean luminance error %.2f %% > %.0f %%", name, sun_el[s], 100.0 * mean,
              100.0 * limit);
        sky_hillaire_free(&t);
    }
    NOTE("%s: mean over the four suns %.2f %%; %.1f s with the reference", name, 100.0 * all_mean, now_s() - t0);
}

/* Hillaire's constants within issue 6's 5 % at each sun (1.9 % over the
 * four, 2.7 % at sun 30 deg); the default Earth, whose aerosol is 16
 * times denser, within 6 % at each sun on this coarser grid (3.4 % over
 * the four, 4.1 % at sun 10 deg; sky-bench's equal-area grid, the issue's
 * measure, is docs/benchmarks.md's): a forward aerosol's multiple scattering is
 * the harder to carry. Isotropic beyond the second order, as Hillaire has
 * it, the table erred by 5.7 % (Hillaire's constants, sun 60 deg) and 5.4
 * % (Earth, sun 10 deg). */
SLOW_TEST(hillaire_sky_vs_reference)
{
    sky_atmosphere_params h = hillaire_2020(), e = earth();
    sky_vs_reference(&h, "hillaire-2020", 0.05);
    sky_vs_reference(&e, "earth", 0.06);
}

/* ---- 3. convergence ---------------------------------------------------------------- */

static sky_hillaire_settings scaled_settings(double f)
{
    sky_hillaire_settings s;
    s.transmittance_width = (int)(256 * f);
    s.transmittance_height = (int)(64 * f);
    s.transmittance_steps = (int)(40 * f);
    s.multiscatter_size = (int)(32 * f);
    s.multiscatter_directions = (int)(64 * f);
    s.multiscatter_steps = (int)(20 * f);
    s.skyview_width = (int)(192 * f);
    s.skyview_height = (int)(108 * f);
    s.skyview_steps = (int)(30 * f);
    return s;
}

/* Mean relative luminance difference of two sky-view builds over a grid
 * of directions above and below the horizon. */
static double sky_difference(const sky_hillaire_tables *x, const sky_hillaire_tables *y, const double sun[3])
{
    double sum = 0.0;
    int n = 0;
    for (int e = -20; e <= 90; e += 2) {
        for (int k = 0; k <= 180; k += 10) {
            double v[3], p[3], q[3];
            dir_at(e + 0.37, k + 0.41, v);
            sky_hillaire_sky(x, v, sun, p);
            sky_hillaire_sky(y, v, sun, q);
            double lq = luminance(q);
            if (lq > 0.0) {
                sum += fabs(luminance(p) / lq - 1.0);
                n++;
            }
        }
    }
    return n ? sum / n : 0.0;
}

SLOW_TEST(hillaire_error_falls_with_table_size)
{
    sky_atmosphere_params a = earth();
    double sun[3];
    dir_at(10.0, 0.0, sun);
    sky_hillaire_tables hi;
    sky_hillaire_settings shi = scaled_settings(2.0);
    double t0 = now_s();
    if (build_all(&hi, &a, &shi, 0.0, sun[1]) != 0) {
        CHECK(0, "high-resolution build failed");
        return;
    }
    const double f[3] = {0.25, 0.5, 1.0};
    double err[3];
    for (int i = 0; i < 3; i++) {
        sky_hillaire_tables t;
        sky_hillaire_settings s = scaled_settings(f[i]);
        if (build_all(&t, &a, &s, 0.0, sun[1]) != 0) {
            CHECK(0, "build failed");
            sky_hillaire_free(&hi);
            return;
        }
        err[i] = sky_difference(&t, &hi, sun);
        sky_hillaire_free(&t);
    }
    NOTE("sun 10 deg, mean relative luminance difference to the 2x build (sizes and steps x2): x0.25 %.3f %%, "
         "x0.5 %.3f %%, x1 (default) %.3f %% (%.1f s)",
         100.0 * err[0], 100.0 * err[1], 100.0 * err[2], now_s() - t0);
    CHECK(err[1] < err[0] && err[2] < err[1], "the error does not fall: %g %g %g", err[0], err[1], err[2]);
    CHECK(err[2] < 0.01, "the default build is %.2f %% from the 2x build", 100.0 * err[2]);
    sky_hillaire_free(&hi);
}

/* ---- 4. finite everywhere ------------------------------------------------------------- */

static int table_ok(const float *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (!isfinite(p[i]) || p[i] < 0.0f) return 0;
    return 1;
}

static int lookups_ok(const sky_hillaire_tables *t, const double sun[3])
{
    double R = t->atm.planet_radius_km, Rt = t->atm.top_radius_km;
    const double radii[] = {0.0, R - 1.0, R, R + 1e-3, 0.5 * (R + Rt), Rt, Rt + 100.0, 1e300, -1.0, NAN, INFINITY};
    for (size_t i = 0; i < sizeof radii / sizeof radii[0]; i++) {
        for (int k = -12; k <= 12; k++) {
            double mu = k / 10.0, rgb[3]; /* includes |mu| > 1 */
            sky_hillaire_transmittance(t, radii[i], mu, rgb);
            for (int c = 0; c < 3; c++)
                if (!isfinite(rgb[c]) || rgb[c] < 0.0 || rgb[c] > 1.0) return 0;
            sky_hillaire_multiscatter(t, radii[i], mu, rgb);
            for (int c = 0; c < 3; c++)
                if (!isfinite(rgb[c]) || rgb[c] < 0.0) return 0;
        }
    }
    for (int e = -90; e <= 90; e += 5) {
        for (int k = 0; k < 360; k += 45) {
            double v[3], rgb[3];
            dir_at(e, k, v);
            sky_hillaire_sky(t, v, sun, rgb);
            for (int c = 0; c < 3; c++)
                if (!isfinite(rgb[c]) || rgb[c] < 0.0) return 0;
        }
    }
    return 1;
}

TEST(hillaire_finite_everywhere)
{
    sky_hillaire_settings s = {16, 8, 8, 8, 16, 8, 16, 12, 8};
    sky_atmosphere_params atms[8];
    const char *names[8] = {"earth", "hazy", "mars", "g +0.999", "g -0.999", "density x1e-3", "density x1e3",
                            "albedo 1"};
    atms[0] = earth();
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_HAZY, &atms[1]);
    sky_atmosphere_get_preset(SKY_ATMOSPHERE_PRESET_MARS, &atms[2]);
    atms[3] = earth();
    atms[3].mie_g = 0.999f;
    atms[4] = earth();
    atms[4].mie_g = -0.999f;
    atms[5] = earth();
    atms[6] = earth();
    for (int c = 0; c < 3; c++) {
        atms[5].rayleigh_scattering[c] *= 1e-3f;
        atms[5].mie_scattering[c] *= 1e-3f;
        atms[5].mie_extinction[c] *= 1e-3f;
        atms[5].ozone_absorption[c] *= 1e-3f;
        atms[6].rayleigh_scattering[c] = fminf(atms[6].rayleigh_scattering[c] * 1e3f, 10.0f);
        atms[6].mie_scattering[c] = fminf(atms[6].mie_scattering[c] * 1e3f, 10.0f);
        atms[6].mie_extinction[c] = fminf(atms[6].mie_extinction[c] * 1e3f, 10.0f);
        atms[6].ozone_absorption[c] = fminf(atms[6].ozone_absorption[c] * 1e3f, 10.0f);
    }
    atms[7] = earth();
    atms[7].ground_albedo[0] = atms[7].ground_albedo[1] = atms[7].ground_albedo[2] = 1.0f;
    atms[7].ozone_absorption[0] = atms[7].ozone_absorption[1] = atms[7].ozone_absorption[2] = 0.0f;
    for (int c = 0; c < 3; c++) atms[7].mie_extinction[c] = atms[7].mie_scattering[c];
    const double alts[5] = {0.0, 0.001, 8.0, 100.0, 250.0};
    int bad = 0;
    for (int i = 0; i < 8; i++) {
        char err[256];
        CHECK(sky_atmosphere_check(&atms[i], err, sizeof err) == SKY_OK, "%s: %s", names[i], err);
        sky_hillaire_tables t;
        CHECK(sky_hillaire_init(&t, &atms[i], &s, err, sizeof err) == 0, "%s: %s", names[i], err);
        sky_hillaire_build_transmittance(&t);
        sky_hillaire_build_multiscatter(&t);
        int ok = table_ok(t.transmittance, 16 * 8 * 3) && table_ok(t.multiscatter, 8 * 8 * 3);
        for (int k = 0; k < 5; k++) {
            /* sun cosines -1..1: every 0.5 deg of the first preset, 6 deg
             * of the others (small tables keep each build cheap) */
            int step = i == 0 && k == 0 ? 1 : 12;
            for (int q = 0; q <= 360; q += step) {
                double el = -90.0 + 0.5 * q, sun[3];
                dir_at(el, 0.0, sun);
                sky_hillaire_build_skyview(&t, alts[k], sun[1]);
                if (!table_ok(t.skyview, 16 * 12 * 3) || (q % 60 == 0 && !lookups_ok(&t, sun))) {
                    if (ok) printf("    %s: altitude %g km, sun %g deg: not finite or negative\n", names[i], alts[k], el);
                    ok = 0;
                }
            }
        }
        if (!ok) bad++;
        CHECK(ok, "%s: a table or lookup is not finite and non-negative", names[i]);
        sky_hillaire_free(&t);
    }
    (void)bad;
}

/* ---- 5. rebuilds ------------------------------------------------------------------------ */

/* A table set rebuilt gives the same bits: the builds keep no state of
 * their own between calls (the sky-view table is rebuilt as the sun
 * moves, and frames must be functions of their inputs). The build times
 * are noted, not held: timing belongs in sky-bench (--only-atmosphere). */
TEST(hillaire_rebuilds_identical)
{
    sky_atmosphere_params a = earth();
    sky_hillaire_tables t;
    char err[256];
    CHECK(sky_hillaire_init(&t, &a, NULL, err, sizeof err) == 0, "init: %s", err);
    const sky_hillaire_settings *st = &t.settings;
    size_t sizes[3] = {(size_t)st->transmittance_width * (size_t)st->transmittance_height * 3u,
                       (size_t)st->multiscatter_size * (size_t)st->multiscatter_size * 3u,
                       (size_t)st->skyview_width * (size_t)st->skyview_height * 3u};
    float *first[3] = {NULL, NULL, NULL};
    double best[3] = {1e9, 1e9, 1e9};
    int differ = 0;
    for (int rep = 0; rep < 3; rep++) {
        double t0 = now_s();
        sky_hillaire_build_transmittance(&t);
        double t1 = now_s();
        sky_hillaire_build_multiscatter(&t);
        double t2 = now_s();
        sky_hillaire_build_skyview(&t, 0.0, sin(10.0 * M_PI / 180.0));
        double t3 = now_s();
        best[0] = fmin(best[0], t1 - t0);
        best[1] = fmin(best[1], t2 - t1);
        best[2] = fmin(best[2], t3 - t2);
        const float *tables[3] = {t.transmittance, t.multiscatter, t.skyview};
        for (int k = 0; k < 3; k++) {
            if (rep == 0) {
                first[k] = malloc(sizes[k] * sizeof(float));
                if (first[k]) memcpy(first[k], tables[k], sizes[k] * sizeof(float));
            } else if (first[k]) {
                differ += memcmp(first[k], tables[k], sizes[k] * sizeof(float)) != 0;
            }
        }
        /* in between, a sky-view table for another sun and altitude */
        sky_hillaire_build_skyview(&t, 3.0, sin(-4.0 * M_PI / 180.0));
    }
    NOTE("default build, best of 3 (single thread): transmittance 256x64x40 %.1f ms, multiscatter 32x32x64x20 %.1f ms, "
         "sky-view 192x108x30 %.1f ms", 1e3 * best[0], 1e3 * best[1], 1e3 * best[2]);
    CHECK(first[0] && first[1] && first[2], "out of memory");
    CHECK(differ == 0, "%d rebuilt tables differ from the first build", differ);
    for (int k = 0; k < 3; k++) free(first[k]);
    sky_hillaire_free(&t);
}

/* ---- 6. bad input ---------------------------------------------------------------------- */

TEST(hillaire_bad_input)
{
    sky_atmosphere_params a = earth(), zero;
    memset(&zero, 0, sizeof zero);
    sky_hillaire_tables t;
    char err[256];
    CHECK(sky_hillaire_init(NULL, &a, NULL, err, sizeof err) == -1 && err[0], "NULL tables accepted");
    CHECK(sky_hillaire_init(&t, NULL, NULL, err, sizeof err) == -1 && err[0], "NULL atmosphere accepted");
    CHECK(t.transmittance == NULL && t.multiscatter == NULL && t.skyview == NULL, "a failed init left tables");
    sky_hillaire_free(&t);
    sky_hillaire_free(NULL);
    /* zero = Earth, NULL settings = defaults */
    CHECK(sky_hillaire_init(&t, &zero, NULL, err, sizeof err) == 0, "zero atmosphere: %s", err);
    CHECK(t.atm.planet_radius_km == a.planet_radius_km && t.atm.mie_g == a.mie_g, "zero is not Earth");
    CHECK(t.settings.transmittance_width == 256 && t.settings.transmittance_height == 64 &&
              t.settings.transmittance_steps == 40 && t.settings.multiscatter_size == 32 &&
              t.settings.multiscatter_directions == 64 && t.settings.multiscatter_steps == 20 &&
              t.settings.skyview_width == 192 && t.settings.skyview_height == 108 && t.settings.skyview_steps == 30,
          "defaults not filled in");
    sky_hillaire_free(&t);
    CHECK(t.transmittance == NULL, "free left a pointer");
    /* each setting out of range on its own */
    for (int f = 0; f < 9; f++) {
        const int bad_values[4] = {-1, 3, 1025, 257};
        for (int b = 0; b < 4; b++) {
            sky_hillaire_settings s;
            memset(&s, 0, sizeof s);
            int *field = &s.transmittance_width + f;
            int is_steps = f == 2 || f == 4 || f == 5 || f == 8;
            int v = bad_values[b];
            if (is_steps && v == 3) continue; /* 3 steps are fine */
            if (!is_steps && v == 257) continue; /* a 257 table is fine */
            *field = v;
            CHECK(sky_hillaire_init(&t, &a, &s, err, sizeof err) == -1 && err[0], "setting %d = %d accepted", f, v);
            sky_hillaire_free(&t);
        }
    }
    /* a bad atmosphere is named */
    sky_atmosphere_params b = a;
    b.mie_g = 1.5f;
    CHECK(sky_hillaire_init(&t, &b, NULL, err, sizeof err) == -1 && strstr(err, "mie_g"), "bad g: '%s'", err);
    b = a;
    b.top_radius_km = NAN;
    CHECK(sky_hillaire_init(&t, &b, NULL, err, sizeof err) == -1 && err[0], "NaN radius accepted");
    /* builds and lookups on an unbuilt or NULL object do nothing harmful */
    sky_hillaire_build_transmittance(NULL);
    sky_hillaire_build_multiscatter(NULL);
    sky_hillaire_build_skyview(NULL, 0.0, 1.0);
    double rgb[3] = {1, 1, 1}, v[3] = {0, 1, 0};
    sky_hillaire_sky(NULL, v, v, rgb);
    CHECK(rgb[0] == 0.0, "lookup on NULL: %g", rgb[0]);
    /* the horizon of an observer at altitude is the geometric one: v = 0.5
     * (texel-centre mapped) at the dip angle acos(R / r) below level */
    CHECK(sky_hillaire_init(&t, &a, NULL, err, sizeof err) == 0, "init: %s", err);
    double R = a.planet_radius_km, r = R + 10.0, dip = acos(R / r), u, vv;
    sky_hillaire_skyview_uv(&t, -sin(dip), 1.0, 10.0, &u, &vv);
    /* the square root at the horizon turns rounding of 1e-16 into 1e-8 */
    CHECK(fabs(vv - 0.5) < 1e-6, "the horizon at 10 km maps to v = %.9f", vv);
    sky_hillaire_skyview_uv(&t, 1.0, 1.0, 10.0, &u, &vv);
    CHECK(fabs(u - 0.5 / 192) < 1e-12 && fabs(vv - 0.5 / 108) < 1e-12, "zenith toward the sun: %g %g", u, vv);
    sky_hillaire_skyview_uv(&t, -1.0, -1.0, 10.0, &u, &vv);
    CHECK(fabs(u - (1.0 - 0.5 / 192)) < 1e-12 && fabs(vv - (1.0 - 0.5 / 108)) < 1e-12, "nadir: %g %g", u, vv);
    sky_hillaire_free(&t);
}
