/*
 * Astronomy tests against ERFA (the IAU SOFA algorithms) as the oracle:
 * our Meeus-class code is never linked to it; only these tests are.
 *
 * The oracle computes the same quantities the independent way: the Earth
 * from eraEpv00, the moon from eraMoon98, stars from eraPmsafe, annual
 * aberration from eraAb, and the whole GCRS -> ITRS rotation (IAU 2006/
 * 2000A precession-nutation and the Earth rotation angle) from eraC2t06a;
 * the observer from the WGS84 ellipsoid (eraGd2gc). Positions are
 * compared without refraction (alt_geometric), which is a model choice,
 * not a computation; refraction is tested on its own.
 */
#include "test.h"
#include "sky_internal.h"

#include <erfa.h>
#include <erfam.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846
#define DEG (PI / 180.0)
#define C_AU_PER_DAY (ERFA_CMPS * 86400.0 / ERFA_DAU)

/* ---- the oracle ------------------------------------------------------------------- */

typedef struct oracle {
    double jd_ut, jd_tt;
    double rc2t[3][3];
    double earth_h[2][3], earth_b[2][3]; /* heliocentric / barycentric pv, au, au/day */
    double obs_itrs_km[3];
    double lat, lon;
} oracle;

static void oracle_init(oracle *o, double jd_ut, double delta_t, double lat, double lon, double h_m)
{
    o->jd_ut = jd_ut;
    o->jd_tt = jd_ut + delta_t / 86400.0;
    o->lat = lat;
    o->lon = lon;
    eraC2t06a(2400000.5, o->jd_tt - 2400000.5, 2400000.5, jd_ut - 2400000.5, 0.0, 0.0, o->rc2t);
    eraEpv00(2400000.5, o->jd_tt - 2400000.5, o->earth_h, o->earth_b);
    double xyz[3];
    eraGd2gc(ERFA_WGS84, lon, lat, h_m, xyz);
    for (int i = 0; i < 3; i++) o->obs_itrs_km[i] = xyz[i] / 1000.0;
}

/* Topocentric geometric altitude and azimuth of a GCRS geocentric
 * position (km). */
static void oracle_altaz(const oracle *o, const double gcrs_km[3], double *alt, double *az)
{
    double p[3], t[3];
    eraRxp((double(*)[3])o->rc2t, (double *)gcrs_km, p);
    for (int i = 0; i < 3; i++) t[i] = p[i] - o->obs_itrs_km[i];
    double sl = sin(o->lat), cl = cos(o->lat), so = sin(o->lon), co = cos(o->lon);
    double east = -so * t[0] + co * t[1];
    double north = -sl * co * t[0] - sl * so * t[1] + cl * t[2];
    double up = cl * co * t[0] + cl * so * t[1] + sl * t[2];
    *alt = atan2(up, sqrt(east * east + north * north));
    *az = atan2(east, north);
}

/* Apparent direction (GCRS) of a natural direction, annual aberration. */
static void oracle_aberrate(const oracle *o, const double dir[3], double out[3])
{
    double v[3], pn[3];
    for (int i = 0; i < 3; i++) v[i] = o->earth_b[1][i] / C_AU_PER_DAY;
    double bm1 = sqrt(1.0 - eraPdp(v, v));
    double r = eraPm((double *)dir);
    for (int i = 0; i < 3; i++) pn[i] = dir[i] / r;
    eraAb(pn, v, eraPm((double *)o->earth_h[0]), bm1, out);
}

static void oracle_sun(const oracle *o, double gcrs_km[3])
{
    double u[3], a[3];
    for (int i = 0; i < 3; i++) u[i] = -o->earth_h[0][i];
    oracle_aberrate(o, u, a);
    double d = eraPm(u) * ERFA_DAU / 1000.0;
    for (int i = 0; i < 3; i++) gcrs_km[i] = a[i] * d;
}

/* The moon at t - light time, seen from the Earth at t: to first order
 * this is what the annual aberration and light time leave for a body that
 * moves with the Earth. */
static void oracle_moon(const oracle *o, double gcrs_km[3])
{
    double pv[2][3];
    eraMoon98(2400000.5, o->jd_tt - 2400000.5, pv);
    double tau = eraPm(pv[0]) / C_AU_PER_DAY;
    for (int i = 0; i < 3; i++) gcrs_km[i] = (pv[0][i] - pv[1][i] * tau) * ERFA_DAU / 1000.0;
}

static void oracle_star(const oracle *o, const sky_star *s, double gcrs_km[3])
{
    double ra, dec, pmr, pmd, px, rv, cd = cos(s->dec);
    eraPmsafe(s->ra, s->dec, cd > 1e-9 ? s->pm_ra / cd * 1e-3 * ERFA_DAS2R : 0.0, s->pm_dec * 1e-3 * ERFA_DAS2R, 0.0,
              0.0, 2451545.0, 0.0, o->jd_tt, 0.0, &ra, &dec, &pmr, &pmd, &px, &rv);
    double u[3], a[3];
    eraS2c(ra, dec, u);
    oracle_aberrate(o, u, a);
    for (int i = 0; i < 3; i++) gcrs_km[i] = a[i] * 1e15; /* at "infinity" */
}

/* Angle between two horizon places. */
static double sep(double alt1, double az1, double alt2, double az2)
{
    return eraSeps(az1, alt1, az2, alt2);
}

/* Instants and observers: 1000 draws over 1800..2200, pole to pole, with
 * the exact poles, the date line and 0 / 8000 m among them. */
typedef struct draw {
    double jd, lat, lon, h;
} draw;

static void make_draws(draw *d, int n)
{
    unsigned long long x = 0x9E3779B97F4A7C15ull;
    for (int i = 0; i < n; i++) {
        double r[3];
        for (int k = 0; k < 3; k++) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            r[k] = (double)(x >> 11) / 9007199254740992.0;
        }
        d[i].jd = sky_jd_from_calendar(1800, 1, 1, 0, 0, 0) + r[0] * 400.0 * 365.2425;
        d[i].lat = (r[1] * 180.0 - 90.0) * DEG;
        d[i].lon = (r[2] * 360.0 - 180.0) * DEG;
        d[i].h = (i % 2) ? 8000.0 : 0.0;
        if (i % 50 == 0) d[i].lat = 90.0 * DEG;
        if (i % 50 == 1) d[i].lat = -90.0 * DEG;
        if (i % 50 == 2) d[i].lon = 180.0 * DEG;
        if (i % 50 == 3) d[i].lon = -180.0 * DEG;
    }
}

#define DRAWS 1000

/* Worst separation (degrees) of a body over the draws; body 0 sun, 1 moon. */
static double worst_body(int body, double *worst_alt, double *worst_az)
{
    draw d[DRAWS];
    make_draws(d, DRAWS);
    double worst = 0.0;
    *worst_alt = *worst_az = 0.0;
    for (int i = 0; i < DRAWS; i++) {
        sky_astro a;
        sky_astro_observer obs = {d[i].lat, d[i].lon, d[i].h};
        if (sky_astro_compute(d[i].jd, &obs, &a, NULL, 0)) {
            CHECK(0, "astro failed at JD %f", d[i].jd);
            return 1e9;
        }
        oracle o;
        oracle_init(&o, d[i].jd, a.delta_t, d[i].lat, d[i].lon, d[i].h);
        double p[3], alt, az;
        if (body == 0)
            oracle_sun(&o, p);
        else
            oracle_moon(&o, p);
        oracle_altaz(&o, p, &alt, &az);
        const sky_astro_body *b = body == 0 ? &a.sun : &a.moon;
        double s = sep(b->alt_geometric, b->az, alt, az) / DEG;
        if (s > worst) worst = s;
        *worst_alt = fmax(*worst_alt, fabs(b->alt_geometric - alt) / DEG);
        /* azimuth error as an angle on the sky (it is undefined at the zenith) */
        double daz = remainder(b->az - az, 2 * PI) * cos(alt);
        *worst_az = fmax(*worst_az, fabs(daz) / DEG);
    }
    return worst;
}

/* ---- tests ------------------------------------------------------------------------------ */

TEST(astro_time_scales)
{
    /* calendar -> JD against eraCal2jd over a spread of dates */
    int bad = 0;
    for (int y = -1999; y <= 3000; y += 7)
        for (int m = 1; m <= 12; m += 5) {
            double djm0, djm;
            if (eraCal2jd(y, m, 28, &djm0, &djm) < 0) continue; /* ERFA stops at -4799 */
            double ours = sky_jd_from_calendar(y, m, 28, 0, 0, 0.0);
            bad += fabs(ours - (djm0 + djm)) > 1e-9;
            int yy, mm, dd;
            double f;
            sky_calendar_from_jd(ours + 0.25, &yy, &mm, &dd, &f);
            bad += yy != y || mm != m || dd != 28 || fabs(f - 0.25) > 1e-9;
        }
    CHECK(bad == 0, "%d calendar mismatches with eraCal2jd or in the round trip", bad);
    CHECK(sky_jd_from_calendar(2000, 1, 1, 12, 0, 0.0) == 2451545.0, "J2000.0");
    CHECK(fabs(sky_jd_from_unix(0.0) - 2440587.5) < 1e-12, "Unix epoch");
    /* Delta T: published anchor values of the Espenak-Meeus fit, and no
     * jump over a second at its piece boundaries */
    CHECK(fabs(sky_delta_t(sky_jd_from_calendar(2000, 1, 1, 0, 0, 0)) - 63.86) < 0.1, "Delta T 2000: %g",
          sky_delta_t(sky_jd_from_calendar(2000, 1, 1, 0, 0, 0)));
    CHECK(fabs(sky_delta_t(sky_jd_from_calendar(1900, 1, 1, 0, 0, 0)) + 2.79) < 0.2, "Delta T 1900");
    double worst_jump = 0.0;
    const int edges[] = {-500, 500, 1600, 1700, 1800, 1860, 1900, 1920, 1941, 1961, 1986, 2005, 2050, 2150};
    for (size_t i = 0; i < sizeof edges / sizeof edges[0]; i++) {
        double jd = 2451545.0 + (edges[i] - 2000.0) * 365.25;
        worst_jump = fmax(worst_jump, fabs(sky_delta_t(jd + 0.01) - sky_delta_t(jd - 0.01)));
    }
    NOTE("largest Delta T step at a fit boundary: %.2f s", worst_jump);
    CHECK(worst_jump < 5.0, "Delta T fit pieces meet (%.2f s)", worst_jump);
    /* sidereal time against IAU 2006 GMST */
    double worst = 0.0;
    for (int k = 0; k < 200; k++) {
        double jd = 2451545.0 + (k - 100) * 730.5 + 0.37 * k;
        double tt = jd + sky_delta_t(jd) / 86400.0;
        double e = remainder(sky_gmst(jd) - eraGmst06(2400000.5, jd - 2400000.5, 2400000.5, tt - 2400000.5), 2 * PI);
        worst = fmax(worst, fabs(e));
    }
    /* Meeus 12.4 is the IAU 1982 GMST; it drifts from the 2006 one by a
     * fraction of an arcsecond over two centuries */
    NOTE("GMST vs eraGmst06 over 1800-2200: %.3f arcsec", worst / ERFA_DAS2R);
    CHECK(worst < 1.0 * ERFA_DAS2R, "sidereal time within 1 arcsec (%.3f)", worst / ERFA_DAS2R);
}

TEST(astro_sun_vs_erfa)
{
    double da, dz, w = worst_body(0, &da, &dz);
    NOTE("sun, %d instants 1800-2200, pole to pole: max error %.5f deg (alt %.5f, az*cos(alt) %.5f)", DRAWS, w, da, dz);
    CHECK(w <= 0.005, "sun topocentric alt/az max error %.5f deg > 0.005", w);
}

TEST(astro_moon_vs_erfa)
{
    double da, dz, w = worst_body(1, &da, &dz);
    NOTE("moon, %d instants 1800-2200, pole to pole: max error %.5f deg (alt %.5f, az*cos(alt) %.5f)", DRAWS, w, da, dz);
    CHECK(w <= 0.01, "moon topocentric alt/az max error %.5f deg > 0.01", w);
}

TEST(astro_stars_vs_erfa)
{
    sky_catalog cat;
    char err[256];
    if (sky_catalog_load(&cat, err, sizeof err)) {
        CHECK(0, "%s", err);
        return;
    }
    NOTE("catalogue: %d stars, faintest V %.2f", cat.count, cat.stars[cat.count - 1].vmag);
    CHECK(cat.count > 8000, "every star to V 6.5 (%d)", cat.count);
    CHECK(cat.stars[cat.count - 1].vmag <= 6.5f && cat.stars[cat.count - 1].vmag > 6.3f, "magnitude limit %.2f",
          cat.stars[cat.count - 1].vmag);
    draw d[DRAWS];
    make_draws(d, DRAWS);
    double worst = 0.0;
    int worst_hip = 0, compared = 0;
    for (int i = 0; i < DRAWS; i++) {
        sky_astro a;
        sky_astro_observer obs = {d[i].lat, d[i].lon, d[i].h};
        sky_astro_compute(d[i].jd, &obs, &a, NULL, 0);
        oracle o;
        oracle_init(&o, d[i].jd, a.delta_t, d[i].lat, d[i].lon, d[i].h);
        for (int k = 0; k < 8; k++) { /* 8 stars per instant, spread over the list */
            const sky_star *st = &cat.stars[(i * 8 + k) * 7919 % cat.count];
            double alt, alt_geo, az, dir[3], p[3], ealt, eaz;
            sky_astro_star(&a, st, &alt, &alt_geo, &az, dir);
            oracle_star(&o, st, p);
            oracle_altaz(&o, p, &ealt, &eaz);
            double s = sep(alt_geo, az, ealt, eaz) / DEG;
            if (s > worst) worst = s, worst_hip = st->hip;
            compared++;
        }
    }
    /* Arcturus, whose 2.3"/yr proper motion matters over centuries */
    const sky_star *arcturus = sky_catalog_find(&cat, 69673);
    CHECK(arcturus && fabs(arcturus->pm_dec + 2000.0) < 5.0, "Arcturus carries its proper motion");
    NOTE("stars: %d star-instants, max error %.5f deg (HIP %d)", compared, worst, worst_hip);
    CHECK(worst <= 0.005, "star apparent alt/az max error %.5f deg > 0.005 (HIP %d)", worst, worst_hip);
    sky_catalog_free(&cat);
}

TEST(astro_phase_and_eclipse_vs_erfa)
{
    draw d[DRAWS];
    make_draws(d, DRAWS);
    double worst_k = 0.0, worst_u = 0.0, worst_p = 0.0;
    for (int i = 0; i < DRAWS; i++) {
        sky_astro a;
        sky_astro_observer obs = {0.0, 0.0, 0.0};
        sky_astro_compute(d[i].jd, &obs, &a, NULL, 0);
        oracle o;
        oracle_init(&o, d[i].jd, a.delta_t, 0.0, 0.0, 0.0);
        double sun[3], moon[3];
        oracle_sun(&o, sun);
        oracle_moon(&o, moon);
        /* phase angle at the moon between the sun and the Earth */
        double to_sun[3], to_earth[3];
        for (int k = 0; k < 3; k++) to_sun[k] = sun[k] - moon[k], to_earth[k] = -moon[k];
        double cos_i = eraPdp(to_sun, to_earth) / (eraPm(to_sun) * eraPm(to_earth));
        double k_erfa = (1.0 + cos_i) / 2.0;
        worst_k = fmax(worst_k, fabs(k_erfa - a.moon_illuminated));
        /* the same shadow rule on ERFA's positions */
        double rs = eraPm(sun), rm = eraPm(moon);
        double pi_m = asin(6378.137 / rm) * 0.998340, pi_s = asin(6378.137 / rs), s_s = atan(696000.0 / rs);
        double s_m = asin(1737.4 / rm);
        double anti[3] = {-sun[0], -sun[1], -sun[2]};
        double dist = eraSepp(anti, moon);
        double u = (1.01 * pi_m + pi_s - s_s + s_m - dist) / (2 * s_m);
        double p = (1.01 * pi_m + pi_s + s_s + s_m - dist) / (2 * s_m);
        worst_u = fmax(worst_u, fabs(u - a.umbral_magnitude));
        worst_p = fmax(worst_p, fabs(p - a.penumbral_magnitude));
    }
    NOTE("illuminated fraction max error %.5f; umbral magnitude %.5f, penumbral %.5f", worst_k, worst_u, worst_p);
    CHECK(worst_k <= 0.002, "illuminated fraction error %.5f > 0.002", worst_k);
    CHECK(worst_u <= 0.01, "umbral magnitude error %.5f > 0.01", worst_u);
    CHECK(worst_p <= 0.01, "penumbral magnitude error %.5f > 0.01", worst_p);
}

TEST(astro_historic_lunar_eclipses)
{
    /* Greatest eclipse (TD) and magnitudes published in F. Espenak's
     * NASA eclipse catalogue; instants converted to UT with our Delta T.
     * NAN: a published value not at hand here, so not asserted. */
    struct {
        const char *name;
        int y, m, d, hh, mm, ss;
        double umbral, penumbral;
    } ecl[] = {
        {"total 2010-12-21", 2010, 12, 21, 8, 17, 46, 1.2561, NAN},
        {"total 2011-06-15", 2011, 6, 15, 20, 12, 37, 1.6998, 2.6868},
        {"partial 2019-07-16", 2019, 7, 16, 21, 30, 44, 0.6531, NAN},
        {"penumbral 2020-01-10", 2020, 1, 10, 19, 11, 11, -0.1146, 0.8956},
    };
    for (size_t i = 0; i < sizeof ecl / sizeof ecl[0]; i++) {
        double jd_td = sky_jd_from_calendar(ecl[i].y, ecl[i].m, ecl[i].d, ecl[i].hh, ecl[i].mm, ecl[i].ss);
        double jd_ut = jd_td - sky_delta_t(jd_td) / 86400.0;
        sky_astro a;
        sky_astro_observer obs = {0.0, 0.0, 0.0};
        sky_astro_compute(jd_ut, &obs, &a, NULL, 0);
        NOTE("%s: umbral %.4f (published %.4f), penumbral %.4f (%.4f)", ecl[i].name, a.umbral_magnitude,
             ecl[i].umbral, a.penumbral_magnitude, ecl[i].penumbral);
        CHECK(fabs(a.umbral_magnitude - ecl[i].umbral) < 0.01, "%s umbral magnitude", ecl[i].name);
        if (!isnan(ecl[i].penumbral))
            CHECK(fabs(a.penumbral_magnitude - ecl[i].penumbral) < 0.01, "%s penumbral magnitude", ecl[i].name);
    }
}

/* ---- solar eclipses ------------------------------------------------------------ */

static sky_astro solar_at(double jd, double lat_deg, double lon_deg)
{
    sky_astro a;
    sky_astro_observer obs = {lat_deg * DEG, lon_deg * DEG, 0.0};
    if (sky_astro_compute(jd, &obs, &a, NULL, 0)) memset(&a, 0, sizeof a);
    return a;
}

TEST(astro_solar_eclipse_totality)
{
    /* Points on the central lines near greatest eclipse (NASA / Espenak's
     * local circumstances): 2017-08-21 near Hopkinsville, Kentucky, greatest
     * at 18:25:32 UT, moon/sun diameter ratio 1.0306; 2024-04-08 near
     * Nazas, Durango, greatest at 18:17:20 UT, ratio 1.0566. The paths are
     * 115 and 198 km wide, so a few km of error in the point stays inside. */
    static const struct {
        const char *name;
        int y, mo, d, h, mi, s;
        double lat, lon, ratio;
    } cases[] = {{"2017-08-21 Hopkinsville", 2017, 8, 21, 18, 25, 32, 36.9664, -87.6709, 1.0306},
                 {"2024-04-08 Nazas", 2024, 4, 8, 18, 17, 20, 25.2900, -104.1383, 1.0566}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        double jd0 = sky_jd_from_calendar(cases[c].y, cases[c].mo, cases[c].d, cases[c].h, cases[c].mi, cases[c].s);
        /* the instant of greatest eclipse there: the least separation
         * within 5 minutes, to the second */
        double best_jd = jd0, best_sep = 1e9;
        for (int k = -300; k <= 300; k++) {
            double jd = jd0 + k / 86400.0;
            sky_astro a = solar_at(jd, cases[c].lat, cases[c].lon);
            if (a.sun_moon_separation < best_sep) best_sep = a.sun_moon_separation, best_jd = jd;
        }
        sky_astro a = solar_at(best_jd, cases[c].lat, cases[c].lon);
        double ratio = a.moon_topo_semidiameter / a.sun_topo_semidiameter;
        NOTE("%s: greatest %+.0f s from the published instant, separation %.1f arcsec, obscuration %.6f, magnitude "
             "%.4f, diameter ratio %.4f (published %.4f), light left %.2e",
             cases[c].name, (best_jd - jd0) * 86400.0, best_sep / DEG * 3600.0, a.solar_obscuration, a.solar_magnitude,
             ratio, cases[c].ratio, a.solar_flux_fraction);
        CHECK(a.solar_obscuration >= 0.999, "%s: obscuration %.6f < 0.999 at totality", cases[c].name,
              a.solar_obscuration);
        CHECK(a.solar_flux_fraction <= 1e-3, "%s: %.3g of the sun's light left at totality", cases[c].name,
              a.solar_flux_fraction);
        CHECK(fabs(ratio - cases[c].ratio) < 0.003, "%s: diameter ratio %.4f, published %.4f", cases[c].name, ratio,
              cases[c].ratio);
        CHECK(fabs(best_jd - jd0) * 86400.0 < 60.0, "%s: greatest eclipse %.0f s from the published instant",
              cases[c].name, (best_jd - jd0) * 86400.0);
        /* an hour later: the moon has moved off (about its own diameter
         * an hour) */
        sky_astro later = solar_at(best_jd + 1.0 / 24.0, cases[c].lat, cases[c].lon);
        CHECK(later.solar_obscuration < 0.5 && later.solar_flux_fraction > 0.5,
              "%s: an hour later obscuration %.3f, light %.3f", cases[c].name, later.solar_obscuration,
              later.solar_flux_fraction);
    }
    /* the limb-darkened light behind a central disc of radius k R has a
     * closed form: with m0 = sqrt(1 - k^2), hidden / total =
     * [(1 - u)(1 - m0^2) + 2u/3 (1 - m0^3)] / (1 - u/3) */
    const double u = SKY_SUN_LIMB_DARKENING;
    double worst = 0.0;
    for (double k = 0.1; k < 0.99; k += 0.1) {
        double obsc, mag, flux, m0 = sqrt(1.0 - k * k);
        sky_solar_eclipse(1.0, k, 0.0, &obsc, &mag, &flux);
        double hidden = ((1.0 - u) * (1.0 - m0 * m0) + 2.0 * u / 3.0 * (1.0 - m0 * m0 * m0)) / (1.0 - u / 3.0);
        worst = fmax(worst, fabs((1.0 - flux) - hidden));
        CHECK(fabs(obsc - k * k) < 1e-12, "central disc of radius %.1f covers %.6f of the area", k, obsc);
    }
    NOTE("annular, central: limb-darkened light hidden within %.1e of the closed form", worst);
    CHECK(worst < 1e-3, "limb-darkened light hidden by a central disc off by %.2e", worst);
    /* off-centre discs against a brute-force sum over a grid on the disc */
    static const double geometry[][2] = {{0.5, 0.3}, {1.03, 0.2}, {0.95, 1.2}, {0.3, 0.9}, {2.0, 2.5}, {1.0, 1.0}};
    double worst_grid = 0.0;
    for (size_t g = 0; g < sizeof geometry / sizeof geometry[0]; g++) {
        double rm = geometry[g][0], dd = geometry[g][1], total = 0.0, behind = 0.0, flux;
        const int n = 1200;
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double x = (i + 0.5) / n * 2.0 - 1.0, y = (j + 0.5) / n * 2.0 - 1.0, r2 = x * x + y * y;
                if (r2 >= 1.0) continue;
                double w = 1.0 - u * (1.0 - sqrt(1.0 - r2));
                total += w;
                if ((x - dd) * (x - dd) + y * y < rm * rm) behind += w;
            }
        sky_solar_eclipse(1.0, rm, dd, NULL, NULL, &flux);
        worst_grid = fmax(worst_grid, fabs((1.0 - flux) - behind / total));
    }
    NOTE("off-centre discs: limb-darkened light hidden within %.1e of a 1200^2 grid sum", worst_grid);
    CHECK(worst_grid < 1e-3, "limb-darkened light hidden off by %.2e against the grid", worst_grid);
    /* a disc covering the limb hides less light than area (the limb is
     * dark), one covering the centre more */
    double o1, f1, o2, f2;
    sky_solar_eclipse(1.0, 0.3, 0.9, &o1, NULL, &f1);
    sky_solar_eclipse(1.0, 0.3, 0.0, &o2, NULL, &f2);
    CHECK(1.0 - f1 < o1 && 1.0 - f2 > o2, "limb darkening: limb %.4f light vs %.4f area; centre %.4f vs %.4f",
          1.0 - f1, o1, 1.0 - f2, o2);
    /* degenerate and bad input: finite, in range */
    double bad[][3] = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {NAN, 1.0, 0.5}, {1.0, INFINITY, 0.1},
                       {1.0, 1.0, NAN}, {1.0, 1.0, -1.0}, {1e-9, 1.0, 1e-9}};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        double obsc, mag, flux;
        sky_solar_eclipse(bad[i][0], bad[i][1], bad[i][2], &obsc, &mag, &flux);
        CHECK(isfinite(obsc) && isfinite(mag) && isfinite(flux) && obsc >= 0.0 && obsc <= 1.0 && flux >= 0.0 &&
                  flux <= 1.0,
              "sky_solar_eclipse(%g, %g, %g) -> %g %g %g", bad[i][0], bad[i][1], bad[i][2], obsc, mag, flux);
        /* no moon, or a value that is not a number: no eclipse */
        int none = !(bad[i][1] > 0.0) || !isfinite(bad[i][0]) || !isfinite(bad[i][1]) || !isfinite(bad[i][2]);
        if (none)
            CHECK(obsc == 0.0 && mag == 0.0 && flux == 1.0, "sky_solar_eclipse(%g, %g, %g) -> %g %g %g, not none",
                  bad[i][0], bad[i][1], bad[i][2], obsc, mag, flux);
    }
}

/* The fraction of the sun's disc behind the moon from ERFA's topocentric
 * vectors, counted on a grid over the sun's disc in its tangent plane:
 * no lens formula shared with the library. */
static double oracle_obscuration(double jd_ut, double delta_t, double lat, double lon)
{
    oracle o;
    oracle_init(&o, jd_ut, delta_t, lat, lon, 0.0);
    double sun_g[3], moon_g[3], sun[3], moon[3];
    oracle_sun(&o, sun_g);
    oracle_moon(&o, moon_g);
    eraRxp(o.rc2t, sun_g, sun);
    eraRxp(o.rc2t, moon_g, moon);
    for (int i = 0; i < 3; i++) sun[i] -= o.obs_itrs_km[i], moon[i] -= o.obs_itrs_km[i];
    double ds = eraPm(sun), dm = eraPm(moon);
    double rs = atan(696000.0 / ds), rm = asin(1737.4 / dm);
    /* tangent-plane coordinates of the moon's centre around the sun's */
    double s[3], m[3], e1[3], e2[3];
    for (int i = 0; i < 3; i++) s[i] = sun[i] / ds, m[i] = moon[i] / dm;
    double a[3] = {0.0, 0.0, 1.0};
    eraPxp(a, s, e1);
    double n1 = eraPm(e1);
    for (int i = 0; i < 3; i++) e1[i] /= n1;
    eraPxp(s, e1, e2);
    double sm = eraPdp(s, m);
    double mx = tan(atan2(eraPdp(m, e1), sm)), my = tan(atan2(eraPdp(m, e2), sm));
    double tr_s = tan(rs), tr_m = tan(rm);
    const int n = 800;
    long inside = 0, covered = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double x = ((i + 0.5) / n * 2.0 - 1.0) * tr_s, y = ((j + 0.5) / n * 2.0 - 1.0) * tr_s;
            if (x * x + y * y > tr_s * tr_s) continue;
            inside++;
            if ((x - mx) * (x - mx) + (y - my) * (y - my) < tr_m * tr_m) covered++;
        }
    return (double)covered / (double)inside;
}

TEST(astro_solar_eclipse_partial_vs_erfa)
{
    /* partial phases of the 2024-04-08 eclipse from New York and of the
     * 2017-08-21 eclipse from Los Angeles, every 10 minutes from first to
     * last contact (and a little beyond) */
    static const struct {
        const char *name;
        int y, mo, d, h0, h1;
        double lat, lon;
    } places[] = {{"2024-04-08 New York", 2024, 4, 8, 18, 21, 40.7128, -74.0060},
                  {"2017-08-21 Los Angeles", 2017, 8, 21, 16, 19, 34.0522, -118.2437}};
    double worst = 0.0, peak = 0.0;
    int partial = 0;
    for (size_t p = 0; p < sizeof places / sizeof places[0]; p++)
        for (int minutes = places[p].h0 * 60; minutes <= places[p].h1 * 60; minutes += 10) {
            double jd = sky_jd_from_calendar(places[p].y, places[p].mo, places[p].d, minutes / 60, minutes % 60, 0.0);
            sky_astro a = solar_at(jd, places[p].lat, places[p].lon);
            double ref = oracle_obscuration(jd, a.delta_t, places[p].lat * DEG, places[p].lon * DEG);
            double e = fabs(a.solar_obscuration - ref);
            if (ref > 0.0 && ref < 1.0) partial++;
            if (e > worst) worst = e;
            if (ref > peak) peak = ref;
            CHECK(e <= 0.01, "%s %02d:%02d UT: obscuration %.4f, ERFA %.4f", places[p].name, minutes / 60,
                  minutes % 60, a.solar_obscuration, ref);
        }
    NOTE("%d partial instants, deepest %.3f: worst obscuration error %.4f against ERFA's positions", partial, peak,
         worst);
    CHECK(partial >= 20, "only %d instants were partial", partial);
}

TEST(astro_refraction)
{
    /* finite, non-negative, continuous; apparent altitude monotonic */
    double prev_app = -1e9, prev_r = sky_refraction(-PI / 2, 1.0), worst_step = 0.0;
    int bad = 0;
    for (int i = 0; i <= 180000; i++) {
        double h = (-90.0 + i * 0.001) * DEG, r = sky_refraction(h, 1.0);
        bad += !isfinite(r) || r < 0.0;
        bad += h + r < prev_app; /* monotonic */
        worst_step = fmax(worst_step, fabs(r - prev_r));
        prev_app = h + r;
        prev_r = r;
    }
    CHECK(bad == 0, "%d refraction values non-finite, negative or non-monotonic", bad);
    CHECK(worst_step < 2.0 * ERFA_DAS2R, "refraction continuous: largest step %.2f arcsec for 0.001 deg",
          worst_step / ERFA_DAS2R);
    /* at the horizon: about 34' (the classical value) */
    double r0 = sky_refraction(0.0, 1.0) / DEG * 60.0;
    CHECK(fabs(r0 - 28.9) < 6.0, "horizontal refraction %.1f arcmin", r0);
    /* above 15 degrees, against ERFA's A tan z + B tan^3 z model at
     * 1010 hPa, 10 C, 50 % humidity, 0.55 um */
    double refa, refb, worst = 0.0;
    eraRefco(1010.0, 10.0, 0.5, 0.55, &refa, &refb);
    for (double hd = 15.0; hd <= 90.0; hd += 0.5) {
        double z = (90.0 - hd) * DEG, tz = tan(z);
        double erfa_r = refa * tz + refb * tz * tz * tz; /* apparent minus true, ~ at the true z */
        worst = fmax(worst, fabs(sky_refraction(hd * DEG, 1.0) - erfa_r));
    }
    NOTE("refraction vs eraRefco above 15 deg: %.2f arcsec", worst / ERFA_DAS2R);
    CHECK(worst < 0.005 * DEG, "refraction above 15 deg within 0.005 deg of ERFA (%.2f arcsec)", worst / ERFA_DAS2R);
    CHECK(sky_refraction(0.0, 0.4) < 0.5 * sky_refraction(0.0, 1.0), "thinner air refracts less");
}

/* The series are evaluated at nodes and interpolated (astro.h): the cache
 * saves work without changing a bit of any result, whatever order the
 * instants come in, and the linear interpolation stays within its stated
 * 0.05" of the series (judged against a cubic through four nodes, whose
 * own error at the midpoint, 3/128 h^4 f'''', is far smaller). */
TEST(astro_node_cache)
{
    const double h = 1.0 / SKY_ASTRO_NODES_PER_DAY;
    sky_astro_observer obs = {0.7, -1.2, 300.0};
    sky_astro_cache cache = {0};
    unsigned rng = 12345u;
    int differ = 0, n = 0;
    for (int i = 0; i < 400; i++) {
        rng = rng * 1664525u + 1013904223u;
        double r = (double)(rng >> 8) / 16777216.0;
        /* runs of a moving clock, the equation of time apart, and jumps */
        double jd = i % 3 == 0 ? 2451545.0 + (r - 0.5) * 730000.0 : 2460000.0 + i * 0.0007 + (i % 3 == 2) * 0.011;
        sky_astro with, without;
        if (sky_astro_compute_cached(jd, 64.0, &obs, &cache, &with, NULL, 0) ||
            sky_astro_compute_dt(jd, 64.0, &obs, &without, NULL, 0)) {
            CHECK(0, "astro failed at JD %f", jd);
            return;
        }
        differ += memcmp(&with, &without, sizeof with) != 0;
        n++;
    }
    CHECK(differ == 0, "%d of %d instants differ with the cache", differ, n);

    double worst_moon = 0.0, worst_sun = 0.0;
    for (int i = 0; i < 200; i++) {
        double node0 = floor((2451545.0 + i * 37.3) / h) * h - 64.0 / 86400.0; /* UT of a node in TT */
        sky_astro a[4], mid;
        for (int k = 0; k < 4; k++) sky_astro_compute_dt(node0 + k * h, 64.0, &obs, &a[k], NULL, 0);
        sky_astro_compute_dt(node0 + 1.5 * h, 64.0, &obs, &mid, NULL, 0);
        for (int body = 0; body < 2; body++) {
            double ra[4], dec[4];
            for (int k = 0; k < 4; k++) {
                const sky_astro_body *b = body ? &a[k].moon : &a[k].sun;
                ra[k] = a[0].moon.ra + remainder(b->ra - a[0].moon.ra, 2 * PI);
                dec[k] = b->dec;
            }
            const sky_astro_body *m = body ? &mid.moon : &mid.sun;
            double ra_cubic = (-ra[0] + 9 * ra[1] + 9 * ra[2] - ra[3]) / 16.0;
            double dec_cubic = (-dec[0] + 9 * dec[1] + 9 * dec[2] - dec[3]) / 16.0;
            double dra = remainder(m->ra - ra_cubic, 2 * PI) * cos(m->dec), ddec = m->dec - dec_cubic;
            double e = sqrt(dra * dra + ddec * ddec) / ERFA_DAS2R;
            if (body)
                worst_moon = fmax(worst_moon, e);
            else
                worst_sun = fmax(worst_sun, e);
        }
    }
    NOTE("interpolation between nodes: moon %.4f arcsec, sun %.5f arcsec", worst_moon, worst_sun);
    CHECK(worst_moon < 0.05 && worst_sun < 0.002, "interpolated places within 0.05\" (moon %.4f, sun %.5f)",
          worst_moon, worst_sun);
}

TEST(astro_bad_input)
{
    sky_astro a;
    char err[256];
    sky_astro_observer ok = {0.5, 0.5, 0.0}, pole = {PI / 2, 3.0, 0.0}, bad_lat = {1.6, 0.0, 0.0},
                       nan_lat = {NAN, 0.0, 0.0};
    CHECK(sky_astro_compute(sky_jd_from_calendar(-2500, 1, 1, 0, 0, 0), &ok, &a, err, sizeof err) < 0 &&
              strstr(err, "outside"),
          "year -2500 rejected: %s", err);
    CHECK(sky_astro_compute(sky_jd_from_calendar(3100, 1, 1, 0, 0, 0), &ok, &a, err, sizeof err) < 0, "year 3100");
    CHECK(sky_astro_compute(NAN, &ok, &a, err, sizeof err) < 0, "NaN date");
    CHECK(sky_astro_compute(2451545.0, &bad_lat, &a, err, sizeof err) < 0 && strstr(err, "latitude"), "|lat| > 90");
    CHECK(sky_astro_compute(2451545.0, &nan_lat, &a, err, sizeof err) < 0, "NaN latitude");
    /* the supported edges compute finite results, poles included */
    double edges[2] = {sky_jd_from_calendar(-1999, 1, 1, 0, 0, 0), sky_jd_from_calendar(3000, 12, 31, 0, 0, 0)};
    for (int i = 0; i < 2; i++) {
        CHECK(sky_astro_compute(edges[i], &pole, &a, err, sizeof err) == 0, "edge date %d: %s", i, err);
        double v[] = {a.sun.alt, a.sun.az, a.moon.alt, a.moon.az, a.moon_illuminated, a.umbral_magnitude,
                      a.moon_libration_lat, a.moon_axis_angle, a.moon_parallactic, a.star_visibility};
        for (size_t k = 0; k < sizeof v / sizeof v[0]; k++) CHECK(isfinite(v[k]), "edge %d value %zu finite", i, k);
    }
    /* public API */
    sky_observer o = {2451545.0, 91.0, 0.0, 0.0, 0};
    sky_astronomy out;
    CHECK(sky_compute_astronomy(&o, 0.5f, NULL, 0, NULL, &out, err, sizeof err) == SKY_ERR_INVALID_ARGUMENT &&
              strstr(err, "latitude"),
          "API rejects latitude 91: %s", err);
    o.latitude_deg = 10.0;
    o.longitude_deg = 181.0;
    CHECK(sky_compute_astronomy(&o, 0.5f, NULL, 0, NULL, &out, err, sizeof err) == SKY_ERR_INVALID_ARGUMENT,
          "API rejects longitude 181");
    o.longitude_deg = 0.0;
    o.julian_day_utc = INFINITY;
    CHECK(sky_compute_astronomy(&o, 0.5f, NULL, 0, NULL, &out, err, sizeof err) == SKY_ERR_INVALID_ARGUMENT,
          "API rejects an infinite date");
    CHECK(sky_compute_astronomy(NULL, 0.5f, NULL, 0, NULL, &out, err, sizeof err) == SKY_ERR_INVALID_ARGUMENT,
          "NULL observer");
    /* a sky keeps its observer when a bad one is offered */
    fixture f;
    if (fixture_open(&f, SKY_GL_AUTO, NULL) == 0) {
        sky_observer before, after, bad = {2451545.0, 0.0, 0.0, -1000.0, 1};
        sky_get_observer(f.s, &before);
        CHECK(sky_set_observer(f.s, &bad) == SKY_ERR_INVALID_ARGUMENT && strstr(sky_last_error(f.s), "altitude"),
              "sky_set_observer rejects 1 km below sea level: %s", sky_last_error(f.s));
        sky_get_observer(f.s, &after);
        CHECK(!memcmp(&before, &after, sizeof before), "a rejected observer changes nothing");
        fixture_close(&f);
    }
    /* command line: exit 2 naming the option */
    char path[512], cmd[1024], outbuf[2048];
    bin_path("sky-render", path, sizeof path);
    const char *args[] = {"--query --date 2011-13-01T00:00:00Z", "--query --date 2011-02-29T00:00:00Z",
                          "--query --date -2500-01-01T00:00:00Z", "--query --date 3001-06-01T00:00:00Z",
                          "--query --lat 91", "--query --lon -181", "--query --alt nan", "--query --hip 1,x",
                          "--hip 5"};
    const char *names[] = {"--date", "--date", "--date", "--date", "--lat", "--lon", "--alt", "--hip", "--hip"};
    for (size_t i = 0; i < sizeof args / sizeof args[0]; i++) {
        snprintf(cmd, sizeof cmd, "%s %s 2>&1 >/dev/null", path, args[i]);
        int rc = run_command(cmd, outbuf, sizeof outbuf);
        CHECK(rc == 2 && strstr(outbuf, names[i]), "'%s' exits 2 naming %s (%d: %s)", args[i], names[i], rc, outbuf);
    }
}

TEST(astro_time_slider_is_solar_time)
{
    /* time 0.5 puts the sun on the meridian (azimuth 180 or 0), whatever
     * the date and longitude; 0.25 and 0.75 put it east and west */
    const double lons[4] = {-150.0, -20.0, 70.0, 179.0};
    const int months[4] = {2, 5, 8, 11};
    double worst = 0.0;
    for (int i = 0; i < 4; i++) {
        sky_observer o = {sky_julian_day(2024, months[i], 10, 3, 0, 0.0), 35.0, lons[i], 0.0, 1};
        sky_astronomy a;
        sky_compute_astronomy(&o, 0.5f, NULL, 0, NULL, &a, NULL, 0);
        worst = fmax(worst, fabs(remainder(a.sun.az_deg - 180.0, 360.0)));
        sky_compute_astronomy(&o, 0.3f, NULL, 0, NULL, &a, NULL, 0);
        CHECK(a.sun.az_deg > 45.0 && a.sun.az_deg < 135.0, "morning sun in the east (%g)", a.sun.az_deg);
        sky_compute_astronomy(&o, 0.7f, NULL, 0, NULL, &a, NULL, 0);
        CHECK(a.sun.az_deg > 225.0 && a.sun.az_deg < 315.0, "evening sun in the west (%g)", a.sun.az_deg);
    }
    NOTE("time 0.5: sun %.4f deg from the meridian at worst", worst);
    CHECK(worst < 0.05, "solar noon on the meridian (%.4f deg off)", worst);
}

TEST(astro_query_json)
{
    char path[512], cmd[1024], out[8192];
    bin_path("sky-render", path, sizeof path);
    snprintf(cmd, sizeof cmd, "%s --query --date 2011-06-15T20:11:31Z --lat -30 --lon 20 --alt 1500 --hip 32349,7",
             path);
    int rc = run_command(cmd, out, sizeof out);
    CHECK(rc == 0, "--query exits 0 (%d)", rc);
    static const char *keys[] = {"\"jd_ut\":", "\"delta_t_s\":", "\"lmst_deg\":", "\"sun\": {\"alt\":",
                                 "\"alt_geometric\":", "\"distance_au\":", "\"moon\": {", "\"distance_km\":",
                                 "\"illuminated_fraction\":", "\"phase_angle\":", "\"bright_limb_angle\":",
                                 "\"libration_lat\":", "\"libration_lon\":", "\"parallactic_angle\":",
                                 "\"eclipse\": {\"umbral_magnitude\":", "\"penumbral_magnitude\":",
                                 "\"stars\": [{\"hip\":32349", "\"vmag\":-1.44", "\"star_visibility\":",
                                 "\"moon_visibility\":", "\"planets\": [{\"name\":\"mercury\", \"alt\":",
                                 "{\"name\":\"venus\"", "{\"name\":\"mars\"", "{\"name\":\"jupiter\"",
                                 "{\"name\":\"saturn\"", "\"diameter_arcsec\":"};
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) CHECK(strstr(out, keys[i]) != NULL, "%s in %s", keys[i], out);
    /* the instant as given: no --time, so JD is exactly the date's */
    double jd = 0.0;
    const char *p = strstr(out, "\"jd_ut\":");
    if (p) jd = atof(p + 8);
    CHECK(fabs(jd - sky_julian_day(2011, 6, 15, 20, 11, 31.0)) < 1e-7, "--date without --time is the instant (%f)", jd);
    double umbral = 0.0;
    p = strstr(out, "\"umbral_magnitude\":");
    if (p) umbral = atof(p + 19);
    CHECK(umbral > 1.6 && umbral < 1.8, "the 2011-06-15 eclipse is total (%g)", umbral);
    /* the planets as sky_compute_astronomy gives them */
    sky_observer o = {sky_julian_day(2011, 6, 15, 20, 11, 31.0), -30.0, 20.0, 1500.0, 0};
    sky_astronomy a;
    CHECK(sky_compute_astronomy(&o, 0.0f, NULL, 0, NULL, &a, NULL, 0) == SKY_OK, "sky_compute_astronomy");
    for (int i = 0; i < SKY_PLANET_COUNT; i++) {
        char key[64];
        snprintf(key, sizeof key, "{\"name\":\"%s\", \"alt\":", sky_planet_name((sky_planet)i));
        p = strstr(out, key);
        double alt = p ? atof(p + strlen(key)) : 1e9;
        const char *vm = p ? strstr(p, "\"vmag\":") : NULL;
        double vmag = vm ? atof(vm + 7) : 1e9;
        CHECK(fabs(alt - a.planets[i].place.alt_deg) < 1e-5 && fabs(vmag - a.planets[i].vmag) < 1e-3,
              "%s: --query alt %g vmag %g, the API %g %g", sky_planet_name((sky_planet)i), alt, vmag,
              a.planets[i].place.alt_deg, a.planets[i].vmag);
    }
}
